// The world rays the screen-space passes will ask for (trace/world_rays.h) as Embree traces
// them (world/embree_world_rays.h): Embree's triangle, ssrt's exact distance and barycentrics,
// the same bits whichever kernels Embree runs.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/ray_triangle.h"
#include "scenes/builtin_scenes.h"
#include "world/embree_world_rays.h"

using namespace ssrt;

namespace {

// Rays as a pass would send them: from the camera, and from surface points the camera sees
// (a step off along the ray back) in random directions, as reflections and bounces leave.
std::vector<WorldRay> passLikeRays(const Scene& scene, const EmbreeScene& embree, int count) {
    std::mt19937 g(7u);
    const auto uniform = [&g] { return float(g() >> 8) * 0x1p-24f; };
    const auto unitVector = [&] {
        const float z = 2.0f * uniform() - 1.0f;
        const float phi = 6.2831853f * uniform();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3{r * std::cos(phi), r * std::sin(phi), z};
    };
    const glm::vec3 eye = scene.camera.position - embree.origin();
    const glm::vec3 forward = glm::normalize(scene.camera.target - scene.camera.position);
    std::vector<WorldRay> rays;
    while (int(rays.size()) < count) {
        WorldRay primary;
        primary.origin = eye;
        const glm::vec3 d = glm::normalize(forward + 0.6f * unitVector());
        primary.direction = d;
        rays.push_back(primary);
        const EmbreeHit h = embree.intersect(eye, d, 0.0f, INFINITY);
        if (!h.hit) continue;
        WorldRay bounce;
        bounce.origin = eye + h.t * d - embree.epsilon() * d;
        bounce.direction = unitVector();
        bounce.tnear = embree.epsilon();
        rays.push_back(bounce);
    }
    return rays;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("world rays: Embree's triangle, ssrt's exact distance and barycentrics") {
    for (const std::string name : {"cornell", "spheres", "corridor", "fence", "bunny"}) {
        CAPTURE(name);
        const Scene scene = makeBuiltinScene(name);
        const EmbreeScene embree(scene);
        const EmbreeWorldRays world(embree);
        const std::vector<WorldRay> rays = passLikeRays(scene, embree, 4000);
        std::vector<WorldHit> hits(rays.size());
        world.intersect(rays, hits);
        int hitCount = 0, inside = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const WorldRay& r = rays[i];
            const EmbreeHit e = embree.intersect(r.origin, r.direction, r.tnear, r.tfar);
            const WorldHit& w = hits[i];
            CAPTURE(i);
            REQUIRE(w.hit == e.hit);
            if (!e.hit) continue;
            ++hitCount;
            CHECK(w.instance == e.instance);
            CHECK(w.triangle == e.triangle);
            CHECK(w.t >= r.tnear);
            CHECK(std::fabs(w.t - e.t) <= 1e-5f * std::max(1.0f, e.t));
            // The barycentrics as the point they name, within 1e-6 of the scene's size.
            const std::array<glm::vec3, 3> c = embree.corners(e.instance, e.triangle);
            const auto at = [&c](float u, float v) {
                return (1.0f - u - v) * c[0] + u * c[1] + v * c[2];
            };
            CHECK(glm::length(at(w.u, w.v) - at(e.u, e.v)) <= 1e-6f * embree.stats().diagonal);
            CHECK(w.u >= 0.0f);
            CHECK(w.v >= 0.0f);
            CHECK(w.u + w.v <= 1.0f);
            // The answer is ssrt's own: the exact test on the triangle's corners, where it
            // agrees the point is inside (almost every hit; the rest sit on an edge).
            const std::array<glm::vec3, 3> p = embree.corners(e.instance, e.triangle);
            const TriangleHit x =
                intersectTriangle(r.origin, r.direction, p[0], p[1], p[2], r.tnear, r.tfar);
            if (x.hit) {
                ++inside;
                CHECK(sameBits(w.t, x.t));
                CHECK(sameBits(w.u, x.u));
                CHECK(sameBits(w.v, x.v));
                CHECK(w.frontFace == x.frontFace);
            }
        }
        CHECK(hitCount > 1500);
        CHECK(inside >= hitCount - hitCount / 200);  // at most 0.5 % on an edge
        MESSAGE(name << ": " << hitCount << " hits, " << hitCount - inside << " on an edge");
    }
}

TEST_CASE("world rays: one exact answer whichever kernels Embree runs") {
    // Embree's SSE2 kernels against the best this CPU has (AVX-512 or AVX2 on x86): its own
    // distances may differ in their last bits; the exact answers may not, where the two meet
    // the same triangle (two triangles at the very same distance are Embree's choice).
    for (const std::string name : {"cornell", "spheres", "bunny"}) {
        CAPTURE(name);
        const Scene scene = makeBuiltinScene(name);
        const EmbreeScene best(scene), sse2(scene, "isa=sse2");
        const std::vector<WorldRay> rays = passLikeRays(scene, best, 4000);
        std::vector<WorldHit> a(rays.size()), b(rays.size());
        EmbreeWorldRays(best).intersect(rays, a);
        EmbreeWorldRays(sse2).intersect(rays, b);
        int same = 0, otherTriangle = 0, embreeBitsDiffer = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const WorldRay& r = rays[i];
            REQUIRE(a[i].hit == b[i].hit);
            if (!a[i].hit) continue;
            CAPTURE(i);
            if (a[i].instance != b[i].instance || a[i].triangle != b[i].triangle) {
                // A tie: two triangles at the same distance (the shared edge of a quad's two
                // halves); each answer is exact on its own triangle.
                ++otherTriangle;
                CHECK(std::fabs(a[i].t - b[i].t) <= 1e-6f * a[i].t);
                continue;
            }
            CHECK(sameBits(a[i].t, b[i].t));
            CHECK(sameBits(a[i].u, b[i].u));
            CHECK(sameBits(a[i].v, b[i].v));
            same += sameBits(a[i].t, b[i].t) && sameBits(a[i].u, b[i].u);
            const EmbreeHit ea = best.intersect(r.origin, r.direction, r.tnear, r.tfar);
            const EmbreeHit eb = sse2.intersect(r.origin, r.direction, r.tnear, r.tfar);
            embreeBitsDiffer += !sameBits(ea.t, eb.t) || !sameBits(ea.u, eb.u);
        }
        CHECK(otherTriangle <= 2);
        MESSAGE(name << ": " << same << " hits the same bits, " << otherTriangle
                     << " on another triangle; Embree's own t or u differ on " << embreeBitsDiffer);
    }
}
