// The Embree BVH of a scene (world/embree_scene.h) against analytic answers: a plane
// and a box face at the exact distance, a tessellated sphere within its sagitta, one mesh
// instanced twice, packets against single rays, shadow rays, the surface at a hit and the
// build statistics.
#include "world/embree_scene.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"

using namespace ssrt;
using namespace ssrt::helpers;

namespace {

// A small counter-based generator: the tests' random rays are the same on every run. Several
// draws in one vector are written in braces, glm::vec3{...}, which evaluate left to right;
// a constructor's parenthesised arguments are evaluated in an unspecified order (gcc and
// clang differ, and so did the rays).
struct TestRng {
    uint64_t state;
    float next() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(uint32_t(state >> 40)) / float(1u << 24);  // [0, 1)
    }
    glm::vec3 unitVector() {
        const float z = 2.0f * next() - 1.0f, phi = 6.2831853f * next();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
};

// The world point of a hit, from its named instance, triangle and barycentrics.
glm::vec3 barycentricPoint(const Scene& s, const EmbreeHit& h) {
    const Instance& inst = s.instances[h.instance];
    const Mesh& m = s.meshes[inst.mesh];
    const uint32_t* idx = &m.indices[3 * std::size_t(h.triangle)];
    glm::vec3 p(0.0f);
    const float w[3] = {1.0f - h.u - h.v, h.u, h.v};
    for (int c = 0; c < 3; ++c)
        p += w[c] * glm::vec3(inst.transform * glm::vec4(m.positions[idx[c]], 1.0f));
    return p;
}

// A floor quad at y = 0.5 (4 x 6 m, facing +Y) and a box 1 x 0.5 x 2 half-extents at x = 5.
Scene planeAndBoxScene() {
    Scene s;
    const uint32_t mat = addMaterial(s, "grey", glm::vec3(0.5f), 0.0f, 0.5f);
    addInstance(s, addMesh(s, makeQuad({2.0f, 3.0f}, 2)), mat, translate({0, 0.5f, 0}));
    addInstance(s, addMesh(s, makeBox({1.0f, 0.5f, 2.0f})), mat, translate({5.0f, 0, 0}));
    return s;
}

}  // namespace

TEST_CASE("embree scene: a ray to a plane and to a box face hits at the analytic distance") {
    const Scene s = planeAndBoxScene();
    const EmbreeScene e(s);
    TestRng rng{7};
    for (int i = 0; i < 200; ++i) {
        // Down onto the floor from 2 m above it, at random slants that stay on the quad.
        const glm::vec3 o{2.0f * rng.next() - 1.0f, 2.5f, 2.0f * rng.next() - 1.0f};
        const glm::vec3 d =
            glm::normalize(glm::vec3{0.8f * rng.next() - 0.4f, -1.0f, 0.8f * rng.next() - 0.4f});
        const EmbreeHit h = e.intersect(o - e.origin(), d, 0.0f, 100.0f);
        REQUIRE(h.hit);
        CHECK(h.instance == 0);
        const float t = 2.0f / -d.y;
        CHECK(std::abs(h.t - t) <= 1e-5f * t);
    }
    for (int i = 0; i < 200; ++i) {
        // Along -X onto the box's +X face (x = 6) from x = 9.
        const glm::vec3 o{9.0f, 0.4f * rng.next() - 0.2f, 3.0f * rng.next() - 1.5f};
        const glm::vec3 d =
            glm::normalize(glm::vec3{-1.0f, 0.1f * rng.next() - 0.05f, 0.1f * rng.next() - 0.05f});
        const EmbreeHit h = e.intersect(o - e.origin(), d, 0.0f, 100.0f);
        REQUIRE(h.hit);
        CHECK(h.instance == 1);
        const float t = 3.0f / -d.x;
        CHECK(std::abs(h.t - t) <= 1e-5f * t);
    }
    // Beyond tfar or before tnear: no hit.
    const glm::vec3 above = glm::vec3(0, 2.5f, 0) - e.origin();
    CHECK_FALSE(e.intersect(above, {0, -1, 0}, 0.0f, 1.99f).hit);
    CHECK_FALSE(e.intersect(above, {0, -1, 0}, 2.01f, 100.0f).hit);
    CHECK_FALSE(e.intersect(above, {0, 1, 0}, 0.0f, 100.0f).hit);
}

