// The scene in world space: its instances in an Embree 3 BVH, built once per scene, and what a
// hit on it means (the surface point, its normals and material). world/ (ssrt_world) is the
// one library that links Embree; the core library never does (DESIGN.md: Embree at the edges).
//
// Embree answers are a measurement, not part of the determinism contract: Embree picks its
// own ISA kernels at run time and builds its BVH on its own threads. A hit distance can differ
// in its last bits between machines; a first hit can differ only where two triangles tie.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <utility>
#include <vector>

#include "scenes/scene.h"
#include "trace/trace_types.h"

// Embree's handles, without its header in ours.
typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace ssrt {

// What the build made, for `ssrt compare` and the sweep.
struct BvhStats {
    double buildMs = 0.0;    // every mesh's BVH and the instance BVH, wall clock
    std::size_t meshes = 0;  // meshes some instance uses (one bottom-level BVH each)
    std::size_t instances = 0;
    std::size_t triangles = 0;     // over instances (what a flattened scene would hold)
    std::size_t bytes = 0;         // Embree's memory after the build (its memory monitor)
    glm::vec3 lo{0.0f}, hi{0.0f};  // world bounds
    float diagonal = 0.0f;
};

// First hit of a world-space ray.
struct EmbreeHit {
    bool hit = false;
    float t = 0.0f;            // distance along the (unit) direction
    uint32_t instance = 0;     // Scene::instances index
    uint32_t triangle = 0;     // triangle of that instance's mesh
    float u = 0.0f, v = 0.0f;  // Embree's barycentrics: p = (1 - u - v) p0 + u p1 + v p2
};

// The surface at a hit, in world space.
struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f};  // unit, the triangle's front side (CCW)
    // unit, interpolated vertex normals, bent by the material's normal map (level 0)
    glm::vec3 shadingNormal{0.0f, 1.0f, 0.0f};
    glm::vec2 uv{0.0f};   // (0, 0) for a mesh without UVs
    glm::vec2 uv1{0.0f};  // the second set, likewise
    uint32_t instance = 0, material = 0;
    glm::vec3 baseColor{0.0f};  // material factor times its texture (level 0, bilinear)
    float metallic = 0.0f, roughness = 0.0f;
    glm::vec3 emissive{0.0f};  // factor times its texture (level 0, bilinear)
    float occlusion = 1.0f;    // 1 + strength (R - 1) of the occlusion texture, 1 without
    bool doubleSided = false;
};

class EmbreeScene;
// Throws std::invalid_argument (naming `who`) unless the camera's positions are measured from
// the Embree scene's origin (TraceCamera::origin == EmbreeScene::origin()).
void requireSameOrigin(const EmbreeScene& embree, const TraceCamera& camera, const char* who);

class EmbreeScene {
public:
    // Builds the BVHs (RTC_BUILD_QUALITY_HIGH): one per mesh, one over the instances. Keeps a
    // reference to `scene`, which must outlive this. `deviceConfig`: Embree's device string
    // (rtcNewDevice; "isa=sse2" picks its kernels, as the tests do), null for its defaults.
    // Throws std::runtime_error when Embree cannot start or the build fails.
    explicit EmbreeScene(const Scene& scene, const char* deviceConfig = nullptr);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    const BvhStats& stats() const { return stats_; }
    const Scene& scene() const { return scene_; }
    // Every position in and out (ray origins, hit points) is measured from here: the
    // scene's origin (Scene::origin()), as the renderer's passes and TraceCamera::position.
    glm::vec3 origin() const { return origin_; }

    // First hit with t in [tnear, tfar]; direction unit. Both faces of every triangle count
    // (the caller decides what a back face means); a point an alpha cut-out removes
    // (scenes/material_alpha.h) does not, here nor in intersect16 and occluded. Thread-safe.
    EmbreeHit intersect(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) const;
    // The same for up to 16 rays at once (Embree's packets; n in [1, 16]); equal answers to
    // intersect(), faster on coherent rays.
    void intersect16(int n, const glm::vec3* origin, const glm::vec3* direction, float tnear,
                     float tfar, EmbreeHit* hits) const;
    // The same with an interval per ray (tnear[k], tfar[k]).
    void intersect16(int n, const glm::vec3* origin, const glm::vec3* direction, const float* tnear,
                     const float* tfar, EmbreeHit* hits) const;
    // Whether anything lies on the ray with t in [tnear, tfar] (shadow rays). Thread-safe.
    bool occluded(glm::vec3 origin, glm::vec3 direction, float tnear, float tfar) const;

    // The corners of an instance's triangle in world space, measured from origin(): the mesh's
    // positions times the instance's transform (transformFrom), as surface() takes them.
    std::array<glm::vec3, 3> corners(uint32_t instance, uint32_t triangle) const;

    // The surface at a hit (hit.hit must be true), its material with textures applied.
    SurfacePoint surface(glm::vec3 origin, glm::vec3 direction, const EmbreeHit& hit) const;

    // A small distance for stepping off a surface: 1e-4 of the bounds' diagonal.
    float epsilon() const { return 1e-4f * stats_.diagonal; }
    // Whether Embree runs 16-ray packets natively on this CPU (its AVX-512 kernels); else
    // intersect16 splits them.
    bool nativePackets16() const;

private:
    const Scene& scene_;
    glm::vec3 origin_;
    std::vector<glm::mat4> transforms_;  // per instance, from the origin (transformFrom)
    RTCDevice device_ = nullptr;
    RTCScene top_ = nullptr;
    std::vector<RTCScene> meshScenes_;  // per mesh (null where no instance uses it)
    // Per mesh, what its geometry's alpha filter reads (its user data): the scene and the
    // mesh's index. Filled before any build, never resized after.
    std::vector<std::pair<const Scene*, uint32_t>> alphaFilters_;
    // Per mesh and UV set, the object-space tangents a normal map reads (scenes/tangents.h,
    // meshTangents), filled only where an instance's material has a normal map.
    std::vector<std::vector<glm::vec4>> tangents_[2];
    BvhStats stats_;
    std::atomic<int64_t> bytes_{0};
};

}  // namespace ssrt
