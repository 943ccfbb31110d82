#include "scenes/material_alpha.h"

namespace ssrt {

namespace {

// glTF: alpha "greater than or equal to" the cutoff is opaque.
bool aboveCutoff(const Material& m, float alpha) { return alpha >= m.alphaCutoff; }

}  // namespace

AlphaCoverage alphaCoverage(const Material& m) {
    if (!m.alphaTested()) return AlphaCoverage::Opaque;
    if (m.baseColorTexture >= 0) return AlphaCoverage::PerPoint;
    return aboveCutoff(m, m.baseColorAlpha) ? AlphaCoverage::Opaque : AlphaCoverage::Invisible;
}

float materialAlpha(const Scene& scene, const Material& m, glm::vec2 uv) {
    if (m.baseColorTexture < 0) return m.baseColorAlpha;
    const UvTransform& t = m.baseColorUv;
    const glm::vec2 st = t.identity() ? uv : t.apply(uv);  // as the texture pass reads it
    return m.baseColorAlpha * scene.textures[std::size_t(m.baseColorTexture)].sampleLevel(0, st).a;
}

bool alphaPasses(const Scene& scene, const Material& m, glm::vec2 uv) {
    return !m.alphaTested() || aboveCutoff(m, materialAlpha(scene, m, uv));
}

}  // namespace ssrt
