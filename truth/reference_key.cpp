// referenceKey (truth/reference_image.h): FNV-1a 64 over everything the reference
// depends on, field by field in a fixed order (never over struct bytes: padding is undefined).
#include <cstring>
#include <string_view>
#include <vector>

#include "renderer/settings_fields.h"
#include "truth/reference_image.h"

namespace ssrt {

namespace {

// Bump whenever the reference's model or sampling changes: old cached images then miss.
// 2: the specular with the DFG table and Kulla-Conty multiple scattering (shade::shadeSurface).
// 3: positions measured from the scene's origin (Scene::origin()), and the march's relative
//    maxDistance (the same image to within float rounding, not to the bit).
// 4: the primary hit that gives a pixel its geometric normal starts at the near plane, as the
//    rasterizer clips (the same bits where nothing lies nearer than the near plane).
// 5: the shadow map's visibility (Visibility::ShadowMap) compares each PCF tap with the
//    receiver's plane (shade::shadowVisibility); Embree's visibility is unchanged.
constexpr uint64_t kReferenceVersion = 5;

// Fowler-Noll-Vo 1a, 64 bits (http://www.isthe.com/chongo/tech/comp/fnv/).
class Fnv1a {
public:
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
    }
    template <class T>
    void value(const T& v) {
        static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
        bytes(&v, sizeof v);
    }
    // Vectors carry their length, so [a][bc] and [ab][c] differ.
    template <class T>
    void array(const std::vector<T>& v) {
        value(uint64_t(v.size()));
        bytes(v.data(), v.size() * sizeof(T));
    }
    void vec3(glm::vec3 v) { bytes(&v[0], 3 * sizeof(float)); }
    void mat4(const glm::mat4& m) {
        for (int c = 0; c < 4; ++c) bytes(&m[c][0], 4 * sizeof(float));
    }
    uint64_t digest() const { return h_; }

private:
    uint64_t h_ = 0xcbf29ce484222325ull;
};

// glm::vec2/3/4 and uint32_t are tightly packed floats or integers: hashed as arrays.
static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec2) == 8 && sizeof(glm::vec4) == 16);

void hashMaterial(Fnv1a& h, const Material& m) {
    h.vec3(m.baseColor);
    h.value(m.metallic);
    h.value(m.roughness);
    h.vec3(m.emissive);
    h.value(m.doubleSided);
    h.value(m.baseColorTexture);
    h.value(m.metallicRoughnessTexture);
    // A slot's UV set and transform only when not set 0 and the identity: the keys of
    // scenes without them stay as they were.
    // The normal, occlusion and emissive slots only when some is used, likewise.
    if (m.normalTexture >= 0 || m.occlusionTexture >= 0 || m.emissiveTexture >= 0) {
        h.value(m.normalTexture);
        h.value(m.occlusionTexture);
        h.value(m.emissiveTexture);
        h.value(m.normalScale);
        h.value(m.occlusionStrength);
    }
    const UvTransform* slots[] = {&m.baseColorUv, &m.metallicRoughnessUv, &m.normalUv,
                                  &m.occlusionUv, &m.emissiveUv};
    const int32_t textures[] = {m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture,
                                m.occlusionTexture, m.emissiveTexture};
    for (uint32_t slot = 0; slot < 5; ++slot) {
        if (slot >= 2 && textures[slot] < 0) continue;  // an unused new slot: nothing to say
        if (slots[slot]->identity() && slots[slot]->set == 0) continue;
        h.value(slot);
        const UvTransform& t = *slots[slot];
        for (float f : {t.row0.x, t.row0.y, t.row1.x, t.row1.y, t.offset.x, t.offset.y}) h.value(f);
        h.value(t.set);
    }
    // The alpha cut-out only where it cuts (MASK, BLEND): the keys of every other scene stay
    // as they were.
    if (m.alphaTested()) {
        h.value(m.alphaMode);
        h.value(m.baseColorAlpha);
        h.value(m.alphaCutoff);
    }
}

