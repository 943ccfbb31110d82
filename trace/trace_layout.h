// Trace layouts (issue 17, item 2): which pixels get rays in a frame. Full traces every
// pixel; the other two trace fewer and leave the rest to a reconstruction
// (trace/reconstruct.h) that fills them from the traced pixels before anything reads the
// planes, and to the denoiser's history, which sees every pixel over a few frames.
//
// - Checkerboard (NRD's CheckerboardMode, SSR and SSGI): pixel (x, y) of frame f gets rays
//   when ((x ^ y ^ f) & 1) == phase; SSR takes phase 0 and SSGI phase 1, so each pixel
//   traces one of the two per frame and every pixel both over two frames. The others keep
//   their place in the full-resolution RayBatch with pdf kPdfLayoutCut: the march packs only
//   pdf > 0, so they cost no march time; RayGenStats::cut counts them.
// - Half (SSGI): one ray-pixel per 2x2 block, the chosen pixel rotating over the block's
//   four positions by frame (halfOffset), traced on a half-resolution frame built from the
//   chosen pixels (buildHalfFrame): its G-buffer, its depth and a Hi-Z pyramid of that
//   depth. The march, the resolve and the hit statistics run at half resolution; the
//   upsample (trace/reconstruct.h) brings them back.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/plane_view.h"
#include "trace/trace_types.h"

namespace ssrt {

enum class TraceLayout { Full, Checkerboard, Half };

// "full", "checkerboard", "half".
std::string_view traceLayoutName(TraceLayout layout);
std::optional<TraceLayout> parseTraceLayout(std::string_view name);

// (A pixel the layout leaves without a ray has pdf kPdfLayoutCut, trace/trace_types.h: the
// mark the reconstruction fills by.)

// The checkerboard phases of the two passes (opposite, as NRD pairs them).
inline constexpr uint32_t kSsrCheckerboardPhase = 0;
inline constexpr uint32_t kSsgiCheckerboardPhase = 1;

// Whether pixel (x, y) gets rays in frame `frame` of a checkerboard of phase `phase`.
constexpr bool checkerboardTraced(int x, int y, uint32_t frame, uint32_t phase) {
    return ((uint32_t(x) ^ uint32_t(y) ^ frame) & 1u) == (phase & 1u);
}

// The thinned checkerboard (TraceSettings::ssrSparseFrames): of a 2x2 block's two pixels
// that the checkerboard traces in frame `frame` (a diagonal pair), the one whose column
// parity is sparseBlockPick(frame) keeps its ray always; the other only where the pixel's
// history is short. Over four frames the pick visits the block's four pixels, so a pixel with
// a long history gets a ray every fourth frame instead of every second, and a cut pixel always
// has a traced pixel among its eight neighbours (its own block's pick).
constexpr uint32_t sparseBlockPick(uint32_t frame) { return (frame >> 1) & 1u; }

// The chosen pixel of each 2x2 block in frame `frame` (Half): the 2x2 Bayer order
// (0,0), (1,1), (1,0), (0,1) by frame & 3, so that two consecutive frames take diagonal
// opposites and four cover the block.
struct PixelOffset {
    int x = 0, y = 0;
};
constexpr PixelOffset halfOffset(uint32_t frame) {
    constexpr PixelOffset kOrder[4] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    return kOrder[frame & 3u];
}

// Where a half frame's pixel lies within it, in half pixels: its block's chosen pixel's
// centre, (offset + 0.5) / 2 on each axis (0.25 or 0.75), not the half pixel's centre. Rays
// start there, on the chosen pixel's own surface; from the centre at that pixel's depth they
// started off a sloped surface, behind it or in front (issue 29: at 640x360 the default
// preset's SSGI agreed with Embree on 27 % of cornell's on-screen hits, 70 % from here).
struct PixelPoint {
    float x, y;
};
constexpr PixelPoint halfPixelPoint(PixelOffset o) {
    return {0.5f * (float(o.x) + 0.5f), 0.5f * (float(o.y) + 0.5f)};
}

// The half-resolution camera: ceil(w / 2) x ceil(h / 2) pixels over the same field of view
// (tanHalf scaled by 2 ceil(w / 2) / w: 1 for an even size; an odd size widens the view by
// half a pixel, so a half pixel sits up to half a full pixel from its block's centre).
TraceCamera halfCamera(const TraceCamera& full);

// What the half-resolution trace reads: the chosen pixel of every 2x2 block (a block at the
// right or bottom edge of an odd size whose chosen pixel is outside takes the nearest one
// inside). The depth is the chosen pixel's own, not a min or max of the block (FidelityFX's
// Hi-Z mip 1, HDRP's checkerboard min/max pick): the ray leaves from that pixel's surface
// point with that pixel's normal, so the half-resolution depth buffer holds the ray's own
// origin (the marchers skip it as their own pixel) and no surface of the block stands in
// front of it to be hit by mistake; the rotation shows every full-resolution depth over four
// frames. (The half frame puts that depth at its own pixel centre, the block's centre, so a
// ray leaves up to half a full pixel beside the chosen pixel in each axis: the price of a
// plain camera for the half frame; the upsample places the result at the chosen pixel.)
struct HalfFrame : PlaneTable<HalfFrame>, GBufferPlanesF {
    // Its G-buffer planes (the rest stay empty): the chosen pixels' viewZ, normal, albedo,
    // metallic.
    static constexpr GBufferPlanes kPlanes = kGViewZ | kGNormal | kGAlbedo | kGMetallic;
    // The guides' planes (HalfFrame::guide).
    static constexpr GBufferPlanes kGuidePlanes = kGViewZ | kGNormal | kGMotion;
    TraceCamera camera;    // halfCamera of the full one
    PixelOffset offset;    // the frame's chosen pixel in each block
    PlaneU16 hitLight[3];  // f16, as the direct pass's (renderer/frame.h, DirectParts)
    PlaneF backZ;  // the chosen pixels' back-face depth (HalfFrameSource::backZ given; empty
                   // otherwise)
    PlaneU32 ids;  // the chosen pixels' visibility ids (HalfFrameSource::ids given; empty
                   // otherwise): mixed tracing's proof of a march hit (trace/hit_proof.h)
    // The guides of a signal denoised on the half frame (HalfFrameSource::guides; empty
    // otherwise): the block's first pixel (offset (0, 0)) every frame, not the rotating chosen
    // one, so that the denoiser's history sees the same surface frame after frame; motion in
    // half pixels (previous minus current).
    GBufferPlanesF guide;

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        // (Named as the renderer's resource table names their channels, renderer/resources.cpp.)
        forEachGBufferChannel("half.gbuffer.", g, kPlanes, fn);
        fn("half.backZ", g.backZ);
        fn("half.ids", g.ids);
        forEachGBufferChannel("half.guide.", g.guide, kGuidePlanes, fn);
        fn("half.hitLight.R", g.hitLight[0]), fn("half.hitLight.G", g.hitLight[1]);
        fn("half.hitLight.B", g.hitLight[2]);
    }
    // Full-resolution surface pixels that are not chosen (RayGenStats::cut).
    uint64_t cutPixels = 0;
    // Its G-buffer (viewZ, normal, albedo, metallic) as the passes read it.
    GBufferView view() const;
};

