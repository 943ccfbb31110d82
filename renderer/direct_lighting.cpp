#include "renderer/direct_lighting.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

namespace ssrt {

bool shadowBoundsPay(int width, int height, int shadowMapSize) {
    return 4.0 * double(width) * double(height) >= double(shadowMapSize) * double(shadowMapSize);
}

void setDirectLighting(const Scene& scene, const RenderSettings& s, const ShadowMap& shadow,
                       std::shared_ptr<const SkyLighting> skyLighting, DirectLighting& out,
                       ShadowBoundsUse bounds) {
    DirectArgs& da = out.args;
    // Sun.
    const glm::vec3 toLight = -glm::normalize(scene.light.direction);
    const glm::vec3 lightRadiance = scene.light.color * scene.light.intensity;
    std::copy_n(glm::value_ptr(toLight), 3, da.toLight);
    std::copy_n(glm::value_ptr(lightRadiance), 3, da.lightRadiance);
    // Sky: analytic colours, or the image's prefiltered levels and irradiance.
    const Sky& sky = scene.sky;
    da.skyGradient = sky.kind == Sky::Kind::Gradient;
    const glm::vec3 zen = sky.zenith * sky.intensity, hor = sky.horizon * sky.intensity,
                    gnd = sky.ground * sky.intensity;
    std::copy_n(glm::value_ptr(zen), 3, da.skyZenith);
    std::copy_n(glm::value_ptr(da.skyGradient ? hor : zen), 3, da.skyHorizon);
    std::copy_n(glm::value_ptr(da.skyGradient ? gnd : zen), 3, da.skyGround);
    out.sky = std::move(skyLighting);
    if (out.sky) {
        static_assert(kSkyLevels <= DirectArgs::kMaxEnvLevels);
        da.envLevelCount = kSkyLevels;
        for (int i = 0; i < kSkyLevels; ++i) da.envLevel[i] = out.sky->level(*sky.image, i);
        std::copy_n(out.sky->irradiance.coeffs, 27, da.envIrradiance);
        da.envIntensity = sky.intensity;
    }
    // Emission per material.
    out.emissive.clear();
    for (const Material& m : scene.materials)
        out.emissive.insert(out.emissive.end(), {m.emissive.r, m.emissive.g, m.emissive.b});
    da.emissive = out.emissive.data();
    da.anyEmissive = anyEmissive(scene);
    // Shadow map.
    da.shadowMap = shadow.depth.row(0);
    da.shadowStride = shadow.depth.stride();
    da.shadowSize = s.shadowMapSize;
    std::copy_n(glm::value_ptr(shadow.lightViewProj), 16, da.lightViewProj);
    da.biasConst = s.shadowBias * shadow.texelSize / shadow.depthRange;
    da.biasSlope = s.shadowSlopeBias * shadow.texelSize / shadow.depthRange;
    da.pcfRadius = s.pcfRadius;
    const bool makeBounds =
        bounds == ShadowBoundsUse::Always || (bounds == ShadowBoundsUse::IfTheyPay &&
                                              shadowBoundsPay(s.width, s.height, s.shadowMapSize));
    if (makeBounds)
        buildShadowBounds(da.shadowMap, da.shadowStride, da.shadowSize, da.pcfRadius,
                          resolveIsa(s.isa), s.threads, out.shadowBounds);
    else out.shadowBounds = ShadowBounds();
    da.shadowBounds = makeBounds ? &out.shadowBounds.block.data()->lo : nullptr;
    da.shadowBlocks = makeBounds ? out.shadowBounds.blocks : 0;
    da.exposure = s.exposure;
    // The GGX energy tables of the specular (multiple scattering, DFG).
    da.energy = &energyTables();
    out.light = da;
    out.light.shadowMap = nullptr;
}

bool anyEmissive(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.emissive.r != 0.0f || m.emissive.g != 0.0f || m.emissive.b != 0.0f;
    });
}

void setDirectGBuffer(const GBuffer& g, DirectArgs& a) { a.g = g.view(); }

}  // namespace ssrt
