// Mesh builders (unit normals, outward counter-clockwise faces) and the built-in scenes.
#include <doctest/doctest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>

#include "scenes/builtin_scenes.h"
#include "scenes/mesh_builders.h"

using namespace ssrt;

namespace {

// Counts the broken vertices or triangles instead of asserting in the loop, so a failure
// reports how much is wrong without thousands of lines.
struct MeshCheck {
    int badNormalLength = 0;
    int inwardTriangles = 0;  // face normal (from winding) against the vertex normals
    int degenerateTriangles = 0;
};

// The face normal from the winding (counter-clockwise = front) must agree with every
// vertex normal of the triangle.
MeshCheck checkMesh(const Mesh& mesh) {
    MeshCheck check;
    for (const glm::vec3& n : mesh.normals)
        if (std::abs(glm::length(n) - 1.0f) > 1e-5f) ++check.badNormalLength;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t* i = &mesh.indices[3 * t];
        const glm::vec3 a = mesh.positions[i[0]], b = mesh.positions[i[1]];
        const glm::vec3 c = mesh.positions[i[2]];
        const glm::vec3 face = glm::cross(b - a, c - a);
        if (glm::length(face) == 0.0f) {
            ++check.degenerateTriangles;
            continue;
        }
        for (int k = 0; k < 3; ++k)
            if (!(glm::dot(face, mesh.normals[i[k]]) > 0.0f)) {
                ++check.inwardTriangles;
                break;
            }
    }
    return check;
}

// UVs are optional in the scene model (the scanned bunny has none); the builders make them.
void requireWellFormed(const Mesh& mesh, bool needsUvs = true) {
    REQUIRE(mesh.triangleCount() > 0);
    CHECK(mesh.normals.size() == mesh.positions.size());
    if (needsUvs || !mesh.uvs.empty()) CHECK(mesh.uvs.size() == mesh.positions.size());
    CHECK(mesh.indices.size() % 3 == 0);
    for (uint32_t i : mesh.indices) REQUIRE(i < mesh.positions.size());
    const MeshCheck check = checkMesh(mesh);
    CHECK(check.badNormalLength == 0);
    CHECK(check.inwardTriangles == 0);
    CHECK(check.degenerateTriangles == 0);
}

// Outward means away from the centre too, for convex shapes: a mesh whose normals and
// winding were both flipped would pass checkMesh but not this.
int countFacingCentre(const Mesh& mesh) {
    int bad = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t* i = &mesh.indices[3 * t];
        const glm::vec3 a = mesh.positions[i[0]], b = mesh.positions[i[1]];
        const glm::vec3 c = mesh.positions[i[2]];
        if (!(glm::dot(glm::cross(b - a, c - a), a + b + c) > 0.0f)) ++bad;
    }
    return bad;
}

}  // namespace

TEST_CASE("makeBox: 24 vertices, 12 outward triangles, flat unit normals") {
    const Mesh box = makeBox({0.5f, 1.0f, 2.0f});
    CHECK(box.positions.size() == 24);
    CHECK(box.triangleCount() == 12);
    requireWellFormed(box);
    CHECK(countFacingCentre(box) == 0);
    // Flat: each vertex normal is the face's axis, and the vertex lies on that face.
    for (std::size_t v = 0; v < box.positions.size(); ++v) {
        const glm::vec3 n = box.normals[v];
        CHECK(std::abs(n.x) + std::abs(n.y) + std::abs(n.z) == 1.0f);
        CHECK(glm::dot(box.positions[v], n) ==
              doctest::Approx(glm::dot(glm::vec3(0.5f, 1, 2), glm::abs(n))));
    }
}

TEST_CASE("makeQuad: XZ plane facing +Y") {
    const Mesh quad = makeQuad({2.0f, 1.0f}, 4);
    CHECK(quad.triangleCount() == 2 * 4 * 4);
    CHECK(quad.positions.size() == 5 * 5);
    requireWellFormed(quad);
    for (std::size_t t = 0; t < quad.triangleCount(); ++t) {
        const uint32_t* i = &quad.indices[3 * t];
        const glm::vec3 a = quad.positions[i[0]];
        const glm::vec3 face = glm::cross(quad.positions[i[1]] - a, quad.positions[i[2]] - a);
        REQUIRE(face.y > 0.0f);
    }
    for (const glm::vec3& p : quad.positions) {
        CHECK(p.y == 0.0f);
        CHECK(std::abs(p.x) <= 2.0f);
        CHECK(std::abs(p.z) <= 1.0f);
    }
}

