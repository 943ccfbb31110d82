// The SSR resolve kernels, one copy per ISA (trace/ssr_resolve_kernel.cpp); the method is
// described in trace/ssr_resolve.h. Two passes over tiles: ssrHitTile turns each pixel's own
// march result into a hit radiance and fade (scratch planes), ssrResolveTile combines them
// (own hit for Mip, 3x3 neighbours for Reuse) and accumulates the sample into the output.
#pragma once

#include <cstddef>

#include "core/camera.h"
#include "core/dispatch.h"
#include "core/gbuffer_view.h"
#include "core/plane_view.h"

namespace ssrt {

struct ColorPyramid;

// The resolve of one sample: the caller sets the camera, the planes it reads (views of the
// camera's size, null where the settings do not need them) and the radiance scale; SsrResolver
// checks them and sets the rest. Plain data only: this crosses into code compiled with other
// ISA flags. Every plane has the frame's size and one stride (`stride`), the pyramid levels
// and the batch's planes aside.
struct SsrResolveArgs {
    // The caller's.
    TraceCamera camera;  // the frame's camera (width, height, tanHalf*, viewToWorld)
    // viewZ (0 = background), roughness; normal (SsrResolveMode::Reuse); motion
    // (HitRadiance::Reprojected: previous pixel position = current + motion)
    GBufferView g;
    ViewF color[3] = {};      // HitRadiance::Current: "color.R/G/B" of the direct pass
    ViewF prevColor[3] = {};  // HitRadiance::Reprojected: last frame's final colour
    const ColorPyramid* pyramid = nullptr;  // SsrResolveMode::Mip: built from `color`
                                            // (Current) or `prevColor` (Reprojected)
    float radianceScale = 1.0f;             // multiplies every radiance read: 1 / exposure
                                            // turns exposed colour planes back into the
                                            // scene-linear units of the composite's inputs
    // Set by the resolver: the camera's size and lens, the planes' one stride.
    int width = 0, height = 0, tilesX = 0;
    std::size_t stride = 0;
    float tanHalfX = 0.0f, tanHalfY = 0.0f;
    float viewToWorld[9] = {};  // rotation, column-major (normals go to view space by its
                                // transpose)
    // Rays and march, read by ssrHitTile (set per tile): a batch's planes, with their own
    // stride, whose element (0, 0) is the frame's pixel (rayX0, rayY0) (trace/trace_types.h,
    // BatchCorner).
    const float* rayDir[3] = {};  // view space
    const float* pdf = nullptr;
    const float* hit = nullptr;
    const float* hitPos[3] = {};  // hitX, hitY (pixels), hitZ (view depth)
    std::size_t rayStride = 0;
    int rayX0 = 0, rayY0 = 0;
    // The pdf and hit planes of the frame that ssrResolveTile reads around each pixel: the
    // batch's own when it is the frame's; else ssrHitTile copies the tile's there.
    const float* framePdf = nullptr;
    const float* frameHit = nullptr;
    float* copyPdf = nullptr;  // null when the batch is the frame's
    float* copyHit = nullptr;  // (reuse only)
    // Where hit radiance comes from: `source` at level 0 (Current: colour; Reprojected: the
    // previous frame's colour), read at hit + g.motion when `reproject`.
    const float* source[3] = {};
    bool reproject = false, bilinear = false, mip = false, reuse = false;
    static constexpr int kMaxLevels = 16;
    int levelCount = 0;  // Mip: pyramid levels (level 0 at the frame's size)
    const float* level[kMaxLevels][3] = {};
    std::size_t levelStride[kMaxLevels] = {};
    int levelWidth[kMaxLevels] = {}, levelHeight[kMaxLevels] = {};
    float edgeFadeScale = 0.0f;                                // 1 / edgeFadeLength; 0: none
    float roughnessFadeEnd = 0.0f, roughnessFadeScale = 0.0f;  // fade = saturate((end - r) * scale)
    // Scratch written by ssrHitTile, read by ssrResolveTile. hitTarget (reuse only): the hit
    // point in view space, or the ray's direction for a miss. The scratch planes (these and
    // frameHit) have `scratchRows` rows: the frame's height, or a ring of tile rows that frame
    // row y maps to at y % scratchRows (the tile chain's, trace/tile_chain.h, which resolves
    // a tile row while the rows around it are still in the ring).
    int scratchRows = 0;
    float* hitRadiance[3] = {};
    float* hitFade = nullptr;
    float* hitTarget[3] = {};
    // Output, accumulated over samples.
    float* outColor[3] = {};
    float* outOpacity = nullptr;
    int sample = 0, sampleCount = 0;
};

SSRT_DECLARE_KERNEL(void, ssrHitTile, (const SsrResolveArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, ssrResolveTile, (const SsrResolveArgs& args, int tile))

}  // namespace ssrt
