// Screen-space reflections, the resolve: from each pixel's ray and what the march found to
// the reflected radiance and an opacity, after Unity HDRP's SSR (ScreenSpaceReflections.compute)
// and, for the ray-reuse mode, Stachowiak 2015, "Stochastic Screen-Space Reflections".
//
// Per hit: radiance L_hit, read at (hitX, hitY) from the current frame's lit colour (the
// direct pass's `color`), or from the previous frame's final colour at the reprojected
// position (hit + motion at the hit pixel; a reprojected position off the frame is a miss).
// Its fade f_hit is the edge-of-screen fade (0 on the frame border, 1 from edgeFadeLength of
// the frame inward, linear between: min(u, 1 - u, v, 1 - v) / edgeFadeLength, u = hitX / W,
// v = hitY / H, clamped to [0, 1]); misses and pixels without a ray have f = 0. With
// edgeFadeLength 0 a hit keeps f = 1 wherever it is: the renderer's choice for mixed and world
// tracing, whose hits are certain (a hit near the border is a true hit, and what lies past the
// border went to world space), so fading them would show the environment where the truth
// shows the hit.
//
// Mip mode (approximate, HDRP): the pixel's own hit, its radiance read from a colour
// pyramid (trace/color_pyramid.h) at mip = roughness * maxMip, trilinear;
//   color = L_hit, opacity = f_hit * roughnessFade.
// Reuse mode (Stachowiak 2015): the 3x3 neighbours' rays (the pixel's own included), each
// weighted for THIS pixel by its GGX lobe over the neighbour ray's pdf,
//   w_j = D(h) V(v, l_j) (n.l_j) / pdf_j,
// with l_j the direction from this pixel's point to neighbour j's hit point (or, for a miss,
// neighbour j's own direction: the sky is as far from every pixel); only neighbours with a
// ray (pdf > 0) in the frame. Ratio estimator:
//   color   = sum(w_j f_j L_j) / sum(w_j f_j)
//   opacity = sum(w_j f_j) / sum(w_j) * roughnessFade
// so a uniform hit field returns its colour whatever the weights. (Fresnel is left to the
// composite's split-sum factor, as HDRP does.)
//
// roughnessFade = clamp((roughnessFadeEnd - roughness) / (roughnessFadeEnd - roughnessFadeStart),
// 0, 1) on the pixel's perceptual roughness: 1 below the start, 0 above the end (HDRP's
// smoothness fade, in roughness).
//
// Misses and faded parts are left to the environment: the composite blends
// SSR x opacity + envSpecular x (1 - opacity). Background pixels: colour 0, opacity 0.
// Everything is finite whatever the input (pdf 0 rays, roughness 0 and 1, frame edges).
#pragma once

#include <glm/glm.hpp>
#include <string_view>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/tiles.h"
#include "trace/color_pyramid.h"
#include "trace/ssr_resolve_kernel.h"
#include "trace/trace_types.h"

namespace ssrt {

enum class SsrResolveMode { Mip, Reuse };
enum class HitRadiance { Current, Reprojected };

// "mip", "reuse".
std::string_view resolveModeName(SsrResolveMode mode);
// "current", "reprojected".
std::string_view hitRadianceName(HitRadiance radiance);

struct SsrResolveSettings {
    SsrResolveMode mode = SsrResolveMode::Reuse;
    HitRadiance radiance = HitRadiance::Current;
    bool bilinear = true;             // colour at the hit: bilinear (true) or nearest pixel
    float edgeFadeLength = 0.1f;      // fraction of the frame (per axis) over which hits fade;
                                      // 0: none
    float roughnessFadeStart = 0.5f;  // perceptual roughness where SSR starts to fade out
    float roughnessFadeEnd = 0.7f;    // ... and where it is gone (<= start: a step at end)
};

struct SsrOutput : PlaneTable<SsrOutput> {
    PlaneF color[3];  // reflected radiance where SSR found something (not premultiplied)
    PlaneF opacity;   // how much of it to use, [0, 1]
    // Scratch (per-pixel hit radiance and fade; for the reuse mode also the view-space hit
    // point, or the ray's direction for a miss): of the frame's height, or a ring of tile rows
    // in a tile chain (SsrResolver's scratchRows).
    PlaneF hitRadiance[3], hitFade, hitTarget[3];

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        fn("resolve.R", g.color[0]), fn("resolve.G", g.color[1]), fn("resolve.B", g.color[2]);
        fn("resolve.opacity", g.opacity);
        fn("resolve.hitRadiance.R", g.hitRadiance[0]),
            fn("resolve.hitRadiance.G", g.hitRadiance[1]);
        fn("resolve.hitRadiance.B", g.hitRadiance[2]), fn("resolve.hitRadiance.fade", g.hitFade);
        fn("resolve.hitTarget.X", g.hitTarget[0]), fn("resolve.hitTarget.Y", g.hitTarget[1]);
        fn("resolve.hitTarget.Z", g.hitTarget[2]);
    }
    // color and opacity at width x height; hitRadiance and hitFade (hitTarget only where the
    // reuse mode asks) at width x scratchRows.
    void ensureSize(int width, int height, int scratchRows, bool reuse);
};

