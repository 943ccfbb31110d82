// Small builders shared by the built-in scenes (builtin_scenes.cpp, failure_scenes.cpp).
// Every built-in scene is a still frame, and every angle goes through the project's own
// sincos so that the scenes are the same to the bit on every machine.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <utility>

#include "core/lane_math.h"
#include "scenes/scene.h"

namespace ssrt::helpers {

inline uint32_t addMesh(Scene& scene, Mesh mesh) {
    scene.meshes.push_back(std::move(mesh));
    return uint32_t(scene.meshes.size() - 1);
}

inline uint32_t addMaterial(Scene& scene, const std::string& name, glm::vec3 baseColor,
                            float metallic, float roughness, bool doubleSided = false) {
    Material m;
    m.name = name;
    m.baseColor = baseColor;
    m.metallic = metallic;
    m.roughness = roughness;
    m.doubleSided = doubleSided;
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
}

// Every built-in scene is a still frame: previous transform = transform.
inline void addInstance(Scene& scene, uint32_t mesh, uint32_t material,
                        const glm::mat4& transform) {
    scene.instances.push_back({mesh, material, transform, transform});
}

inline glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }

// Cosine and sine of an angle in degrees through the project's own sincos (libm's may
// differ between machines, and so would every golden image); quarter turns are exact so
// that the walls meet without gaps.
inline glm::vec2 cosSinDegrees(float degrees) {
    const float quarters = degrees / 90.0f;
    if (quarters == std::floor(quarters)) {
        const int q = int(quarters) & 3;  // two's complement: -1 & 3 = 3
        const glm::vec2 exact[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        return exact[q];
    }
    float s = 0.0f, c = 0.0f;
    lanes::sincos(glm::radians(degrees), s, c);
    return {c, s};
}

// Rotation about a unit axis (Rodrigues), counter-clockwise looking down the axis.
inline glm::mat4 rotate(float degrees, glm::vec3 axis) {
    const glm::vec2 cs = cosSinDegrees(degrees);
    const glm::mat3 k(0, axis.z, -axis.y, -axis.z, 0, axis.x, axis.y, -axis.x, 0);  // cross
    return glm::mat4(glm::mat3(1.0f) + cs.y * k + (1.0f - cs.x) * (k * k));
}

// The way light travels when it comes from azimuth `azimuthDeg` (0 = from +Z, the side
// the cameras stand on; 90 = from +X) at `elevationDeg` above the horizon.
inline glm::vec3 lightFrom(float azimuthDeg, float elevationDeg) {
    const glm::vec2 a = cosSinDegrees(azimuthDeg), e = cosSinDegrees(elevationDeg);
    return glm::normalize(-glm::vec3(e.x * a.y, e.y, e.x * a.x));
}

inline Camera makeCamera(glm::vec3 position, glm::vec3 target, float fovY) {
    Camera c;
    c.position = position;
    c.target = target;
    c.fovY = fovY;
    return c;
}

inline void setCamera(Scene& scene, const Camera& camera) {
    scene.camera = camera;
    scene.previousCamera = camera;  // a still frame
}

}  // namespace ssrt::helpers
