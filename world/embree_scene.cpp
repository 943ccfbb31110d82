#include "world/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scenes/material_alpha.h"
#include "scenes/tangents.h"

namespace ssrt {

namespace {

void check(RTCDevice device, const char* what) {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                                 std::to_string(int(e)) + ")");
}

// The mesh's `uvs` at Embree's barycentrics (u, v) of triangle `idx`; (0, 0) without UVs.
glm::vec2 hitUv(const std::vector<glm::vec2>& uvs, const uint32_t* idx, float u, float v) {
    if (uvs.empty()) return glm::vec2(0.0f);
    const float w0 = 1.0f - u - v;
    return w0 * uvs[idx[0]] + u * uvs[idx[1]] + v * uvs[idx[2]];
}

// The alpha cut-out as Embree's intersect and occlusion filter (Embree 3 API, "Filter
// Callback Functions"): a candidate hit that its instance's material cuts out at the hit's
// UV is dropped (valid = 0) and traversal goes on, so rays pass through the holes the
// rasterizer leaves, by the same rule (level 0, bilinear).
void alphaFilter(const RTCFilterFunctionNArguments* args) {
    const auto* f = static_cast<const std::pair<const Scene*, uint32_t>*>(args->geometryUserPtr);
    const Scene& scene = *f->first;
    const Mesh& mesh = scene.meshes[f->second];
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned inst = RTCHitN_instID(args->hit, args->N, i, 0);
        const Material& m = scene.materials[scene.instances[inst].material];
        if (!m.alphaTested()) continue;  // an opaque instance of a mesh another cuts out
        const uint32_t* idx = &mesh.indices[3 * std::size_t(RTCHitN_primID(args->hit, args->N, i))];
        const std::vector<glm::vec2>& uvs = m.baseColorUv.set == 1 ? mesh.uvs1 : mesh.uvs;
        const glm::vec2 uv =
            hitUv(uvs, idx, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
        if (!alphaPasses(scene, m, uv)) args->valid[i] = 0;
    }
}

RTCScene buildMeshScene(RTCDevice device, const Mesh& mesh, void* alphaFilterData) {
    RTCScene s = rtcNewScene(device);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    // Copies, not shared buffers: Embree may read 4 bytes past the last vertex.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    for (const glm::vec3& p : mesh.positions) *v++ = p.x, *v++ = p.y, *v++ = p.z;
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangleCount()));
    std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
    if (alphaFilterData) {
        rtcSetGeometryUserData(g, alphaFilterData);
        rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
        rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(s, g, 0);
    rtcReleaseGeometry(g);
    rtcCommitScene(s);
    return s;
}

