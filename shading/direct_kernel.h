// Direct light, sky and tone map per pixel, one copy per ISA (shading/direct_kernel.cpp).
#pragma once

#include <cstddef>

#include "core/dispatch.h"
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
    float lightViewProj[16];  // column-major
    float biasConst, biasSlope;  // depth-key units; slope term scales tan(angle to light)
    int pcfRadius;
    float exposure;
    // Outputs (outStride): color RGB (linear), display RGB (tone mapped, sRGB), shadow.
    float* out[7];
    std::size_t outStride;
};

SSRT_DECLARE_KERNEL(void, shadeTile, (const DirectArgs& args, int tile))

}  // namespace ssrt