TEST_CASE("embree scene: a tessellated sphere is hit within its sagitta of the true sphere") {
    Scene s;
    const uint32_t mat = addMaterial(s, "grey", glm::vec3(0.5f), 0.0f, 0.5f);
    const float r = 1.5f;
    const int segments = 48, rings = 24;
    const glm::vec3 centre(0.3f, -0.2f, 0.7f);
    addInstance(s, addMesh(s, makeUvSphere(r, segments, rings)), mat, translate(centre));
    const EmbreeScene e(s);
    // Every vertex lies on the sphere, so every triangle is inside it, no farther from it than
    // r (1 - cos theta) with theta the angular half-diagonal of a 7.5 x 7.5 degree cell.
    const float dLon = 6.2831853f / float(segments), dLat = 3.1415927f / float(rings);
    const float sagitta = r * (1.0f - std::cos(0.5f * std::sqrt(dLon * dLon + dLat * dLat)));
    TestRng rng{11};
    for (int i = 0; i < 500; ++i) {
        // From 4 m out, aimed at a random point near the centre.
        const glm::vec3 o = centre + 4.0f * rng.unitVector();
        const glm::vec3 aim =
            centre + 0.5f * r * (glm::vec3{rng.next(), rng.next(), rng.next()} - 0.5f);
        const glm::vec3 d = glm::normalize(aim - o);
        const EmbreeHit h = e.intersect(o - e.origin(), d, 0.0f, 100.0f);
        REQUIRE(h.hit);
        // The true sphere along the same ray.
        const glm::vec3 oc = o - centre;
        const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - r * r;
        const float tSphere = -b - std::sqrt(b * b - c);
        const glm::vec3 p = o + h.t * d;
        const float radius = glm::length(p - centre);
        CHECK(h.t >= tSphere - 1e-5f);
        CHECK(radius <= r + 1e-5f);
        CHECK(radius >= r - sagitta - 1e-5f);
    }
    MESSAGE("sphere r = " << r << ", sagitta bound " << sagitta);
}

TEST_CASE("embree scene: a mesh instanced twice names the instance and triangle hit") {
    Scene s;
    const uint32_t mat = addMaterial(s, "grey", glm::vec3(0.5f), 0.0f, 0.5f);
    const uint32_t box = addMesh(s, makeBox({0.5f, 0.5f, 0.5f}));
    addInstance(s, box, mat, translate({-3.0f, 0, 0}));
    addInstance(s, box, mat,
                translate({3.0f, 1.0f, 0}) * rotate(30.0f, {0, 1, 0}) * glm::mat4(glm::mat3(2.0f)));
    const EmbreeScene e(s);
    TestRng rng{3};
    int hits[2] = {0, 0};
    for (int i = 0; i < 400; ++i) {
        // From 2.5 m out around each box (the other is 6 m away: never in between), aimed
        // inside it.
        const int which = i % 2;
        const glm::vec3 c = which == 0 ? glm::vec3(-3.0f, 0, 0) : glm::vec3(3.0f, 1.0f, 0);
        const glm::vec3 o = c + 2.5f * rng.unitVector();
        const glm::vec3 aim = c + 0.4f * (glm::vec3{rng.next(), rng.next(), rng.next()} - 0.5f);
        const glm::vec3 d = glm::normalize(aim - o);
        const EmbreeHit h = e.intersect(o - e.origin(), d, 0.0f, 100.0f);
        REQUIRE(h.hit);
        CHECK(h.instance == uint32_t(which));
        CHECK(h.triangle < 12);
        // The named triangle at the named barycentrics is the point at t.
        const glm::vec3 p = o + h.t * d;
        CHECK(glm::length(barycentricPoint(s, h) - p) <= 1e-4f);
        ++hits[h.instance == 1];
    }
    CHECK(hits[0] == 200);
    CHECK(hits[1] == 200);
}

TEST_CASE("embree scene: 16-ray packets give the single-ray answers") {
    Scene s = planeAndBoxScene();
    addInstance(s, addMesh(s, makeUvSphere(0.7f, 32, 16)), 0, translate({0, 1.5f, 0}));
    const EmbreeScene e(s);
    TestRng rng{5};
    int hitCount = 0;
    for (int packet = 0; packet < 200; ++packet) {
        const int n = 1 + packet % 16;  // every packet size
        glm::vec3 o[16], d[16];
        for (int k = 0; k < n; ++k) {
            o[k] = glm::vec3{8.0f * rng.next() - 4.0f, 3.0f * rng.next(), 8.0f * rng.next() - 4.0f};
            d[k] = rng.unitVector();
        }
        EmbreeHit packed[16];
        e.intersect16(n, o, d, 1e-3f, 50.0f, packed);
        for (int k = 0; k < n; ++k) {
            const EmbreeHit one = e.intersect(o[k], d[k], 1e-3f, 50.0f);
            REQUIRE(packed[k].hit == one.hit);
            if (!one.hit) continue;
            ++hitCount;
            CHECK(packed[k].instance == one.instance);
            CHECK(packed[k].triangle == one.triangle);
            CHECK(packed[k].t == doctest::Approx(one.t).epsilon(1e-6));
        }
    }
    CHECK(hitCount > 250);  // the rays met geometry, not only the sky (286 of 1668 hit)
    glm::vec3 o{0, 2.5f, 0}, d{0, -1, 0};
    EmbreeHit h;
    CHECK_THROWS_AS(e.intersect16(0, &o, &d, 0.0f, 1.0f, &h), std::invalid_argument);
    CHECK_THROWS_AS(e.intersect16(17, &o, &d, 0.0f, 1.0f, &h), std::invalid_argument);
}

