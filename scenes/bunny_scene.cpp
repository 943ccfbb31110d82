#include "scenes/bunny_scene.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "scenes/data/bunny_mesh.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"

namespace ssrt {

using namespace helpers;

Mesh makeBunnyMesh(float height) {
    if (!(height > 0.0f))  // also rejects NaN
        throw std::invalid_argument("bunny height must be positive (got " + std::to_string(height) +
                                    ")");
    const std::span<const float> xyz = data::bunnyPositions();
    const std::span<const uint32_t> indices = data::bunnyIndices();
    Mesh mesh;
    mesh.name = "bunny";
    mesh.positions.reserve(xyz.size() / 3);
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
        mesh.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    mesh.indices.assign(indices.begin(), indices.end());
    // Scale about the bottom centre of the bounds: that point lands on the origin, so the
    // lowest vertex sits at y = 0 exactly ((lo.y - lo.y) * s).
    glm::vec3 lo = mesh.positions[0], hi = mesh.positions[0];
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 anchor(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z));
    const float scale = height / (hi.y - lo.y);
    for (glm::vec3& p : mesh.positions) p = (p - anchor) * scale;
    mesh.normals = smoothNormals(mesh);
    return mesh;
}

// ---- bunny -----------------------------------------------------------------------------
// At 1 m tall the scan's 3.7k triangles have edges of 3 to 6 cm, laid out with no grid or
// symmetry (a scan, not a builder). The bunny faces -X; the camera stands three-quarters in
// front of it, to its left (-X, +Z), where the ears overlap each other and the head. The sun
// comes low from behind the camera's right, so the whole shadow, ears included, lies on the
// ground to the left; the ground is a glossy dielectric, so the feet meet their blurred
// reflection.
Scene makeBunnyScene() {
    Scene scene;
    scene.name = "bunny";
    const uint32_t groundMat = addMaterial(scene, "bunny_ground", glm::vec3(0.3f), 0.0f, 0.12f);
    addInstance(scene, addMesh(scene, makeQuad({4.0f, 4.0f}, 4)), groundMat, glm::mat4(1.0f));
    const uint32_t bunnyMat = addMaterial(scene, "bunny", {0.62f, 0.56f, 0.5f}, 0.0f, 0.45f);
    addInstance(scene, addMesh(scene, makeBunnyMesh(1.0f)), bunnyMat, glm::mat4(1.0f));
    scene.light.direction = lightFrom(30.0f, 35.0f);
    setCamera(scene, makeCamera({-1.7f, 0.75f, 2.0f}, {0.0f, 0.4f, 0.0f}, 38.0f));
    return scene;
}

}  // namespace ssrt
