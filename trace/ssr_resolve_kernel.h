// The SSR resolve kernels, one copy per ISA (trace/ssr_resolve_kernel.cpp); the method is
// described in trace/ssr_resolve.h. Two passes over tiles: ssrHitTile turns each pixel's own
// march result into a hit radiance and fade (scratch planes), ssrResolveTile combines them
// (own hit for Mip, 3x3 neighbours for Reuse) and accumulates the sample into the output.
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"

namespace ssrt {

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
// Every plane has the frame's size and one stride (`stride`), the pyramid levels and the
// batch's planes aside.
struct SsrResolveArgs {
    int width, height, tilesX;
    std::size_t stride;
    float tanHalfX, tanHalfY;
    float viewToWorld[9];  // rotation, column-major (normals go to view space by its transpose)
    GBufferView g;         // viewZ, roughness; normal (reuse); motion (reproject)
    // Rays and march, read by ssrHitTile: a batch's planes, with their own stride, whose
    // element (0, 0) is the frame's pixel (rayX0, rayY0) (trace/trace_types.h, BatchCorner).
    const float* rayDir[3];  // view space
    const float* pdf;
    const float* hit;
    const float* hitPos[3];  // hitX, hitY (pixels), hitZ (view depth)
    std::size_t rayStride;
    int rayX0, rayY0;
    // The pdf and hit planes of the frame that ssrResolveTile reads around each pixel: the
    // batch's own when it is the frame's; else ssrHitTile copies the tile's there.
    const float* framePdf;
    const float* frameHit;
    float* copyPdf;  // null when the batch is the frame's
    float* copyHit;  // (reuse only)
    // Where hit radiance comes from: `source` at level 0 (Current: colour; Reprojected: the
    // previous frame's colour), read at hit + g.motion when `reproject`.
    const float* source[3];
    bool reproject, bilinear, mip, reuse;
    static constexpr int kMaxLevels = 16;
    int levelCount;  // Mip: pyramid levels (level 0 at the frame's size)
    const float* level[kMaxLevels][3];
    std::size_t levelStride[kMaxLevels];
    int levelWidth[kMaxLevels], levelHeight[kMaxLevels];
    float edgeFadeScale;                         // 1 / edgeFadeLength
    float roughnessFadeEnd, roughnessFadeScale;  // fade = saturate((end - r) * scale)
    float radianceScale;
    // Scratch written by ssrHitTile, read by ssrResolveTile. hitTarget (reuse only): the hit
    // point in view space, or the ray's direction for a miss. The scratch planes (these and
    // frameHit) have `scratchRows` rows: the frame's height, or a ring of tile rows that frame
    // row y maps to at y % scratchRows (the tile chain's, trace/tile_chain.h, which resolves
    // a tile row while the rows around it are still in the ring).
    int scratchRows;
    float* hitRadiance[3];
    float* hitFade;
    float* hitTarget[3];
    // Output, accumulated over samples.
    float* outColor[3];
    float* outOpacity;
    int sample, sampleCount;
};

SSRT_DECLARE_KERNEL(void, ssrHitTile, (const SsrResolveArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, ssrResolveTile, (const SsrResolveArgs& args, int tile))

}  // namespace ssrt