void initRay(RTCRayHit& rh, glm::vec3 o, glm::vec3 d, float tnear, float tfar) {
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.time = 0.0f;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// The slot's texel at the mesh's `uv` through its UV transform (skipped when the identity,
// as in the texture pass).
glm::vec3 texel(const Scene& scene, int32_t texture, const UvTransform& t, const SurfacePoint& s,
                glm::vec3 fallback) {
    if (texture < 0) return fallback;
    const glm::vec2 uv = t.set == 1 ? s.uv1 : s.uv;
    const glm::vec2 st = t.identity() ? uv : t.apply(uv);
    return glm::vec3(scene.textures[std::size_t(texture)].sampleLevel(0, st));
}

// Embree's memory monitor: bytes it holds (ptr: an std::atomic<int64_t>).
bool countBytes(void* ptr, ssize_t bytes, bool /*post*/) {
    static_cast<std::atomic<int64_t>*>(ptr)->fetch_add(int64_t(bytes));
    return true;
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene, const char* deviceConfig) : scene_(scene) {
    scene.validate();
    const Bounds bounds = scene.bounds();
    origin_ = bounds.centre();
    stats_.lo = bounds.lo;
    stats_.hi = bounds.hi;
    stats_.diagonal = bounds.diagonal();
    for (const Instance& inst : scene.instances)
        transforms_.push_back(transformFrom(inst.transform, origin_));
    device_ = rtcNewDevice(deviceConfig);
    if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
    rtcSetDeviceMemoryMonitorFunction(device_, countBytes, &bytes_);
    const auto t0 = std::chrono::steady_clock::now();
    meshScenes_.assign(scene.meshes.size(), nullptr);
    // Meshes some instance draws with a cut-out material get the alpha filter; the others
    // are built as before.
    std::vector<bool> cutOut(scene.meshes.size(), false);
    for (const Instance& inst : scene.instances)
        if (scene.materials[inst.material].alphaTested()) cutOut[inst.mesh] = true;
    const bool anyCutOut = std::find(cutOut.begin(), cutOut.end(), true) != cutOut.end();
    if (anyCutOut &&
        !rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
        rtcReleaseDevice(device_);  // the destructor does not run for a throwing constructor
        device_ = nullptr;
        throw std::runtime_error(
            "Embree: this build has no filter functions, which alpha cut-outs (alphaMode MASK, "
            "BLEND) need");
    }
    for (uint32_t m = 0; m < scene.meshes.size(); ++m) alphaFilters_.emplace_back(&scene, m);
    for (auto& t : tangents_) t.assign(scene.meshes.size(), {});
    for (const Instance& inst : scene.instances) {
        const Material& m = scene.materials[inst.material];
        const int set = m.normalUv.set == 1 ? 1 : 0;
        if (m.normalTexture >= 0 && tangents_[set][inst.mesh].empty())
            tangents_[set][inst.mesh] = meshTangents(scene.meshes[inst.mesh], set);
    }
    top_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_HIGH);
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        RTCScene& ms = meshScenes_[inst.mesh];
        if (!ms) {
            ms = buildMeshScene(device_, scene.meshes[inst.mesh],
                                cutOut[inst.mesh] ? &alphaFilters_[inst.mesh] : nullptr);
            ++stats_.meshes;
        }
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, ms);
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &transforms_[i][0][0]);
        rtcCommitGeometry(g);
        // The instance's geometry id is its index in the scene: hits name it directly.
        rtcAttachGeometryByID(top_, g, unsigned(i));
        rtcReleaseGeometry(g);
        stats_.triangles += scene.meshes[inst.mesh].triangleCount();
    }
    rtcCommitScene(top_);
    stats_.buildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    check(device_, "the scene build");
    stats_.bytes = std::size_t(std::max<int64_t>(0, bytes_.load()));
    stats_.instances = scene.instances.size();
}

void requireSameOrigin(const EmbreeScene& embree, const TraceCamera& c, const char* who) {
    const glm::vec3 o = embree.origin();
    if (c.origin[0] != o.x || c.origin[1] != o.y || c.origin[2] != o.z)
        throw std::invalid_argument(std::string(who) +
                                    ": the camera's origin is not the scene's (TraceCamera::origin "
                                    "must be Scene::origin(), as the renderer sets it)");
}

EmbreeScene::~EmbreeScene() {
    if (top_) rtcReleaseScene(top_);
    for (RTCScene s : meshScenes_)
        if (s) rtcReleaseScene(s);
    if (device_) rtcReleaseDevice(device_);
}

EmbreeHit EmbreeScene::intersect(glm::vec3 o, glm::vec3 d, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    initRay(rh, o, d, tnear, tfar);
    rtcIntersect1(top_, &ctx, &rh);
    EmbreeHit h;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    h.hit = true;
    h.t = rh.ray.tfar;
    h.instance = rh.hit.instID[0];
    h.triangle = rh.hit.primID;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    return h;
}

void EmbreeScene::intersect16(int n, const glm::vec3* o, const glm::vec3* d, float tnear,
                              float tfar, EmbreeHit* hits) const {
    if (n < 1 || n > 16) throw std::invalid_argument("intersect16: n must be in [1, 16]");
    float nears[16], fars[16];
    for (int k = 0; k < n; ++k) nears[k] = tnear, fars[k] = tfar;
    intersect16(n, o, d, nears, fars, hits);
}

void EmbreeScene::intersect16(int n, const glm::vec3* o, const glm::vec3* d, const float* tnear,
                              const float* tfar, EmbreeHit* hits) const {
    if (n < 1 || n > 16) throw std::invalid_argument("intersect16: n must be in [1, 16]");
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    for (int k = 0; k < 16; ++k) {
        const int i = k < n ? k : 0;
        valid[k] = k < n ? -1 : 0;
        rh.ray.org_x[k] = o[i].x, rh.ray.org_y[k] = o[i].y, rh.ray.org_z[k] = o[i].z;
        rh.ray.dir_x[k] = d[i].x, rh.ray.dir_y[k] = d[i].y, rh.ray.dir_z[k] = d[i].z;
        rh.ray.tnear[k] = tnear[i];
        rh.ray.tfar[k] = tfar[i];
        rh.ray.time[k] = 0.0f;
        rh.ray.mask[k] = ~0u;
        rh.ray.id[k] = unsigned(k);
        rh.ray.flags[k] = 0;
        rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, top_, &ctx, &rh);
    for (int k = 0; k < n; ++k) {
        EmbreeHit& h = hits[k];
        h = EmbreeHit{};
        if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
        h.hit = true;
        h.t = rh.ray.tfar[k];
        h.instance = rh.hit.instID[0][k];
        h.triangle = rh.hit.primID[k];
        h.u = rh.hit.u[k];
        h.v = rh.hit.v[k];
    }
}

