#include "renderer/texture_pass.h"

#include <algorithm>

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

void texturePixel(const Scene& scene, const TexturePlanes& p, int x, int y) {
    const float id = p.materialId->at(x, y);
    if (!(id >= 0.0f)) return;  // background
    const Material& m = scene.materials[std::size_t(id)];
    if (!m.textured()) return;
    if (m.baseColorTexture >= 0) {
        const glm::vec4 t = sample(scene.textures[m.baseColorTexture], m.baseColorUv, p, x, y);
        for (int c = 0; c < 3; ++c) p.albedo[c]->at(x, y) *= t[c];
    }
    if (m.metallicRoughnessTexture >= 0) {
        const glm::vec4 t =
            sample(scene.textures[m.metallicRoughnessTexture], m.metallicRoughnessUv, p, x, y);
        p.metallic->at(x, y) = std::clamp(p.metallic->at(x, y) * t.b, 0.0f, 1.0f);
        p.roughness->at(x, y) = std::clamp(p.roughness->at(x, y) * t.g, 0.0f, 1.0f);
    }
}

}  // namespace

void applyTextures(const Scene& scene, const TexturePlanes& planes, const TileGrid& grid,
                   int threads) {
    parallelForTiles(grid.count(), threads, [&](int tile) {
        const TileRect r = grid.rect(tile);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) texturePixel(scene, planes, x, y);
    });
}

}  // namespace ssrt
