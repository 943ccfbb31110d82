// The Embree truth honours alpha cut-outs (truth/embree_scene.cpp's filter, the rule of
// scenes/material_alpha.h): first hits and shadow rays pass through the holes, an opaque
// instance of the same mesh stays whole, and the truth agrees with the rasterizer pixel by
// pixel, for camera rays over a slanted cut-out plane (perspective-correct UVs, clipped
// triangles) and for sun rays through a cut-out roof (the shadow map).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "renderer/renderer.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"
#include "world/embree_scene.h"

using namespace ssrt;
using namespace ssrt::helpers;

namespace {

constexpr int kTexels = 8;
bool solid(int x, int y) { return (x + y) % 2 == 0; }

// An 8 x 8 checker of alpha 1 (x + y even) and 0, grey.
Texture checker() {
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) texels.emplace_back(0.5f, 0.5f, 0.5f, solid(x, y));
    return Texture("checker", kTexels, kTexels, texels);
}

uint32_t addCutOutMaterial(Scene& s, uint32_t texture) {
    const uint32_t m = addMaterial(s, "cut-out", glm::vec3(1.0f), 0.0f, 1.0f, true);
    s.materials[m].alphaMode = Material::AlphaMode::Mask;
    s.materials[m].baseColorTexture = int32_t(texture);
    return m;
}

Frame render(const Scene& scene, int size) {
    RenderSettings rs;
    rs.width = rs.height = size;
    rs.shadowMapSize = 1024;
    rs.threads = 2;
    rs.trace.ssr = rs.trace.ssgi = false;
    return Renderer(rs).renderWithoutHistory(scene);
}

// The world-space ray through the centre of pixel (x, y) of a square image.
glm::vec3 cameraRay(const Camera& c, int x, int y, int size) {
    const glm::vec3 f = glm::normalize(c.target - c.position);
    const glm::vec3 r = glm::normalize(glm::cross(f, c.up));
    const glm::vec3 u = glm::cross(r, f);
    const float t = std::tan(glm::radians(c.fovY) * 0.5f);
    const float ndcX = 2.0f * (float(x) + 0.5f) / float(size) - 1.0f;
    const float ndcY = 1.0f - 2.0f * (float(y) + 0.5f) / float(size);
    return glm::normalize(f + r * (ndcX * t) + u * (ndcY * t));
}

}  // namespace

TEST_CASE("alpha truth: rays pass through the holes, an opaque instance of the mesh does not") {
    // One quad mesh (z = 0, UV (0, 0) top-left) twice: cut out at z = -2, opaque at z = -4.
    Scene s;
    Mesh quad;
    quad.positions = {{-2, 2, 0}, {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}};
    quad.normals.assign(4, {0, 0, 1});
    quad.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    s.textures.push_back(checker());
    const uint32_t mesh = addMesh(s, quad);
    addInstance(s, mesh, addCutOutMaterial(s, 0), translate({0, 0, -2}));
    addInstance(s, mesh, addMaterial(s, "opaque", glm::vec3(0.5f), 0.0f, 1.0f),
                translate({0, 0, -4}));
    const EmbreeScene e(s);
    std::vector<glm::vec3> origins, dirs;
    std::vector<uint32_t> expected;
    for (int ty = 0; ty < kTexels; ++ty)
        for (int tx = 0; tx < kTexels; ++tx) {
            CAPTURE(tx);
            CAPTURE(ty);
            // Straight down -Z through texel (tx, ty)'s centre.
            const glm::vec3 o(-2.0f + 0.5f * (tx + 0.5f), 2.0f - 0.5f * (ty + 0.5f), 1.0f);
            const EmbreeHit h = e.intersect(o - e.origin(), {0, 0, -1}, 0.0f, 100.0f);
            REQUIRE(h.hit);
            CHECK(h.instance == (solid(tx, ty) ? 0u : 1u));
            CHECK(h.t == doctest::Approx(solid(tx, ty) ? 3.0 : 5.0));
            // A shadow ray from between the quads toward +Z: blocked by the solid texels only.
            CHECK(e.occluded(o - glm::vec3(0, 0, 4) - e.origin(), {0, 0, 1}, 0.0f, 100.0f) ==
                  solid(tx, ty));
            origins.push_back(o - e.origin());
            dirs.emplace_back(0, 0, -1);
            expected.push_back(solid(tx, ty) ? 0u : 1u);
        }
    // Packets take the same filter.
    for (std::size_t i = 0; i < origins.size(); i += 16) {
        EmbreeHit hits[16];
        e.intersect16(16, &origins[i], &dirs[i], 0.0f, 100.0f, hits);
        for (int k = 0; k < 16; ++k) CHECK(hits[k].instance == expected[i + k]);
    }
}

