#include "renderer/resolve_tables.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

#include "core/tiles.h"
#include "scenes/tangents.h"

namespace ssrt {

bool anyTextured(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.textured(); });
}

bool anyUvSet1(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.usesUvSet1(); });
}

bool anyNormalMapped(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.normalTexture >= 0; });
}

bool anyOcclusionTextured(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.occlusionTexture >= 0; });
}

bool anyEmissiveTextured(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.emissiveTexture >= 0; });
}

namespace {

// Per instance, the object-space tangents its normal map reads (the mesh's, or generated
// from the map's UV set once per mesh and set), or null for instances without a normal map.
std::vector<const std::vector<glm::vec4>*> instanceTangents(
    const Scene& scene, std::vector<std::vector<glm::vec4>>& generated) {
    std::vector<const std::vector<glm::vec4>*> out(scene.instances.size(), nullptr);
    // Generated sets by (mesh, UV set): index into `generated`.
    std::vector<int> slot(2 * scene.meshes.size(), -1);
    generated.reserve(scene.instances.size());  // pointers into it stay valid
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        const Material& m = scene.materials[inst.material];
        if (m.normalTexture < 0) continue;
        const Mesh& mesh = scene.meshes[inst.mesh];
        if (!mesh.tangents.empty()) {
            out[i] = &mesh.tangents;
            continue;
        }
        int& s = slot[2 * inst.mesh + (m.normalUv.set == 1 ? 1 : 0)];
        if (s < 0) {
            s = int(generated.size());
            generated.push_back(generateTangents(mesh, m.normalUv.set));
        }
        out[i] = &generated[std::size_t(s)];
    }
    return out;
}

ResolveInstance resolveInstance(const Scene& scene, const Instance& inst, glm::vec3 origin,
                                const glm::mat4& view, const glm::mat4& prevViewProj) {
    const Material& m = scene.materials[inst.material];
    ResolveInstance r;
    r.albedo[0] = m.baseColor.r;
    r.albedo[1] = m.baseColor.g;
    r.albedo[2] = m.baseColor.b;
    r.metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    r.roughness = std::clamp(m.roughness, 0.0f, 1.0f);
    r.materialId = float(inst.material);
    // current view -> world -> object (current) -> world (previous) -> previous clip
    // (every world here measured from the origin)
    const glm::mat4 toPrev = prevViewProj * transformFrom(inst.previousTransform, origin) *
                             glm::inverse(transformFrom(inst.transform, origin)) *
                             glm::inverse(view);
    std::copy_n(glm::value_ptr(toPrev), 16, r.viewToPrevClip);
    return r;
}

// Runs fn(instance, first, end) over chunks of [0, count(instance)) for every instance, so
// that one big mesh still spreads over every thread.
template <class CountFn, class Fn>
void forInstanceChunks(std::size_t instances, int threads, CountFn count, Fn fn) {
    constexpr uint32_t kChunk = 4096;
    std::vector<std::pair<uint32_t, uint32_t>> work;  // (instance, first)
    for (uint32_t i = 0; i < instances; ++i)
        for (uint32_t first = 0; first < count(i); first += kChunk) work.push_back({i, first});
    parallelFor(int(work.size()), threads, [&](int w) {
        const auto [i, first] = work[w];
        fn(i, first, std::min<uint32_t>(count(i), first + kChunk));
    });
}

}  // namespace

