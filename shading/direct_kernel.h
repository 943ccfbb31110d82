// Direct light, sky and tone map per pixel, one copy per ISA (shading/direct_kernel.cpp).
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "shading/energy_tables.h"
#include "shading/environment.h"

namespace ssrt {

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
struct DirectArgs {
    // G-buffer planes, all with gStride: viewZ, normal XYZ, albedo RGB, metallic,
    // roughness, materialId.
    const float* g[10];
    std::size_t gStride;
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
    // Shadow map: depth key 1 - z01 (larger = nearer the light)
    const float* shadow;
    std::size_t shadowStride;
    int shadowSize;
    float lightViewProj[16];     // column-major
    float biasConst, biasSlope;  // depth-key units; slope term scales tan(angle to light)
    int pcfRadius;
    float exposure;
    // Outputs (outStride): color RGB (linear), display RGB (tone mapped, sRGB), shadow.
    float* out[7];
    std::size_t outStride;
    // Optional parts of `color`, for the composite (shading/composite_kernel.h); each an RGB
    // triple of planes with outStride, null = not written (the outputs above keep their bits
    // either way). Scene-linear: BEFORE the exposure, which the composite applies. Per pixel
    //   color = (((direct + envDiffuse) + specWeight * envSpecular) + emission) * exposure
    // to the bit, in that order (so the composite can rebuild it exactly).
    //   direct:      sun light, Lambert + GGX, shadowed; on background pixels the sky seen
    //                through the pixel (the whole of `color` there, the other parts 0).
    //                Emission is NOT in it (a separate plane, to keep the order above).
    //   emission:    the material's emission (0 where none, and on background).
    //   envDiffuse:  sky irradiance times the diffuse colour albedo (1 - metallic) / pi (the
    //                term SSGI replaces).
    //   envSpecular: the prefiltered sky radiance along the reflection, before the BRDF
    //                factor (the term SSR replaces where it finds a hit).
    //   specWeight:  the split-sum BRDF factor F0 scale + bias (Karis' analytic fit), times
    //                the Kulla-Conty compensation below when `compensation` is set (`color`
    //                never applies it, so with it the sum above no longer holds exactly).
    float* direct[3];
    float* emission[3];
    float* envDiffuse[3];
    float* envSpecular[3];
    float* specWeight[3];
    // Optional too (null = not written): the Lambert part of the sun light leaving each
    // surface pixel, plus its emission where any material emits,
    //   albedo (1 - metallic) / pi  lightRadiance  saturate(n.l)  shadow  (+ emission),
    // the radiance SSGI reads at its hits (trace/ssgi.h), by the function SSGI's G-buffer path
    // uses (shade::lambertSunLight), so reading it gives the same bits; 0 on background.
    float* hitLight[3];
    // Kulla-Conty energy compensation of the specWeight part (null: none, the part is the
    // single-scattering factor above). With the tables, the part is multiplied by
    //   1 + F0 (1 / E(n.v, roughness) - 1)
    // (Fdez-Aguera 2019, "A Multiple-Scattering Microfacet Model for Real-Time Image-based
    // Lighting": the energy single scattering loses, tinted by F0; E is Kulla and Conty's
    // directional albedo, shading/multiscatter.h), so the composite's specular light does not
    // darken as roughness grows. `color` is never compensated (its bits stay as they were).
    const EnergyTables* compensation;
};

SSRT_DECLARE_KERNEL(void, shadeTile, (const DirectArgs& args, int tile))

}  // namespace ssrt