TEST_CASE("alpha truth: camera rays over a slanted cut-out plane agree with the raster") {
    // A cut-out plane at y = 0 (UV = position / 4, repeated: half-unit texels) over a red
    // ground at y = -0.5, both far wider than the view, seen from 2 above looking down and
    // ahead: the texels shrink with distance (an affine UV would misplace them) and the
    // plane's triangles reach behind the camera (clipped).
    Scene s;
    s.textures.push_back(checker());
    Mesh plane = makeQuad({100.0f, 100.0f}, 1);
    for (std::size_t i = 0; i < plane.positions.size(); ++i)
        plane.uvs[i] = glm::vec2(plane.positions[i].x, plane.positions[i].z) / 4.0f;
    const uint32_t mesh = addMesh(s, plane);
    addInstance(s, mesh, addCutOutMaterial(s, 0), glm::mat4(1.0f));
    addInstance(s, mesh, addMaterial(s, "ground", {1, 0, 0}, 0.0f, 1.0f), translate({0, -0.5f, 0}));
    s.camera = makeCamera({0.3f, 2.0f, 0.0f}, {0.0f, 0.0f, -3.0f}, 60.0f);
    s.camera.farZ = 1000.0f;
    s.previousCamera = s.camera;
    constexpr int kSize = 128;
    const Frame f = render(s, kSize);
    CHECK(f.stats.visibility.trianglesClipped > 0);
    const EmbreeScene e(s);
    int counts[2] = {0, 0}, wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const EmbreeHit h = e.intersect(s.camera.position - e.origin(),
                                            cameraRay(s.camera, x, y, kSize), 0.0f, 1e4f);
            const float truth = h.hit ? float(h.instance) : -1.0f;
            const float raster = f.gbuffer.instanceId.at(x, y);
            wrong += !(truth == raster);
            if (raster >= 0.0f) ++counts[int(raster)];
        }
    MESSAGE("cut-out " << counts[0] << ", ground " << counts[1] << ", disagree " << wrong);
    // Both in view, in about equal shares; disagreement only where a pixel centre lies
    // within rounding of a texel edge (at a grazing angle a texel is a few pixels).
    CHECK(counts[0] > kSize * kSize / 3);
    CHECK(counts[1] > kSize * kSize / 3);
    CHECK(wrong <= kSize * kSize / 1000);
}

TEST_CASE("alpha truth: sun rays through a cut-out roof agree with the shadow map") {
    // A white floor (y = 0), the checker roof (y = 1, 2 x 2) and a sun from the side, slanted
    // so that the roof's shadow falls beside it; the camera looks down from above the roof.
    Scene s;
    s.textures.push_back(checker());
    const uint32_t white = addMaterial(s, "floor", glm::vec3(1.0f), 0.0f, 1.0f);
    addInstance(s, addMesh(s, makeQuad({4.0f, 4.0f}, 1)), white, glm::mat4(1.0f));
    addInstance(s, addMesh(s, makeQuad({1.0f, 1.0f}, 1)), addCutOutMaterial(s, 0),
                translate({0, 1, 0}));
    s.light.direction = glm::normalize(glm::vec3(0.6f, -1.0f, 0.2f));
    s.camera = makeCamera({0.6f, 5.0f, 0.2f}, {0.6f, 0.0f, 0.2f}, 40.0f);
    s.camera.up = {0, 0, -1};
    s.previousCamera = s.camera;
    constexpr int kSize = 128;
    const Frame f = render(s, kSize);
    const EmbreeScene e(s);
    int exact = 0, lit = 0, wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (f.gbuffer.instanceId.at(x, y) != 0.0f) continue;  // the floor's pixels only
            const float shadow = f.plane(Res::Shadow).at(x, y);
            if (shadow != 0.0f && shadow != 1.0f) continue;  // the filter's penumbra
            ++exact;
            lit += shadow == 1.0f;
            const glm::vec3 d = cameraRay(s.camera, x, y, kSize);
            const glm::vec3 p = s.camera.position + d * (-s.camera.position.y / d.y);
            const bool blocked = e.occluded(p - e.origin(), -s.light.direction, e.epsilon(), 1e4f);
            wrong += blocked == (shadow == 1.0f);
        }
    MESSAGE("floor pixels fully lit or shadowed " << exact << " (lit " << lit << "), disagree "
                                                  << wrong);
    CHECK(exact > kSize * kSize / 2);
    CHECK(exact - lit > 1000);  // the solid texels' shadow is in view
    CHECK(wrong <= exact / 200);
}