TEST_CASE("makeUvSphere: normals are the normalized positions, faces outward") {
    const float radius = 1.5f;
    const Mesh sphere = makeUvSphere(radius, 24, 12);
    CHECK(sphere.triangleCount() == 2 * 24 * (12 - 1));
    requireWellFormed(sphere);
    CHECK(countFacingCentre(sphere) == 0);
    int off = 0;
    for (std::size_t v = 0; v < sphere.positions.size(); ++v) {
        const glm::vec3 d = glm::normalize(sphere.positions[v]) - sphere.normals[v];
        if (glm::length(d) > 1e-6f) ++off;
        if (std::abs(glm::length(sphere.positions[v]) - radius) > 1e-5f) ++off;
    }
    CHECK(off == 0);
    // The poles close the sphere: the first and last rings collapse onto them exactly.
    for (int c = 0; c <= 24; ++c) {
        CHECK(sphere.positions[c] == glm::vec3(0.0f, radius, 0.0f));
        CHECK(sphere.positions[12 * 25 + c] == glm::vec3(0.0f, -radius, 0.0f));
    }
}

TEST_CASE("makeTorusKnot: smooth unit normals, outward faces, closed seams") {
    const Mesh knot = makeTorusKnot(2, 3, 1.0f, 0.3f, 128, 16);
    CHECK(knot.triangleCount() == 2 * 128 * 16);
    requireWellFormed(knot);
    // Outward from the tube: each vertex sits `tube` away from the curve along its normal,
    // so stepping back along the normal must land on the same curve point for the whole ring.
    for (int s = 0; s < 128; s += 17) {
        const glm::vec3 centre0 = knot.positions[s * 17] - 0.3f * knot.normals[s * 17];
        for (int k = 1; k <= 16; ++k) {
            const std::size_t v = std::size_t(s) * 17 + std::size_t(k);
            const glm::vec3 centre = knot.positions[v] - 0.3f * knot.normals[v];
            REQUIRE(glm::length(centre - centre0) < 1e-5f);
        }
    }
    // The last ring (duplicated for UVs) sits exactly on the first: no crack at the seam.
    for (int k = 0; k <= 16; ++k) REQUIRE(knot.positions[128 * 17 + k] == knot.positions[k]);
}

TEST_CASE("mesh builders reject degenerate input") {
    CHECK_THROWS_AS(makeBox({-1.0f, 1.0f, 1.0f}), std::invalid_argument);
    CHECK_THROWS_AS(makeBox({1.0f, 0.0f, 1.0f}), std::invalid_argument);
    CHECK_THROWS_AS(makeQuad({1.0f, -1.0f}, 1), std::invalid_argument);
    CHECK_THROWS_AS(makeQuad({1.0f, 1.0f}, 0), std::invalid_argument);
    CHECK_THROWS_AS(makeUvSphere(1.0f, 2, 8), std::invalid_argument);
    CHECK_THROWS_AS(makeUvSphere(1.0f, 8, 1), std::invalid_argument);
    CHECK_THROWS_AS(makeUvSphere(-1.0f, 8, 8), std::invalid_argument);
    CHECK_THROWS_AS(makeUvSphere(NAN, 8, 8), std::invalid_argument);
    CHECK_THROWS_AS(makeTorusKnot(2, 3, 1.0f, 0.3f, 2, 8), std::invalid_argument);
    CHECK_THROWS_AS(makeTorusKnot(2, 3, 1.0f, 0.3f, 64, 2), std::invalid_argument);
    CHECK_THROWS_AS(makeTorusKnot(2, 3, 1.0f, -0.3f, 64, 8), std::invalid_argument);
    CHECK_THROWS_AS(makeTorusKnot(0, 3, 1.0f, 0.3f, 64, 8), std::invalid_argument);
    CHECK_NOTHROW(makeUvSphere(1.0f, 3, 2));
}