TEST_CASE("embree scene: occluded() sees what lies within [tnear, tfar]") {
    const Scene s = planeAndBoxScene();
    const EmbreeScene e(s);
    // Positions go in measured from the scene's origin.
    const glm::vec3 o = glm::vec3(0.2f, 2.5f, -0.3f) - e.origin(), down(0, -1, 0);
    CHECK(e.occluded(o, down, 0.0f, 2.01f));
    CHECK_FALSE(e.occluded(o, down, 0.0f, 1.99f));
    CHECK_FALSE(e.occluded(o, down, 2.01f, 100.0f));
    CHECK_FALSE(e.occluded(o, -down, 0.0f, 100.0f));
    // Back faces count: from under the floor, upward.
    const glm::vec3 below = glm::vec3(0.2f, 0.0f, -0.3f) - e.origin();
    CHECK(e.occluded(below, -down, 0.0f, 1.0f));
    CHECK(e.intersect(below, -down, 0.0f, 1.0f).hit);
}

TEST_CASE("embree scene: the surface at a hit (position, normals, uv, textured material)") {
    Scene s;
    // A 2x2 texture, one colour (uv-independent): the base colour is factor times texel.
    s.textures.emplace_back("tex", 2, 2,
                            std::vector<glm::vec4>(4, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f)));
    s.textures.emplace_back("mr", 2, 2,
                            std::vector<glm::vec4>(4, glm::vec4(0.0f, 0.5f, 0.25f, 1.0f)));
    const uint32_t mat = addMaterial(s, "tex", {0.8f, 0.6f, 0.4f}, 1.0f, 0.8f, true);
    s.materials[mat].baseColorTexture = 0;
    s.materials[mat].metallicRoughnessTexture = 1;
    s.materials[mat].emissive = {0.1f, 0.2f, 0.3f};
    // The floor quad turned to face +Z (a wall at z = -2) and stretched 2x along X: the
    // normal matrix must keep the normal unit and along +Z.
    addInstance(
        s, addMesh(s, makeQuad({1.0f, 1.0f}, 1)), mat,
        translate({0, 0, -2.0f}) * rotate(90.0f, {1, 0, 0}) *
            glm::mat4(glm::mat3(glm::vec3(2, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1))));
    const EmbreeScene e(s);
    const glm::vec3 o(0.0f, 0.0f, 1.0f);
    const glm::vec3 target(1.2f, -0.4f, -2.0f);
    const glm::vec3 d = glm::normalize(target - o);
    const EmbreeHit h = e.intersect(o - e.origin(), d, 0.0f, 100.0f);
    REQUIRE(h.hit);
    const SurfacePoint p = e.surface(o - e.origin(), d, h);
    CHECK(glm::length(p.position + e.origin() - target) <= 1e-5f);  // from the origin
    CHECK(glm::length(p.geometricNormal - glm::vec3(0, 0, 1)) <= 1e-6f);
    CHECK(glm::length(p.shadingNormal - glm::vec3(0, 0, 1)) <= 1e-6f);
    CHECK(glm::dot(p.geometricNormal, d) < 0.0f);  // faces the ray: it is the front side
    // makeQuad's uv is ((x / hx + 1) / 2, (z / hz + 1) / 2) in its own frame; the rotation
    // about +X maps local z to world -y, the scale local x = world x / 2.
    CHECK(p.uv.x == doctest::Approx(0.5f * (0.6f + 1.0f)).epsilon(1e-5));
    CHECK(p.uv.y == doctest::Approx(0.5f * (0.4f + 1.0f)).epsilon(1e-5));
    CHECK(p.instance == 0);
    CHECK(p.material == mat);
    CHECK(glm::length(p.baseColor - glm::vec3(0.4f, 0.15f, 0.4f)) <= 1e-6f);
    CHECK(p.metallic == doctest::Approx(0.25f));
    CHECK(p.roughness == doctest::Approx(0.4f));
    CHECK(p.emissive == glm::vec3(0.1f, 0.2f, 0.3f));
    CHECK(p.doubleSided);
    // From behind, the geometric normal still names the front side (it faces along the ray).
    const glm::vec3 ob(0.5f, 0.3f, -3.0f), db(0, 0, 1);
    const EmbreeHit hb = e.intersect(ob, db, 0.0f, 100.0f);
    REQUIRE(hb.hit);
    const SurfacePoint pb = e.surface(ob, db, hb);
    CHECK(glm::dot(pb.geometricNormal, db) > 0.99f);
    CHECK(std::abs(glm::length(pb.shadingNormal) - 1.0f) <= 1e-6f);
}