void hashTexture(Fnv1a& h, const Texture& t) {
    h.value(t.wrapU);
    h.value(t.wrapV);
    h.value(uint64_t(t.levels.size()));
    for (const TextureLevel& l : t.levels) {
        h.value(l.width);
        h.value(l.height);
        h.array(l.texels);
    }
}

void hashSky(Fnv1a& h, const Sky& s) {
    h.value(s.kind);
    h.vec3(s.zenith);
    h.vec3(s.horizon);
    h.vec3(s.ground);
    h.value(s.intensity);
    h.value(bool(s.image));
    if (s.image) {
        h.value(s.image->width);
        h.value(s.image->height);
        h.array(s.image->rgb);
    }
}

void hashCamera(Fnv1a& h, const Camera& c) {
    h.vec3(c.position);
    h.vec3(c.target);
    h.vec3(c.up);
    h.value(c.fovY);
    h.value(c.nearZ);
    h.value(c.farZ);
}

// The scene's content; names and the scene's own cameras aside (the camera is an argument).
void hashScene(Fnv1a& h, const Scene& scene) {
    h.value(uint64_t(scene.meshes.size()));
    for (const Mesh& m : scene.meshes) {
        h.array(m.positions);
        h.array(m.normals);
        h.array(m.uvs);
        if (!m.uvs1.empty()) h.array(m.uvs1);          // only then: keys without it unchanged
        if (!m.tangents.empty()) h.array(m.tangents);  // likewise
        h.array(m.indices);
    }
    h.value(uint64_t(scene.materials.size()));
    for (const Material& m : scene.materials) hashMaterial(h, m);
    h.value(uint64_t(scene.instances.size()));
    for (const Instance& i : scene.instances) {
        h.value(i.mesh);
        h.value(i.material);
        h.mat4(i.transform);  // the previous transform moves motion vectors only
    }
    h.value(uint64_t(scene.textures.size()));
    for (const Texture& t : scene.textures) hashTexture(h, t);
    h.vec3(scene.light.direction);
    h.vec3(scene.light.color);
    h.value(scene.light.intensity);
    hashSky(h, scene.sky);
}

// The render settings that shape the reference, as the field tables mark them (kFieldKey,
// renderer/settings_fields.h), in table order: the G-buffer (size), the shadow map (its
// visibility mode and the ray offsets' surface), the exposure, and the SSR sampler, with the
// frame index (the reference's rays are the frame's sample sequence) between the
// RenderSettings fields and the tracing ones. Threads and ISA do not (the determinism
// contract), nor the marcher, the resolve or the frame's spp (the reference replaces them);
// the march's maxDistance does through ReferenceSettings. Each field is hashed as its
// member's bytes, so the key is the one the hand-written list gave.
void hashRender(Fnv1a& h, const RenderSettings& r, uint32_t frameIndex) {
    for (const auto& f : kRenderOwnFields)
        if (f.has(kFieldKey)) h.bytes(f.address(r), f.size);
    h.value(frameIndex);
    for (const auto& f : kTraceFields)
        if (f.has(kFieldKey)) h.bytes(f.address(r.trace), f.size);
}

}  // namespace

uint64_t referenceKey(const Scene& scene, const Camera& camera, uint32_t frameIndex,
                      const RenderSettings& render, const ReferenceSettings& settings) {
    Fnv1a h;
    h.value(kReferenceVersion);
    hashScene(h, scene);
    hashCamera(h, camera);
    hashRender(h, render, frameIndex);
    h.value(settings.visibility);
    h.value(settings.spp);
    h.value(settings.maxDistance);
    // Only when not 1: the one-bounce keys (every cache made before) stay as they were.
    if (settings.bounces != 1) h.value(settings.bounces);
    return h.digest();
}

}  // namespace ssrt
