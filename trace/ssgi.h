// Screen-space one-bounce diffuse light (SSGI), as in the GAMES202 screen-space ray tracing
// assignment (homework 4): with cosine-weighted rays (pdf = cos / pi) a Lambertian x0 has
//   L_indirect(x0) = 1/N sum_k f_r cos / pdf L(x1_k -> x0) = diffuse(x0) 1/N sum_k L(x1_k -> x0),
// diffuse(x0) = albedo0 (1 - metallic0). resolveSsgi outputs the average incoming radiance
// 1/N sum_k L(x1_k -> x0), WITHOUT x0's diffuse colour (the composite multiplies by it).
//
// At a hit x1 (the pixel containing (hitX, hitY), nearest: G-buffer attributes do not
// interpolate across edges), L is the Lambert part of x1's direct light,
//   L(x1 -> x0) = albedo1 (1 - metallic1) / pi  sunRadiance  max(0, n1.l)  shadow(x1) + emission1,
// its specular part and its own indirect light left out (one bounce of diffuse light, as in
// GAMES202). shadow(x1) is the direct pass's `shadow` plane (PCF visibility, 0 facing away).
// A miss (and a hit that landed on a background pixel) takes the sky's radiance along the
// ray, in world space: the same sky the direct pass shows (gradient, constant or the equirect
// image's level 0), unfiltered; a choice for the ray's own direction rather than the
// prefiltered irradiance, so that N samples converge to the sky's share of the hemisphere
// (which screen space cannot see beyond the frame, GAMES202 returns black there instead).
// A pixel without a ray (pdf 0: background, rejected sample) contributes 0 for that sample.
//
// Multi-bounce feedback (TraceSettings::ssgiFeedback, issue 17): given the previous frame's
// incoming diffuse radiance E' (what this resolve output a frame ago, or what replaced it in
// the composite), a hit also sends on the light it received then,
//   L(x1 -> x0) += albedo1 (1 - metallic1) occlusion1  E'(reproject(x1)),
// reproject(x1) = the centre of x1's pixel + its motion, read at the NEAREST pixel (as the
// hit's G-buffer attributes: a bilinear read would blend the light of two surfaces across a
// depth edge; on a still camera it is the pixel's own estimate, so the series is not
// blurred), nothing where it falls off the frame. With cosine rays the Lambert reflection of
// E' is exactly that (f_r cos / pdf = albedo (1 - metallic)); so each frame adds a bounce and
// a still camera converges to all of them, the path tracer's geometric series
// (truth/reference_image.h, ReferenceSettings::bounces). The direct pass adds it to the
// hitLight planes as it writes them (DirectArgs::prevDiffuse, shading/direct_kernel.h), once
// per frame, per pixel, before the samples: the resolve's gathers at the hits stay 3 (per hit it
// would take 9 more, 4x the resolve's time at 1 ray). E' is not tested for disocclusion: a pixel
// that showed another surface a frame ago lends that surface's light for a frame.
#pragma once

#include <span>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/tiles.h"
#include "shading/direct_kernel.h"
#include "trace/ssgi_kernel.h"
#include "trace/trace_types.h"

namespace ssrt {

// One sample's diffuse rays into out[3] (ensured to the frame's size); `args` (SsgiArgs: the
// caller's part) names the camera, the planes and the lighting: sample 0 overwrites,
// later samples accumulate, and after sample == sampleCount - 1 `out` is the average.
// Throws std::invalid_argument when a plane is missing or of another size, or sample is not
// in [0, sampleCount).
// `lit` (mixed and world tracing): the frame's world hits no pixel shows, in row order, lit
// at the hit; their light replaces what the resolve reads at the hit pixel.
void resolveSsgi(Isa isa, const SsgiArgs& args, const RayBatch& rays, const MarchResult& march,
                 PlaneF out[3], int sample, int sampleCount, int threads,
                 std::span<const WorldLit> lit = {});

// The same, checked and set up once, then run tile by tile: over the frame by resolveSsgi, or
// one tile at a time in a trace pass's tile chain (trace/tile_chain.h), whose batches do not
// outlive their tile: `pdfCopy` (optional) then receives the rays' pdf, which the layouts'
// reconstruction reads after the chain.
class SsgiResolver {
public:
    SsgiResolver(Isa isa, const SsgiArgs& args, PlaneF out[3], int sample, int sampleCount,
                 PlaneF* pdfCopy = nullptr);
    const TileGrid& grid() const { return grid_; }
    // Tile `tile` of the batches: the frame's (corner (0, 0)) or a tile's; one corner. `lit`:
    // the tile's world hits no pixel shows, in row order (std::logic_error otherwise).
    void tile(int tile, const RayBatch& rays, const MarchResult& march,
              std::span<const WorldLit> lit = {}) const;

private:
    SsgiArgs args_{};
    TileGrid grid_;
    decltype(&isa_scalar::ssgiTile) kernel_ = nullptr;
};

}  // namespace ssrt