TEST_CASE("embree scene: build statistics count instances, meshes and triangles") {
    Scene s = planeAndBoxScene();
    const uint32_t sphere = addMesh(s, makeUvSphere(0.5f, 16, 8));
    addMesh(s, makeBox({9.0f, 9.0f, 9.0f}));  // used by no instance: no BVH, no bounds
    addInstance(s, sphere, 0, translate({0, 3.0f, 0}));
    addInstance(s, sphere, 0, translate({0, 4.0f, 0}));
    const EmbreeScene e(s);
    const BvhStats& b = e.stats();
    CHECK(b.instances == 4);
    CHECK(b.meshes == 3);
    CHECK(b.triangles == s.triangleCount());
    CHECK(b.triangles == 8 + 12 + 2 * std::size_t(2 * 16 * 7));
    CHECK(b.bytes > 0);
    CHECK(b.buildMs >= 0.0);
    // Bounds: the floor's x from -2, the box's x to 6, the top sphere's top at 4.5.
    CHECK(b.lo.x == doctest::Approx(-2.0f));
    CHECK(b.hi.x == doctest::Approx(6.0f));
    CHECK(b.hi.y == doctest::Approx(4.5f));
    CHECK(b.diagonal == doctest::Approx(glm::length(b.hi - b.lo)));
    CHECK(e.epsilon() == doctest::Approx(1e-4f * b.diagonal));
    MESSAGE("BVH: " << b.instances << " instances, " << b.meshes << " meshes, " << b.triangles
                    << " triangles, " << b.bytes << " bytes, " << b.buildMs << " ms");
}

TEST_CASE("embree scene: a texture slot's UV transform moves where the texel is read") {
    Scene s;
    // 2x2 texels, clamped: texel (0, 0) centred at UV (0.25, 0.25).
    s.textures.emplace_back(
        "tex", 2, 2,
        std::vector<glm::vec4>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}});
    s.textures[0].wrapU = s.textures[0].wrapV = TextureWrap::ClampToEdge;
    const uint32_t mat = addMaterial(s, "tex", {1.0f, 1.0f, 1.0f}, 0.0f, 0.5f, true);
    s.materials[mat].baseColorTexture = 0;
    addInstance(
        s, addMesh(s, makeQuad({1.0f, 1.0f}, 1)), mat,
        translate({0, 0, -2.0f}) * rotate(90.0f, {1, 0, 0}) *
            glm::mat4(glm::mat3(glm::vec3(2, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1))));
    // The hit's UV is (0.8, 0.7) (as above); the offset takes it to (0.25, 0.25).
    s.materials[mat].baseColorUv.offset = {-0.55f, -0.45f};
    const EmbreeScene e(s);
    const glm::vec3 o(0.0f, 0.0f, 1.0f);
    const glm::vec3 d = glm::normalize(glm::vec3(1.2f, -0.4f, -2.0f) - o);
    const EmbreeHit h = e.intersect(o, d, 0.0f, 100.0f);
    REQUIRE(h.hit);
    const SurfacePoint p = e.surface(o, d, h);
    CHECK(glm::length(p.baseColor - glm::vec3(1.0f, 0.0f, 0.0f)) <= 1e-4f);
    // On the second UV set, (0.75, 0.25) everywhere, no offset: texel (1, 0).
    Scene s1 = s;
    s1.meshes[0].uvs1.assign(s1.meshes[0].positions.size(), glm::vec2(0.75f, 0.25f));
    s1.materials[mat].baseColorUv = UvTransform{};
    s1.materials[mat].baseColorUv.set = 1;
    const EmbreeScene e1(s1);
    const SurfacePoint p1 = e1.surface(o, d, e1.intersect(o, d, 0.0f, 100.0f));
    CHECK(p1.uv1 == glm::vec2(0.75f, 0.25f));
    CHECK(glm::length(p1.baseColor - glm::vec3(0.0f, 1.0f, 0.0f)) <= 1e-4f);
}
