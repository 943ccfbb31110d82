// The reference image: the frame's lighting model with the screen-space guesses replaced by
// world-space truth traced with Embree, converged with many samples.
//
// What stays as the frame has it: primary visibility (the rasterized G-buffer is exact for
// the camera's rays) and every BRDF and sky term of the direct pass. What changes:
//   direct  sun visibility by an Embree shadow ray per pixel (Visibility::Embree), or the
//           frame's own shadow map (Visibility::ShadowMap: isolates the tracing errors from
//           the shadow map's);
//   ssr     reflected radiance before the BRDF factor, from `spp` rays per pixel drawn with
//           the frame's SSR sampler (trace/ray_gen.h, samples 0..spp-1 of the frame's
//           sequence: the first ones are the rays the screen-space pass marched), traced by
//           Embree to maxDistance. Each ray's radiance L: at a hit, the hit point's own light
//           toward the ray's origin in the direct pass's model (sun with the chosen
//           visibility, sky diffuse and split-sum specular, emission: the direct pass's
//           `color`, without Kulla-Conty); on a miss, the sky along the ray. A back face of a
//           single-sided material is black. Weighted like the reuse resolve: ssr = sum(w L) /
//           sum(w), w = D V n.l / pdf (a pixel none of whose rays weighs keeps envSpecular);
//           opacity 1 (nothing fades).
//   ssgi    the average incoming radiance of `spp` cosine rays (the SSGI definition,
//           trace/ssgi.h): at a hit the Lambert part of the hit's direct light with the chosen
//           visibility plus emission; on a miss the sky along the ray. With `bounces` N > 1
//           each ray is a diffuse path of up to N hits x_1..x_N (Kajiya's path tracing,
//           Lambert only),
//             L = L_1 + r_1 (L_2 + r_2 (... + r_{N-1} L_N)),
//           L_k the hit's light as above (the same sun, visibility and emission at every
//           vertex), r_k = albedo (1 - metallic) occlusion its diffuse reflectance, the next
//           direction cosine-sampled around x_k's shading normal (f_r cos / pdf = r_k), a miss
//           the sky; a direction below x_k's geometric surface, or a back face of a
//           single-sided material, ends the path. N frames of SSGI feedback (ssgiFeedback)
//           estimate the same N bounces. ReferenceSettings::kConverged: the path goes on
//           until its throughput r_1 ... r_k is negligible (all the light, to 0.1 %). Its random
//           numbers: randomFloat(pixel, frame, sample, kReferenceBounceDim + 2 (k - 1)) and the
//           next dimension, at x_k.
// The chosen visibility holds at the hits too, so that ShadowMap differs from the frame only
// by what was traced. Every ray (and shadow ray) leaves its pixel's point stepped
// EmbreeScene::epsilon() off the surface along the geometric normal (Embree's primary hit):
// the G-buffer's point is exact only to float rounding, and grazing rays would hit their own
// surface from behind.
// The composite (shading/composite.h) then puts them together exactly as the frame does, so
// reference and frame differ only where screen space guessed.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>

#include "core/image.h"
#include "renderer/renderer.h"
#include "world/embree_scene.h"
#include "world/hit_light.h"

