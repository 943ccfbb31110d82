#include "renderer/texture_pass.h"

#include <algorithm>

#include "scenes/tangents.h"

namespace ssrt {

namespace {

// The slot's UV set, then its UV transform on the UV and, linear part only, on the screen
// derivatives, so the level of detail sees the transformed footprint. The identity is
// skipped (the same bits as without one).
glm::vec4 sample(const Texture& tex, const UvTransform& t, const TexturePlanes& p, int x, int y) {
    const PlaneF* const* s = p.uv[t.set];
    const glm::vec2 uv(s[0]->at(x, y), s[1]->at(x, y));
    const glm::vec2 dx(s[2]->at(x, y), s[3]->at(x, y));
    const glm::vec2 dy(s[4]->at(x, y), s[5]->at(x, y));
    if (t.identity()) return tex.sample(uv, dx, dy);
    return tex.sample(t.apply(uv), t.linear(dx), t.linear(dy));
}

// The normal map bends the G-buffer normal in the pixel's tangent frame. (A UV transform's
// rotation is not applied to the frame: KHR_texture_transform does not say that it should.)
void normalMap(const Scene& scene, const Material& m, const TexturePlanes& p, int x, int y) {
    const glm::vec4 t = sample(scene.textures[m.normalTexture], m.normalUv, p, x, y);
    const glm::vec3 n(p.normal[0]->at(x, y), p.normal[1]->at(x, y), p.normal[2]->at(x, y));
    const glm::vec4 tangent(p.tangent[0]->at(x, y), p.tangent[1]->at(x, y), p.tangent[2]->at(x, y),
                            p.tangent[3]->at(x, y));
    const glm::vec3 bent = perturbNormal(n, tangent, glm::vec3(t), m.normalScale);
    for (int c = 0; c < 3; ++c) p.normal[c]->at(x, y) = bent[c];
}

// The per-pixel emission and occlusion planes: every pixel, textured or not.
void materialPlanes(const Scene& scene, const Material* m, const TexturePlanes& p, int x, int y) {
    if (p.emission[0]) {
        glm::vec3 e = m ? m->emissive : glm::vec3(0.0f);
        if (m && m->emissiveTexture >= 0)
            e *= glm::vec3(sample(scene.textures[m->emissiveTexture], m->emissiveUv, p, x, y));
        for (int c = 0; c < 3; ++c) p.emission[c]->at(x, y) = e[c];
    }
    if (p.occlusion) {
        float o = 1.0f;
        if (m && m->occlusionTexture >= 0) {
            const float r = sample(scene.textures[m->occlusionTexture], m->occlusionUv, p, x, y).r;
            o = 1.0f + m->occlusionStrength * (r - 1.0f);
        }
        p.occlusion->at(x, y) = o;
    }
}

void texturePixel(const Scene& scene, const TexturePlanes& p, int x, int y) {
    const float id = p.materialId->at(x, y);
    const Material* m = id >= 0.0f ? &scene.materials[std::size_t(id)] : nullptr;
    materialPlanes(scene, m, p, x, y);
    if (!m || !m->textured()) return;  // background, or nothing to sample
    if (m->baseColorTexture >= 0) {
        const glm::vec4 t = sample(scene.textures[m->baseColorTexture], m->baseColorUv, p, x, y);
        for (int c = 0; c < 3; ++c) p.albedo[c]->at(x, y) *= t[c];
    }
    if (m->metallicRoughnessTexture >= 0) {
        const glm::vec4 t =
            sample(scene.textures[m->metallicRoughnessTexture], m->metallicRoughnessUv, p, x, y);
        p.metallic->at(x, y) = std::clamp(p.metallic->at(x, y) * t.b, 0.0f, 1.0f);
        p.roughness->at(x, y) = std::clamp(p.roughness->at(x, y) * t.g, 0.0f, 1.0f);
    }
    if (m->normalTexture >= 0 && p.tangent[0]) normalMap(scene, *m, p, x, y);
}

}  // namespace

void applyTexturesTile(const Scene& scene, const TexturePlanes& planes, const TileGrid& grid,
                       int tile) {
    const TileRect r = grid.rect(tile);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) texturePixel(scene, planes, x, y);
}

}  // namespace ssrt