TEST_CASE("built-in scenes: default first, valid, still frames") {
    const auto& infos = builtinScenes();
    REQUIRE(infos.size() == 8);
    CHECK(infos[0].name == "cornell");
    CHECK(infos[1].name == "spheres");
    CHECK(infos[2].name == "thin");
    CHECK(infos[3].name == "corridor");
    CHECK(infos[4].name == "offscreen");
    CHECK(infos[5].name == "occluded");
    CHECK(infos[6].name == "bunny");
    CHECK(infos[7].name == "fence");
    for (const BuiltinSceneInfo& info : infos) {
        CAPTURE(info.name);
        CHECK(!info.description.empty());
        const Scene scene = makeBuiltinScene(info.name);
        CHECK(scene.name == info.name);
        CHECK_NOTHROW(scene.validate());
        CHECK(!scene.instances.empty());
        CHECK(scene.triangleCount() > 0);
        CHECK(std::abs(glm::length(scene.light.direction) - 1.0f) < 1e-6f);
        CHECK(scene.light.direction.y < 0.0f);  // light travels downward, onto the floor
        CHECK(scene.previousCamera.position == scene.camera.position);
        CHECK(scene.previousCamera.target == scene.camera.target);
        CHECK(scene.previousCamera.fovY == scene.camera.fovY);
        for (const Instance& inst : scene.instances)
            CHECK(inst.previousTransform == inst.transform);
        for (const Mesh& mesh : scene.meshes) {
            CAPTURE(mesh.name);
            requireWellFormed(mesh, false);
        }
        // The camera looks at the scene: the target lies within the scene's bounds.
        glm::vec3 lo, hi;
        scene.bounds(lo, hi);
        CHECK(glm::all(glm::lessThanEqual(lo, scene.camera.target)));
        CHECK(glm::all(glm::lessThanEqual(scene.camera.target, hi)));
    }
}

TEST_CASE("cornell: open front and top, mirror sphere and glossy floor") {
    const Scene scene = makeBuiltinScene("cornell");
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    // The camera stands outside the open front.
    CHECK(scene.camera.position.z > hi.z);
    bool mirror = false, glossy = false;
    for (const Material& m : scene.materials) {
        mirror |= m.metallic == 1.0f && m.roughness <= 0.05f;
        glossy |= m.metallic == 0.0f && m.roughness >= 0.1f && m.roughness <= 0.2f;
    }
    CHECK(mirror);
    CHECK(glossy);
    // Every wall and the floor face into the box (toward its middle, (0, 1, 0)).
    int wallsFacingIn = 0;
    for (const Instance& inst : scene.instances) {
        if (scene.meshes[inst.mesh].name != "quad") continue;
        const glm::vec3 n = glm::vec3(inst.transform * glm::vec4(0, 1, 0, 0));
        const glm::vec3 p = glm::vec3(inst.transform * glm::vec4(0, 0, 0, 1));
        CHECK(std::abs(glm::length(n) - 1.0f) < 1e-6f);
        if (glm::dot(n, glm::vec3(0, 1, 0) - p) > 0.0f) ++wallsFacingIn;
    }
    CHECK(wallsFacingIn == 4);  // floor, back, left, right
    // The light comes from the front (+Z side, where the camera is) toward the back.
    CHECK(scene.light.direction.z < 0.0f);
    // No ceiling to block the directional light: nothing lies above the walls' tops.
    CHECK(hi.y <= 2.0f + 1e-5f);
}

TEST_CASE("spheres: roughness runs 0 to 1 in a dielectric and a metal row") {
    const Scene scene = makeBuiltinScene("spheres");
    int dielectric = 0, metal = 0;
    float minR = 1.0f, maxR = 0.0f;
    for (const Instance& inst : scene.instances) {
        if (scene.meshes[inst.mesh].name != "uv_sphere") continue;
        const Material& m = scene.materials[inst.material];
        (m.metallic == 1.0f ? metal : dielectric) += 1;
        minR = std::min(minR, m.roughness);
        maxR = std::max(maxR, m.roughness);
    }
    CHECK(dielectric >= 4);
    CHECK(metal == dielectric);
    CHECK(minR == 0.0f);
    CHECK(maxR == 1.0f);
}

TEST_CASE("makeKnotScene: triangle count within 10% of the request") {
    for (int requested : {3700, 121000}) {
        CAPTURE(requested);
        const Scene scene = makeKnotScene(requested);
        CHECK_NOTHROW(scene.validate());
        CHECK(scene.previousCamera.position == scene.camera.position);
        const double n = double(scene.triangleCount());
        CHECK(std::abs(n - requested) <= 0.1 * requested);
    }
    CHECK_THROWS_AS(makeKnotScene(10), std::invalid_argument);
}

TEST_CASE("unknown scene names throw, naming the scene and the known ones") {
    try {
        makeBuiltinScene("cornel");
        FAIL("no exception for an unknown scene");
    } catch (const std::invalid_argument& e) {
        CHECK(std::string(e.what()) ==
              "unknown scene 'cornel'; did you mean cornell? (built-in scenes: cornell, spheres, "
              "thin, corridor, "
              "offscreen, occluded, bunny, fence)");
    }
}
