// Direct light, sky and tone map per pixel, one copy per ISA (shading/direct_kernel.cpp).
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "core/float_planes.h"
#include "core/gbuffer_view.h"
#include "shading/energy_tables.h"
#include "shading/environment.h"

namespace ssrt {

// The widest shadow PCF kernel, (2 kMaxPcfRadius + 1)^2 taps: the setting's range
// (RenderSettings::pcfRadius) and the taps' per-column arrays (shade::shadowTaps).
inline constexpr int kMaxPcfRadius = 8;

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
struct DirectArgs {
    GBufferView g;  // viewZ, normal, albedo, metallic, roughness, materialId (motion: feedback)
    int width, height, tilesX;
    float tanHalfX, tanHalfY;
    float camPos[3];
    float viewToWorld[9];  // rotation, column-major
    float toLight[3];      // unit, towards the light
    float lightRadiance[3];
    bool skyGradient;
    float skyZenith[3], skyHorizon[3], skyGround[3];  // radiance (intensity folded in)
    // Equirect sky, used instead of the analytic one when envLevelCount > 0: the background
    // reads level 0 (the image), specular light the level pair around roughness *
    // (envLevelCount - 1) (level i prefiltered at roughness i / (envLevelCount - 1)), diffuse
    // light the irradiance polynomial of shading/irradiance_sh.h; all scaled by envIntensity.
    static constexpr int kMaxEnvLevels = 8;
    EquirectView envLevel[kMaxEnvLevels];
    int envLevelCount;
    float envIrradiance[27];  // ShIrradiance::coeffs
    float envIntensity;
    const float* emissive;  // 3 per material id
    bool anyEmissive;       // false: skip the emission lookup
    // Per-pixel emission RGB (g.stride; the texture pass's, with emissive textures), read
    // instead of the per-material table when set (with anyEmissive); null otherwise.
    const float* emissivePlane[3];
    // Per-pixel occlusion (g.stride; occlusion textures), or null (1). Indirect light only:
    // it multiplies envDiffuse and specWeight (so the sky's specular and SSR, which the
    // composite weighs by specWeight) and, in the composite, SSGI; never the sun or the
    // emission (shade::occludeIndirect).
    const float* occlusion;
    // Shadow map: depth key 1 - z01 (larger = nearer the light)
    const float* shadowMap;
    std::size_t shadowStride;
    int shadowSize;
    float lightViewProj[16];     // column-major
    float biasConst, biasSlope;  // depth-key units: shade::shadowMapVisibility's tolerances
    int pcfRadius;               // 0 .. kMaxPcfRadius
    // The map's depth bounds for pcfRadius (ShadowBounds::block as floats,
    // shading/shadow_bounds.h), with shadowBlocks blocks per side; null: every pixel reads its taps
    // (the same answers).
    const float* shadowBounds;
    int shadowBlocks;
    float exposure;
    // Outputs (outStride; renderer/resources.cpp's Res::Color, Display and Shadow say what each
    // holds): colour (linear), display (tone mapped, sRGB) and the sun's shadow. The display may be
    // null (not written, its tone map skipped): with a trace pass the composite writes the display
    // from its own colour.
    float* color[3];
    float* display[3];
    float* shadow;
    std::size_t outStride;
    // Optional parts of `color`, for the composite (shading/composite_kernel.h); each an RGB
    // triple of planes with outStride, f32 or f16 (the renderer's are f16: core/float_planes.h,
    // stored rounded to nearest even, clamped to 65504), null = not written (the outputs above
    // keep their bits either way). Scene-linear: BEFORE the exposure, which the composite
    // applies. Per pixel
    //   color = (((direct + envDiffuse) + specWeight * envSpecular) + emission) * exposure
    // in that order, before the parts are stored (f32 parts rebuild it to the bit; f16 ones
    // to their rounding).
    //   direct:      sun light, Lambert + GGX with Kulla-Conty's multiple-scattering lobe,
    //                shadowed; on background pixels the sky seen through the pixel (the whole
    //                of `color` there, the other parts 0). Emission is NOT in it (a separate
    //                plane, to keep the order above).
    //   emission:    the material's emission (0 where none, and on background).
    //   envDiffuse:  sky irradiance times the diffuse colour albedo (1 - metallic) / pi (the
    //                term SSGI replaces), times the occlusion where there is one.
    //   envSpecular: the prefiltered sky radiance along the reflection, before the BRDF
    //                factor (the term SSR replaces where it finds a hit).
    //   specWeight:  the sky's BRDF factor: the split sum's DFG table, F0 A + F90 B, plus
    //                Kulla-Conty's multiple scattering, T(F_avg, E_avg) (1 - E(n.v)) (the
    //                derivation over shade::shadeSurface, shading/direct_lanes.h), times the
    //                occlusion where there is one. `color` holds the same factor, so the sum
    //                above holds in every pixel.
    SignalOut direct[3];
    SignalOut emission[3];
    SignalOut envDiffuse[3];
    SignalOut envSpecular[3];
    SignalOut specWeight[3];
    // Optional too (null = not written): the Lambert part of the sun light leaving each
    // surface pixel, plus its emission where any material emits,
    //   albedo (1 - metallic) / pi  lightRadiance  saturate(n.l)  shadow  (+ emission),
    // the radiance SSGI reads at its hits (trace/ssgi.h), by the function SSGI's G-buffer path
    // uses (shade::lambertSunLight), so reading it gives the same bits; 0 on background.
    SignalOut hitLight[3];
    // Optional (null = not written): hitLight at half resolution, for SSGI traced on a half
    // frame (trace/trace_layout.h): each half pixel (hx, hy) gets the value of its chosen
    // pixel, halfSource(hx, hy, {halfOffsetX, halfOffsetY}, width, height), as buildHalfFrame
    // would copy it from hitLight, which then need not exist at full resolution. f16, as the
    // frame's hitLight (the same bits as a copy of it).
    uint16_t* hitLightHalf[3];
    std::size_t halfStride;
    int halfOffsetX, halfOffsetY;
    // Multi-bounce diffuse (TraceSettings::ssgiFeedback; null: none): the previous frame's
    // incoming diffuse radiance (f32, the frame's size: outStride), added into hitLight once
    // it is stored, for each surface pixel from the nearest pixel of its reprojected centre
    // (g.motion: previous = current + motion; none off the frame), times its diffuse colour
    // albedo (1 - metallic) and the occlusion where there is one: the light SSGI's hits then
    // reflect. (hitLight is read back as stored and the sum stored again, so f16 planes round
    // twice, as a pass of its own after this one would.)
    const float* prevDiffuse[3];
    // The GGX energy tables (E, E_avg, DFG; shading/energy_tables.h) that shade the
    // specular of every surface pixel, sun and sky: required (setDirectLighting sets the
    // stored ones, energyTables()).
    const EnergyTables* energy;
};

SSRT_DECLARE_KERNEL(void, shadeTile, (const DirectArgs& args, int tile))

}  // namespace ssrt
