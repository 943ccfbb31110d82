#include "scenes/gltf_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace ssrt::gltf {
namespace {

// A unit rotation composed in float is orthonormal to about 1e-7; anything past this is a
// scale or a shear the file meant.
constexpr double kTolerance = 1e-5;

std::string shortNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

bool sheared(const glm::dvec3& a, const glm::dvec3& b) {
    return std::abs(glm::dot(a, b)) > kTolerance * glm::length(a) * glm::length(b);
}

}  // namespace

Camera placeCamera(const glm::mat4& world, double yfov, double znear, double zfar,
                   CameraPlacement& placement) {
    const glm::dvec3 x(world[0]), y(world[1]), z(world[2]), position(world[3]);
    const double sx = glm::length(x), sy = glm::length(y), sz = glm::length(z);
    placement = {};
    // Orthonormalised: the view axis exactly, up made perpendicular to it (Gram-Schmidt).
    const glm::dvec3 forward = -z / sz;
    const glm::dvec3 upInPlane = y - glm::dot(y, forward) * forward;
    const double upLength = glm::length(upInPlane);
    if (!(sz > 0.0) || !(upLength > 0.0) || !std::isfinite(upLength + sz) ||
        !std::isfinite(position.x + position.y + position.z)) {
        placement.degenerate = true;
        return {};
    }
    const double largest = std::max({sx, sy, sz}), smallest = std::min({sx, sy, sz});
    placement.uneven =
        largest > (1.0 + kTolerance) * smallest || sheared(x, y) || sheared(x, z) || sheared(y, z);
    placement.mirrored = glm::dot(glm::cross(x, y), z) < 0.0;
    placement.scale = std::abs(sz - 1.0) > kTolerance ? float(sz) : 1.0f;

    Camera c;
    c.position = glm::vec3(position);
    c.nearZ = float(znear * placement.scale);
    c.farZ = float(zfar * placement.scale);
    // The look-at point as far from the camera as the camera is from 0 (and at least its near
    // distance): rounding it to float then turns the view by about 1e-7 rad, where a point one
    // unit ahead of a camera 1e6 units out would turn it by its float spacing, 0.06 rad.
    const double lever = glm::length(position) + double(c.nearZ);
    c.target = glm::vec3(position + forward * lever);
    c.up = glm::vec3(upInPlane / upLength);
    c.fovY = glm::degrees(float(yfov));
    return c;
}

std::size_t trianglesBeyondFar(const Scene& scene) {
    const Camera& camera = scene.camera;
    // View depth in double: a scene far from 0 keeps its precision.
    const glm::dvec3 eye(camera.position);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
    const double far = camera.farZ;
    std::size_t count = 0;
    std::vector<char> beyond;
    for (const Instance& inst : scene.instances) {
        const Mesh& mesh = scene.meshes[inst.mesh];
        const glm::dmat4 m(inst.transform);
        beyond.resize(mesh.positions.size());
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            const glm::dvec3 p(m * glm::dvec4(glm::dvec3(mesh.positions[v]), 1.0));
            beyond[v] = glm::dot(p - eye, forward) > far;
        }
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
            count += beyond[mesh.indices[i]] && beyond[mesh.indices[i + 1]] &&
                     beyond[mesh.indices[i + 2]];
    }
    return count;
}

std::vector<std::string> placementWarnings(const CameraPlacement& placement, double znear,
                                           double zfar, const Scene& scene) {
    std::vector<std::string> lines;
    const Camera& c = scene.camera;
    if (placement.scale != 1.0f) {
        std::string planes = shortNumber(znear) + " -> " + shortNumber(c.nearZ);
        if (zfar > 0.0) planes += ", " + shortNumber(zfar) + " -> " + shortNumber(c.farZ);
        lines.push_back("its node scales by " + shortNumber(placement.scale) +
                        " along the view axis: znear and zfar are scaled with it (" + planes +
                        "), where glTF ignores a camera's scale");
    }
    if (placement.uneven)
        lines.push_back(
            "its node scales unevenly or shears: the view is orthonormalised "
            "(along its -Z, up from its +Y)");
    if (placement.mirrored)
        lines.push_back("its node mirrors: the mirror is ignored (the image is not flipped)");
    if (placement.beyondFar > 0)
        lines.push_back(std::to_string(placement.beyondFar) + " of " +
                        std::to_string(scene.triangleCount()) +
                        " triangles lie wholly beyond its far plane (" + shortNumber(c.farZ) +
                        " scene units) and are not drawn");
    return lines;
}

}  // namespace ssrt::gltf
