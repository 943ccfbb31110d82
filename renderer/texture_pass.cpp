#include "renderer/texture_pass.h"

#include <algorithm>

#include "scenes/tangents.h"

namespace ssrt {

namespace {

// The slot's UV set, then its UV transform on the UV and, linear part only, on the screen
// derivatives, so the level of detail sees the transformed footprint. The identity is
// skipped (the same bits as without one).
glm::vec4 sample(const Texture& tex, const UvTransform& t, const Frame& f, int x, int y) {
    const PlaneF* s = f.scratch.uv[t.set];
    const glm::vec2 uv(s[kUvU].at(x, y), s[kUvV].at(x, y));
    const glm::vec2 dx(s[kUvDuDx].at(x, y), s[kUvDvDx].at(x, y));
    const glm::vec2 dy(s[kUvDuDy].at(x, y), s[kUvDvDy].at(x, y));
    if (t.identity()) return tex.sample(uv, dx, dy);
    return tex.sample(t.apply(uv), t.linear(dx), t.linear(dy));
}

// The normal map bends the G-buffer normal in the pixel's tangent frame. (A UV transform's
// rotation is not applied to the frame: KHR_texture_transform does not say that it should.)
void normalMap(const Scene& scene, const Material& m, Frame& f, int x, int y) {
    const glm::vec4 t = sample(scene.textures[m.normalTexture], m.normalUv, f, x, y);
    PlaneF* normal = f.gbuffer.normal;
    const PlaneF* tf = f.scratch.tangent;
    const glm::vec3 n(normal[0].at(x, y), normal[1].at(x, y), normal[2].at(x, y));
    const glm::vec4 tangent(tf[0].at(x, y), tf[1].at(x, y), tf[2].at(x, y), tf[3].at(x, y));
    const glm::vec3 bent = perturbNormal(n, tangent, glm::vec3(t), m.normalScale);
    for (int c = 0; c < 3; ++c) normal[c].at(x, y) = bent[c];
}

// The per-pixel emission and occlusion planes: every pixel, textured or not.
// (Each written where the frame holds it: the graph gives the frame a material plane only
// where some material has that texture.)
void materialPlanes(const Scene& scene, const Material* m, Frame& f, int x, int y) {
    GBuffer& out = f.gbuffer;
    if (!out.emission[0].empty()) {
        glm::vec3 e = m ? m->emissive : glm::vec3(0.0f);
        if (m && m->emissiveTexture >= 0)
            e *= glm::vec3(sample(scene.textures[m->emissiveTexture], m->emissiveUv, f, x, y));
        for (int c = 0; c < 3; ++c) out.emission[c].at(x, y) = e[c];
    }
    if (!out.occlusion.empty()) {
        float o = 1.0f;
        if (m && m->occlusionTexture >= 0) {
            const float r = sample(scene.textures[m->occlusionTexture], m->occlusionUv, f, x, y).r;
            o = 1.0f + m->occlusionStrength * (r - 1.0f);
        }
        out.occlusion.at(x, y) = o;
    }
}

void texturePixel(const Scene& scene, Frame& f, int x, int y) {
    GBuffer& g = f.gbuffer;
    const float id = g.materialId.at(x, y);
    const Material* m = id >= 0.0f ? &scene.materials[std::size_t(id)] : nullptr;
    materialPlanes(scene, m, f, x, y);
    if (!m || !m->textured()) return;  // background, or nothing to sample
    if (m->baseColorTexture >= 0) {
        const glm::vec4 t = sample(scene.textures[m->baseColorTexture], m->baseColorUv, f, x, y);
        for (int c = 0; c < 3; ++c) g.albedo[c].at(x, y) *= t[c];
    }
    if (m->metallicRoughnessTexture >= 0) {
        const glm::vec4 t =
            sample(scene.textures[m->metallicRoughnessTexture], m->metallicRoughnessUv, f, x, y);
        g.metallic.at(x, y) = std::clamp(g.metallic.at(x, y) * t.b, 0.0f, 1.0f);
        g.roughness.at(x, y) = std::clamp(g.roughness.at(x, y) * t.g, 0.0f, 1.0f);
    }
    // (The resolve gives the tangent frame whenever some material has a normal map.)
    if (m->normalTexture >= 0 && !f.scratch.tangent[0].empty()) normalMap(scene, *m, f, x, y);
}

}  // namespace

void applyTexturesTile(const Scene& scene, Frame& frame, const TileGrid& grid, int tile) {
    const TileRect r = grid.rect(tile);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) texturePixel(scene, frame, x, y);
}

}  // namespace ssrt
