// The direct pass's lighting set-up (sun, sky, prefiltered sky levels, SH irradiance,
// emission table, shadow map) as DirectArgs, in one place: the renderer's direct pass and the
// reference image (truth/) shade with the same arguments.
#pragma once

#include <memory>
#include <vector>

#include "raster/shadow_map.h"
#include "renderer/frame.h"
#include "renderer/settings.h"
#include "renderer/sky_lighting.h"
#include "scenes/scene.h"
#include "shading/direct_kernel.h"
#include "shading/shadow_bounds.h"

namespace ssrt {

// Owns what DirectArgs points to; neither copied nor moved, so the pointers stay valid.
// Whether setDirectLighting makes the shadow map's block bounds (DirectArgs::shadowBounds,
// shading/shadow_bounds.h), which let a pixel skip its PCF taps where a block is wholly lit or
// wholly dark. Either way the answers are the same bits; the bounds cost a pass over every
// texel of the map and save taps per pixel shaded, so IfTheyPay makes them only for a frame
// with at least a quarter as many pixels as the map has texels (shadowBoundsPay). Measured
// (callgrind, cornell, a 2048-texel map, one thread, AVX2), a frame without them runs 19 %
// fewer instructions at 160x90, 12 % at 320x180, 4 % at 640x360 and 0.6 % at 1280x720; at
// 1920x1080 they were kept, where they were measured to pay on AVX-512. Always and Never are
// for the tests and the benchmarks.
enum class ShadowBoundsUse { IfTheyPay, Always, Never };
bool shadowBoundsPay(int width, int height, int shadowMapSize);

struct DirectLighting {
    DirectArgs args{};  // lighting and shadow fields set; the rest left zero
    // args as setDirectLighting leaves them, kept while its caller adds the direct pass's own
    // planes to args: the lighting alone (sun, sky, emission table, the shadow map's
    // transform and bounds), for what lights points the frame does not show (SSGI's misses, a
    // world hit: world/hit_light.h). No plane of the frame: its shadow map pointer is null, so
    // a pass that reads the map sets it from its own declared read (renderer/world_stage.cpp).
    DirectArgs light{};
    std::vector<float> emissive;             // args.emissive: 3 per material
    std::shared_ptr<const SkyLighting> sky;  // args.envLevel's pixels (Sky::Kind::Image)
    ShadowBounds shadowBounds;               // args.shadowBounds

    DirectLighting() = default;
    DirectLighting(const DirectLighting&) = delete;
    DirectLighting& operator=(const DirectLighting&) = delete;
};

// Fills out.args' sun, sky (analytic, or the image's levels and irradiance from `sky`, which
// must be cachedSkyLighting(scene.sky.image) for an image sky), emission and shadow-map fields
// from the scene, the render settings and the frame's shadow map (which must outlive `out`;
// its depth bounds are made here, on settings.threads), and the stored energy tables
// (args.energy). Camera, G-buffer, outputs and parts are the
// caller's.
void setDirectLighting(const Scene& scene, const RenderSettings& settings, const ShadowMap& shadow,
                       std::shared_ptr<const SkyLighting> sky, DirectLighting& out,
                       ShadowBoundsUse bounds = ShadowBoundsUse::IfTheyPay);

// Some material emits light (DirectArgs::anyEmissive): else no pass reads emission.
bool anyEmissive(const Scene& scene);

// Points args.g at the G-buffer.
void setDirectGBuffer(const GBuffer& gbuffer, DirectArgs& args);

}  // namespace ssrt