struct HalfFrameSource {
    GBufferView g;        // the frame's: viewZ, normal, albedo, metallic; motion with `guides`
    bool guides = false;  // make the denoiser's guides (HalfFrame::guide)
    // DirectArgs::hitLight (SSGI's radiance at a hit); all absent: out.hitLight holds the
    // chosen pixels' already, at the half frame's size (DirectArgs::hitLightHalf).
    ViewU16 hitLight[3] = {};  // f16
    // Optional: the back-face depth layer (raster/back_depth.h), which the march reads.
    ViewF backZ{};
    // Optional: the visibility buffer's ids (raster/visibility.h), which mixed tracing's proof
    // reads.
    ViewU32 ids{};
};

// Fills `out` (planes reused when the size matches) for frame `frame`. Throws
// std::invalid_argument on a missing plane or one not of the camera's size.
void buildHalfFrame(const TraceCamera& full, const HalfFrameSource& src, uint32_t frame,
                    HalfFrame& out, int threads);

// The full-resolution pixel that half pixel (hx, hy) of a w x h frame stands for.
constexpr PixelOffset halfSource(int hx, int hy, PixelOffset o, int w, int h) {
    const int x = 2 * hx + o.x, y = 2 * hy + o.y;
    return {x < w ? x : w - 1, y < h ? y : h - 1};
}

}  // namespace ssrt