// Resolves one sample's rays into `out`; `args` (SsrResolveArgs: the caller's part) names the
// camera and the planes read. sample 0 overwrites, later samples accumulate, and
// after the call with sample == sampleCount - 1 `out` holds the average: opacity the mean
// opacity, color the opacity-weighted mean colour (so that color x opacity is the mean of
// the samples' color x opacity). Throws std::invalid_argument when a plane the settings need
// is missing or of another size, or sample is not in [0, sampleCount).
void resolveSsr(Isa isa, const SsrResolveSettings& settings, const SsrResolveArgs& args,
                const RayBatch& rays, const MarchResult& march, SsrOutput& out, int sample,
                int sampleCount, int threads);

// The same, checked and set up once, then run in its two passes tile by tile: over the frame
// by resolveSsr, or in a trace pass's tile chain (trace/tile_chain.h) with the first pass one
// tile at a time as its `consume` and the second as its `finish`. The second pass reads the pdf
// and hits around each pixel in the frame's batches, `frameRays.pdf` and `frameMarch.hit`: a
// first pass given a tile's batches, which do not outlive their tile, copies the tile's there
// (and only those two planes of the frame's batches need exist).
//
// `scratchRows` is the rows of the scratch planes (the output's hit radiance, fade and target,
// and `frameMarch.hit`): 0 for the frame's height (resolveSsr, resolveFrame), or
// kChainRingTileRows * kTileSize for a tile chain's ring (resolveTile as its finish), whose
// memory does not grow with the frame.
class SsrResolver {
public:
    // resolveSsr's arguments less threads.
    SsrResolver(Isa isa, const SsrResolveSettings& settings, const SsrResolveArgs& args,
                SsrOutput& out, int sample, int sampleCount, RayBatch& frameRays,
                MarchResult& frameMarch, int scratchRows = 0);
    const TileGrid& grid() const { return grid_; }
    // Pass 1 on tile `tile`: the batches are the frame's or the tile's (one corner).
    void hitTile(int tile, const RayBatch& rays, const MarchResult& march) const;
    // After pass 1 on a pixel's tile: its hit answered elsewhere (a world ray lit at the hit),
    // its radiance (before the exposure), fade and view-space hit point in place of pass 1's.
    void setHit(int x, int y, glm::vec3 radiance, float fade, glm::vec3 target) const;
    // Pass 2 on one tile, once pass 1 ran on it and on the tiles around it.
    void resolveTile(int tile) const;
    // Pass 2 on every tile, once pass 1 ran on all of them (scratch of the frame's height).
    void resolveFrame(int threads) const;

private:
    SsrResolveArgs args_{};
    TileGrid grid_;
    const RayBatch* frameRays_;
    const MarchResult* frameMarch_;
    // Where a tile's pdf and hits go for pass 2: the frame's planes' rows (null: not copied).
    float* pdfTarget_ = nullptr;
    float* hitTarget_ = nullptr;
    decltype(&isa_scalar::ssrHitTile) hitKernel_ = nullptr;
    decltype(&isa_scalar::ssrResolveTile) resolveKernel_ = nullptr;
};

}  // namespace ssrt