bool EmbreeScene::occluded(glm::vec3 o, glm::vec3 d, float tnear, float tfar) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
    r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
    r.tnear = tnear;
    r.tfar = tfar;
    r.time = 0.0f;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(top_, &ctx, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf when something is in the way
}

bool EmbreeScene::nativePackets16() const {
    return rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
}

std::array<glm::vec3, 3> EmbreeScene::corners(uint32_t instance, uint32_t triangle) const {
    const Mesh& mesh = scene_.meshes[scene_.instances[instance].mesh];
    const uint32_t* idx = &mesh.indices[3 * std::size_t(triangle)];
    std::array<glm::vec3, 3> p;
    for (int c = 0; c < 3; ++c)
        p[c] = glm::vec3(transforms_[instance] * glm::vec4(mesh.positions[idx[c]], 1.0f));
    return p;
}

SurfacePoint EmbreeScene::surface(glm::vec3 o, glm::vec3 d, const EmbreeHit& h) const {
    const Instance& inst = scene_.instances[h.instance];
    const Mesh& mesh = scene_.meshes[inst.mesh];
    const Material& mat = scene_.materials[inst.material];
    const uint32_t* idx = &mesh.indices[3 * std::size_t(h.triangle)];
    const float w0 = 1.0f - h.u - h.v;
    SurfacePoint s;
    s.position = o + h.t * d;
    s.instance = h.instance;
    s.material = inst.material;
    // The triangle in world space, for its geometric normal (Embree's Ng is in object space
    // under instancing).
    const std::array<glm::vec3, 3> p = corners(h.instance, h.triangle);
    const glm::vec3 ng = glm::cross(p[1] - p[0], p[2] - p[0]);
    const float ngl = glm::length(ng);
    s.geometricNormal = ngl > 0.0f ? ng / ngl : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
    const glm::vec3 n = normalMatrix * (w0 * mesh.normals[idx[0]] + h.u * mesh.normals[idx[1]] +
                                        h.v * mesh.normals[idx[2]]);
    const float nl = glm::length(n);
    s.shadingNormal = nl > 0.0f && std::isfinite(nl) ? n / nl : s.geometricNormal;
    s.uv = hitUv(mesh.uvs, idx, h.u, h.v);
    s.uv1 = hitUv(mesh.uvs1, idx, h.u, h.v);
    s.baseColor =
        mat.baseColor * texel(scene_, mat.baseColorTexture, mat.baseColorUv, s, glm::vec3(1.0f));
    const glm::vec3 mr =
        texel(scene_, mat.metallicRoughnessTexture, mat.metallicRoughnessUv, s, glm::vec3(1.0f));
    s.metallic = std::clamp(mat.metallic * mr.b, 0.0f, 1.0f);
    s.roughness = std::clamp(mat.roughness * mr.g, 0.0f, 1.0f);
    s.emissive =
        mat.emissive * texel(scene_, mat.emissiveTexture, mat.emissiveUv, s, glm::vec3(1.0f));
    if (mat.occlusionTexture >= 0)
        s.occlusion =
            1.0f +
            mat.occlusionStrength *
                (texel(scene_, mat.occlusionTexture, mat.occlusionUv, s, glm::vec3(1.0f)).r - 1.0f);
    if (mat.normalTexture >= 0) {
        // The world tangents at the corners, interpolated, as the resolve interpolates them.
        const std::vector<glm::vec4>& t = tangents_[mat.normalUv.set == 1 ? 1 : 0][inst.mesh];
        const glm::vec4 tangent = w0 * worldTangent(inst.transform, t[idx[0]]) +
                                  h.u * worldTangent(inst.transform, t[idx[1]]) +
                                  h.v * worldTangent(inst.transform, t[idx[2]]);
        const glm::vec3 map =
            texel(scene_, mat.normalTexture, mat.normalUv, s, glm::vec3(0.5f, 0.5f, 1.0f));
        s.shadingNormal = perturbNormal(s.shadingNormal, tangent, map, mat.normalScale);
    }
    s.doubleSided = mat.doubleSided;
    return s;
}

}  // namespace ssrt
