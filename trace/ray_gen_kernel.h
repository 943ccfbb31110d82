// Ray generation per pixel, one copy per ISA (trace/ray_gen_kernel.cpp); the set-up and the
// conventions are in trace/ray_gen.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"

namespace ssrt {

// What the kernel draws: the SsrMethod values, then the diffuse lobe.
enum class RayGenLobe : int {
    Mirror = 0,
    GgxNdf = 1,
    VndfEllipsoid = 2,
    VndfSphericalCaps = 3,
    VndfBounded = 4,
    Diffuse = 5,
};

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
struct RayGenArgs {
    RayGenLobe lobe;
    // Reads viewZ, normal; roughness (specular lobes); albedo, metallic (noDiffuseColour).
    GBufferView g;
    // RayBatch's planes (trace/trace_types.h says what each holds), all with outStride
    float* origin[3];
    float* dir[3];
    float* pdf;
    std::size_t outStride;
    int outX0, outY0;  // the frame pixel of the planes' element (0, 0) (RayBatch::corner)
    bool stream;       // store past the cache (a frame's batch; not a tile's, read next)
    int width, height, tilesX;
    float tanHalfX, tanHalfY;
    // Where in its pixel a ray starts (0.5: the centre). A half-resolution frame's pixel
    // holds its block's chosen pixel, which lies off the block's centre.
    float originX, originY;
    float viewToWorld[9];  // rotation, column-major
    uint32_t frame, sample;
    uint32_t dim;  // first of the two random-number dimensions
    // Specular lobes: pixels whose perceptual roughness is not below this (NaN included)
    // get no ray ("hidden"); +infinity traces every pixel.
    float maxRoughness;
    // Diffuse lobe: pixels whose albedo (1 - metallic) is 0 in every channel get no ray
    // ("hidden": DiffuseCut::NoDiffuseColour).
    bool noDiffuseColour;
    // The checkerboard cut (RayGenCheckerboard): pixels with ((x ^ y ^ frame) & 1) !=
    // checkerPhase get no ray (pdf kPdfLayoutCut where they would have had one).
    bool checkerboard;
    uint32_t checkerPhase;
    float cutPdf;  // kPdfLayoutCut (trace/trace_types.h)
    // The checkerboard thinned (RayGenCheckerboard::sparseFrames): where the last frame's
    // history length at the pixel's previous position (g.motion) is at least sparseMin, a
    // traced pixel that is not its block's pick (sparseBlockPick) gets no ray either. Null: off.
    const float* historyFrames;
    std::size_t historyStride;
    float sparseMin;
};

// Counters of one tile (RayGenStats, as plain numbers).
struct RayGenCounts {
    uint64_t pixels, rays, belowSurface, background, hidden, cut, sparse;
};

SSRT_DECLARE_KERNEL(void, generateRaysTile,
                    (const RayGenArgs& args, int tile, RayGenCounts& counts))

}  // namespace ssrt