namespace ssrt {

// The random-number dimensions of the SSGI paths' further bounces (past the ray generators'
// 16..19, trace/ray_gen.h): 2 per vertex.
inline constexpr uint32_t kReferenceBounceDim = 32;

struct ReferenceSettings {
    using Visibility = SunVisibility;  // world/hit_light.h
    Visibility visibility = Visibility::Embree;
    int spp = 64;               // rays per pixel for each of SSR and SSGI
    float maxDistance = 30.0f;  // scene units: the march's (marchLengths().maxDistance);
                                // every bounce's rays too
    int bounces = 1;            // diffuse hits per SSGI path, 1 to kMaxBounces: 1 is the
                                // one-bounce SSGI model, N matches N frames of feedback;
                                // kConverged: all the light (what `ssrt compare` defaults to)
    static constexpr int kMaxBounces = 256;
    // A path of kConverged goes on until its throughput (the product of its reflectances,
    // largest of RGB) is below kNegligibleThroughput, or kMaxBounces hits. What the later
    // hits would add is at most that throughput times the light a path could still gather,
    // about 0.1 % of a pixel's diffuse light; on cornell the converged mean diffuse matches
    // 64 fixed bounces' to 4 digits (tests/truth/reference_bounces_test.cpp).
    static constexpr int kConverged = 0;
    static constexpr float kNegligibleThroughput = 1e-3f;
    // When set and true, renderReference stops at its next tile and throws ReferenceCancelled
    // (a tile is a few milliseconds of rays at any spp): how `ssrt reference` and `ssrt sweep`
    // stop within a second of SIGINT (cli/interrupt.h). Not part of the image or its key.
    const std::atomic<bool>* cancel = nullptr;
    void validate() const;  // throws std::invalid_argument naming the field
};

// What renderReference throws when ReferenceSettings::cancel turned true: no image is given.
struct ReferenceCancelled : std::runtime_error {
    ReferenceCancelled() : std::runtime_error("the reference was cancelled") {}
};

// Planes of the frame's size. Scene-linear (before exposure) except color.
struct ReferenceImage {
    PlaneF color[3];     // composite, exposed (as the frame's "color")
    PlaneF direct[3];    // sun light with the chosen visibility (the direct part)
    PlaneF ssr[3];       // reflected radiance (as the frame's "ssr"), 0 on background
    PlaneF ssgi[3];      // incoming diffuse radiance (as the frame's "ssgi"), 0 on background
    PlaneF specular[3];  // specWeight x ssr: the specular part of color before exposure
    PlaneF diffuse[3];   // albedo (1 - metallic) x ssgi: the diffuse part before exposure
};

// Progress: fraction done in (0, 1], rising, ending at 1; called on the thread that called
// renderReference, after each sample pass, at most about 200 times.
using Progress = std::function<void(double fraction)>;

// Pixel rows [y0, y1) of a frame: a band of the reference, in whole tile rows (y0 a multiple
// of kTileSize, y1 one too or the frame's height), for shards of its work (cli/shard.h).
struct RowBand {
    int y0 = 0, y1 = 0;
};
// Band `index` (from 0) of `count` bands of a frame `height` rows high: tile rows
// [index T / count, (index + 1) T / count) of its T tile rows (empty when count > T).
RowBand referenceBand(int height, int index, int count);

// Renders the reference for `frame` (rendered by `renderer` from `scene` with both trace
// passes on: its G-buffer, direct parts, shadow map and frame index are read). Deterministic for a
// given Embree build: per-pixel sample sequences from the counter-based RNG. With `band`, only
// its rows are traced (the others hold what a pixel without rays gets): each of its pixels
// has the bits the whole frame's reference gives it, so bands assemble into that reference.
// A band that is not whole tile rows (or is empty) is std::invalid_argument.
ReferenceImage renderReference(const EmbreeScene& embree, const Renderer& renderer,
                               const Frame& frame, const ReferenceSettings& settings,
                               const Progress& progress = {},
                               std::optional<RowBand> band = std::nullopt);

// A key over everything the reference depends on: the scene's content (meshes, materials,
// instances, textures, light, sky, cameras), the render settings that shape it (size,
// shadow map, exposure, frame index, SSR sampler) and the reference settings. For caching.
uint64_t referenceKey(const Scene& scene, const Camera& camera, uint32_t frameIndex,
                      const RenderSettings& render, const ReferenceSettings& settings);

// The same parts of a screen-space frame, before exposure, for the per-component error:
// direct = the direct pass's sun part, specular = specWeight x (ssr x opacity + envSpecular x
// (1 - opacity)), diffuse = albedo (1 - metallic) x ssgi (0 on background). A pass that was
// off stands in as the composite has it (SSR off: opacity 0; SSGI off: the sky's diffuse
// part). Throws std::invalid_argument when both were off: the direct pass then hands out no
// parts.
struct FrameParts {
    PlaneF direct[3], specular[3], diffuse[3];
};
FrameParts frameParts(const Frame& frame);

}  // namespace ssrt