ResolveTables buildResolveTables(const Scene& scene, glm::vec3 origin, const glm::mat4& view,
                                 const glm::mat4& prevViewProj, bool textured, int threads) {
    ResolveTables t;
    std::vector<uint32_t> vertexOffset, triOffset;
    uint32_t nv = 0, nt = 0;
    for (const Instance& inst : scene.instances) {
        vertexOffset.push_back(nv);
        triOffset.push_back(nt);
        nv += uint32_t(scene.meshes[inst.mesh].positions.size());
        nt += uint32_t(scene.meshes[inst.mesh].triangleCount());
        t.instances.push_back(resolveInstance(scene, inst, origin, view, prevViewProj));
    }
    t.triangles.resize(nt);
    t.nx.resize(nv);
    t.ny.resize(nv);
    t.nz.resize(nv);
    const bool set1 = textured && anyUvSet1(scene);
    if (textured) {
        t.u.resize(nv);
        t.v.resize(nv);
    }
    if (set1) {
        t.u1.resize(nv);
        t.v1.resize(nv);
    }
    const bool tangents = textured && anyNormalMapped(scene);
    std::vector<std::vector<glm::vec4>> generated;
    std::vector<const std::vector<glm::vec4>*> objectTangents;
    if (tangents) {
        objectTangents = instanceTangents(scene, generated);
        for (std::vector<float>& c : t.tangent) c.assign(nv, 0.0f);
    }
    std::vector<glm::vec3> viewPos(nv);
    auto meshOf = [&](uint32_t i) -> const Mesh& { return scene.meshes[scene.instances[i].mesh]; };
    // View-space positions and world-space unit normals per vertex.
    forInstanceChunks(
        scene.instances.size(), threads,
        [&](uint32_t i) { return uint32_t(meshOf(i).positions.size()); },
        [&](uint32_t i, uint32_t first, uint32_t end) {
            const Instance& inst = scene.instances[i];
            const Mesh& mesh = meshOf(i);
            const glm::mat4 modelView = view * transformFrom(inst.transform, origin);
            const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(inst.transform));
            for (uint32_t v = first; v < end; ++v) {
                const uint32_t g = vertexOffset[i] + v;
                viewPos[g] = glm::vec3(modelView * glm::vec4(mesh.positions[v], 1.0f));
                glm::vec3 n = normalMatrix * mesh.normals[v];
                const float len = glm::length(n);
                n = std::isfinite(len) && len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
                t.nx[g] = n.x;
                t.ny[g] = n.y;
                t.nz[g] = n.z;
                if (textured) {
                    const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
                    t.u[g] = uv.x;
                    t.v[g] = uv.y;
                }
                if (set1) {
                    const glm::vec2 uv = mesh.uvs1.empty() ? glm::vec2(0.0f) : mesh.uvs1[v];
                    t.u1[g] = uv.x;
                    t.v1[g] = uv.y;
                }
                if (tangents && objectTangents[i]) {
                    const glm::vec4 tw = worldTangent(inst.transform, (*objectTangents[i])[v]);
                    for (int c = 0; c < 4; ++c) t.tangent[c][g] = tw[c];
                }
            }
        });
    // Ray-plane and barycentric set-up per triangle.
    forInstanceChunks(
        scene.instances.size(), threads,
        [&](uint32_t i) { return uint32_t(meshOf(i).triangleCount()); },
        [&](uint32_t i, uint32_t first, uint32_t end) {
            const Mesh& mesh = meshOf(i);
            const glm::vec3* pv = viewPos.data() + vertexOffset[i];
            for (uint32_t k = first; k < end; ++k) {
                const uint32_t* idx = &mesh.indices[3 * k];
                const glm::vec3 p0 = pv[idx[0]], e1 = pv[idx[1]] - p0, e2 = pv[idx[2]] - p0;
                const glm::vec3 n = glm::cross(e1, e2);
                const float nn = glm::dot(n, n);
                ResolveTriangle& r = t.triangles[triOffset[i] + k];
                r = ResolveTriangle{};
                r.instance = i;
                r.localTriangle = k;
                for (int c = 0; c < 3; ++c) r.v[c] = vertexOffset[i] + idx[c];
                if (!(nn > 0.0f) || !std::isfinite(nn)) continue;  // never rasterized
                const glm::vec3 un = n / std::sqrt(nn);
                const glm::vec3 g1 = glm::cross(e2, n) / nn, g2 = glm::cross(n, e1) / nn;
                for (int c = 0; c < 3; ++c) {
                    r.p0[c] = p0[c];
                    r.n[c] = un[c];
                    r.g1[c] = g1[c];
                    r.g2[c] = g2[c];
                }
                r.d = glm::dot(un, p0);
            }
        });
    t.viewPositions = std::move(viewPos);
    return t;
}

}  // namespace ssrt
