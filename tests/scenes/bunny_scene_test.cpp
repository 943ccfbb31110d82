// The bunny scene: the committed scan is the package's mesh (counts, indices, a closed
// outward surface), it stands on the ground in view, and it renders cleanly with its shadow.
#include "scenes/bunny_scene.h"

#include <doctest/doctest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "scenes/data/bunny_mesh.h"

using namespace ssrt;

namespace {

// The package's own counts (bunny@1.0.1; scripts/import-bunny.sh prints them).
constexpr std::size_t kVertices = 1839, kTriangles = 3674;

constexpr int kWidth = 160, kHeight = 90;

// Signed volume of a closed mesh, sum of a . (b x c) / 6 over its triangles, in double:
// positive when the triangles run counter-clockwise seen from outside.
double signedVolume(const Mesh& mesh) {
    double volume = 0.0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
        const glm::dvec3 b(mesh.positions[mesh.indices[3 * t + 1]]);
        const glm::dvec3 c(mesh.positions[mesh.indices[3 * t + 2]]);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return volume;
}

// The raw data as a mesh (the package's units), without normals.
Mesh rawBunny() {
    Mesh mesh;
    const auto xyz = data::bunnyPositions();
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
        mesh.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    mesh.indices.assign(data::bunnyIndices().begin(), data::bunnyIndices().end());
    return mesh;
}

uint32_t instanceNamed(const Scene& scene, const std::string& material) {
    uint32_t found = 0, count = 0;
    for (uint32_t i = 0; i < scene.instances.size(); ++i)
        if (scene.materials[scene.instances[i].material].name == material) found = i, ++count;
    REQUIRE(count == 1);
    return found;
}

void worldBounds(const Scene& scene, uint32_t instance, glm::vec3& lo, glm::vec3& hi) {
    const Instance& inst = scene.instances[instance];
    lo = glm::vec3(INFINITY);
    hi = glm::vec3(-INFINITY);
    for (const glm::vec3& p : scene.meshes[inst.mesh].positions) {
        const glm::vec3 w = glm::vec3(inst.transform * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
}

bool inView(const Camera& camera, float aspect, glm::vec3 p) {
    const glm::vec4 c = camera.projection(aspect) * camera.view() * glm::vec4(p, 1.0f);
    return c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && std::abs(c.z) <= c.w;
}

}  // namespace

TEST_CASE("bunny data: the package's 1839 vertices and 3674 triangles, indices in range") {
    const auto xyz = data::bunnyPositions();
    const auto indices = data::bunnyIndices();
    CHECK(xyz.size() == 3 * kVertices);
    CHECK(indices.size() == 3 * kTriangles);
    int notFinite = 0, outOfRange = 0;
    for (float v : xyz) notFinite += !std::isfinite(v);
    std::set<uint32_t> used;
    for (uint32_t i : indices) {
        outOfRange += i >= kVertices;
        used.insert(i);
    }
    CHECK(notFinite == 0);
    CHECK(outOfRange == 0);
    CHECK(used.size() == kVertices);  // no stray vertices
}

TEST_CASE("bunny data: one closed surface, counter-clockwise seen from outside") {
    const Mesh mesh = rawBunny();
    // Closed and consistently wound: every directed edge occurs once and so does its twin
    // (a flipped triangle would repeat a directed edge, a hole would leave one unpaired).
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
            ++edges[{mesh.indices[3 * t + k], mesh.indices[3 * t + (k + 1) % 3]}];
    int unpaired = 0;
    for (const auto& [edge, count] : edges) {
        const auto twin = edges.find({edge.second, edge.first});
        unpaired += count != 1 || twin == edges.end() || twin->second != 1;
    }
    CHECK(unpaired == 0);
    // One piece of genus 0 (a sphere's topology): V - E + F = 2, with E = directed / 2.
    const long euler =
        long(mesh.positions.size()) - long(edges.size() / 2) + long(mesh.triangleCount());
    CHECK(euler == 2);
    // Outward: a positive volume, and not a sliver of its bounding box.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 size = hi - lo;
    const double volume = signedVolume(mesh);
    CHECK(volume > 0.2 * double(size.x) * double(size.y) * double(size.z));
}

TEST_CASE("bunny mesh: scaled to its height, resting on y = 0, normals facing out") {
    const Mesh raw = rawBunny();
    const Mesh bunny = makeBunnyMesh(1.0f);
    REQUIRE(bunny.positions.size() == kVertices);
    REQUIRE(bunny.indices == raw.indices);
    REQUIRE(bunny.normals.size() == kVertices);
    glm::vec3 lo(INFINITY), hi(-INFINITY), rawLo(INFINITY), rawHi(-INFINITY);
    for (const glm::vec3& p : bunny.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    for (const glm::vec3& p : raw.positions) {
        rawLo = glm::min(rawLo, p);
        rawHi = glm::max(rawHi, p);
    }
    CHECK(lo.y == 0.0f);
    CHECK(hi.y == doctest::Approx(1.0f).epsilon(1e-6));
    CHECK(lo.x + hi.x == doctest::Approx(0.0f).epsilon(1e-6));
    CHECK(lo.z + hi.z == doctest::Approx(0.0f).epsilon(1e-6));
    // A uniform scale: the volume scales by its cube and keeps its sign.
    const double s = 1.0 / double(rawHi.y - rawLo.y);
    CHECK(signedVolume(bunny) == doctest::Approx(signedVolume(raw) * s * s * s).epsilon(1e-5));
    // Smooth normals agree with the winding at every corner of every triangle, so with the
    // positive volume above they point out of the surface.
    int badLength = 0, against = 0;
    for (const glm::vec3& n : bunny.normals)
        badLength += !(std::abs(glm::length(n) - 1.0f) <= 1e-5f);
    for (std::size_t t = 0; t < bunny.triangleCount(); ++t) {
        const uint32_t* i = &bunny.indices[3 * t];
        const glm::vec3 a = bunny.positions[i[0]];
        const glm::vec3 face = glm::cross(bunny.positions[i[1]] - a, bunny.positions[i[2]] - a);
        for (int k = 0; k < 3; ++k) against += !(glm::dot(face, bunny.normals[i[k]]) > 0.0f);
    }
    CHECK(badLength == 0);
    CHECK(against == 0);
    CHECK_THROWS_AS(makeBunnyMesh(0.0f), std::invalid_argument);
    CHECK_THROWS_AS(makeBunnyMesh(NAN), std::invalid_argument);
}

TEST_CASE("bunny scene: about 1 m tall, standing on the glossy ground, wholly in view") {
    const Scene scene = makeBuiltinScene("bunny");
    const uint32_t ground = instanceNamed(scene, "bunny_ground");
    const uint32_t bunny = instanceNamed(scene, "bunny");
    const Material& groundMat = scene.materials[scene.instances[ground].material];
    CHECK(groundMat.metallic == 0.0f);
    CHECK(groundMat.roughness <= 0.2f);  // glossy: a sharp highlight, a blurred reflection
    glm::vec3 groundLo, groundHi, lo, hi;
    worldBounds(scene, ground, groundLo, groundHi);
    worldBounds(scene, bunny, lo, hi);
    REQUIRE(groundLo.y == groundHi.y);  // flat, level
    CHECK(std::abs(lo.y - groundLo.y) <= 1e-5f);
    CHECK(hi.y - lo.y == doctest::Approx(1.0f).epsilon(0.05));
    // Its footprint, and room for its shadow, lie on the ground.
    CHECK(groundLo.x < lo.x - 1.0f);
    CHECK(groundLo.z < lo.z - 1.0f);
    CHECK(groundHi.x > hi.x + 1.0f);
    CHECK(groundHi.z > hi.z + 1.0f);
    // Every corner of its bounds is inside the frustum, at the CLI's 16:9 and the tests'.
    for (const float aspect : {1280.0f / 720.0f, float(kWidth) / float(kHeight)})
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
            CAPTURE(i);
            CHECK(inView(scene.camera, aspect, p));
        }
}

TEST_CASE("bunny scene renders finite: many small triangles seen, a shadow on the ground") {
    const Scene scene = makeBuiltinScene("bunny");
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.shadowMapSize = 512;
    const Frame frame = Renderer(settings).renderWithoutHistory(scene);
    for (const PlaneRef& p : frame.layers()) {
        int bad = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) bad += !std::isfinite(p.plane->at(x, y));
        CAPTURE(p.name);
        CHECK(bad == 0);
    }
    const float ground = float(instanceNamed(scene, "bunny_ground"));
    const float bunny = float(instanceNamed(scene, "bunny"));
    const PlaneF& ids = frame.gbuffer.instanceId;
    const PlaneF& triangles = frame.gbuffer.triangleId;
    const PlaneF& shadow = frame.plane(Res::Shadow);
    int bunnyPixels = 0, shadowedGround = 0, litGround = 0;
    std::set<float> bunnyTriangles;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float id = ids.at(x, y);
            if (id == bunny) {
                ++bunnyPixels;
                bunnyTriangles.insert(triangles.at(x, y));
            } else if (id == ground) {
                (shadow.at(x, y) < 0.5f ? shadowedGround : litGround) += 1;
            }
        }
    const int pixels = kWidth * kHeight;
    MESSAGE("bunny covers " << bunnyPixels << " of " << pixels << " pixels, "
                            << bunnyTriangles.size() << " of its triangles; ground in shadow "
                            << shadowedGround << ", lit " << litGround);
    CHECK(bunnyPixels > pixels / 20);
    CHECK(bunnyPixels < pixels / 2);
    // Small triangles: most pixels show a triangle of their own.
    CHECK(bunnyTriangles.size() > std::size_t(bunnyPixels) / 3);
    CHECK(shadowedGround > pixels / 50);
    CHECK(litGround > pixels / 5);
}
