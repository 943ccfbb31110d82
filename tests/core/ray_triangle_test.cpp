#include "core/ray_triangle.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <random>

namespace ssrt {

namespace {

// Floats in [lo, hi) from a generator whose sequence the standard fixes (mt19937), so the
// cases are the same on every machine.
struct Draw {
    std::mt19937 g{12345u};
    float operator()(float lo, float hi) { return lo + (hi - lo) * float(g() >> 8) * 0x1p-24f; }
    glm::vec3 vec(float lo, float hi) {
        return {(*this)(lo, hi), (*this)(lo, hi), (*this)(lo, hi)};
    }
};

// Moller-Trumbore in double: the reference the float answers are held to.
struct Exact {
    bool planeMet = false;
    double t = 0.0, u = 0.0, v = 0.0;
};
Exact inDouble(glm::vec3 o, glm::vec3 d, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
    const glm::dvec3 O(o), D(d), P0(p0), E1 = glm::dvec3(p1) - P0, E2 = glm::dvec3(p2) - P0;
    const glm::dvec3 pv = glm::cross(D, E2);
    const double det = glm::dot(E1, pv);
    Exact r;
    if (det == 0.0) return r;
    const glm::dvec3 tv = O - P0;
    const glm::dvec3 qv = glm::cross(tv, E1);
    r.planeMet = true;
    r.u = glm::dot(tv, pv) / det;
    r.v = glm::dot(D, qv) / det;
    r.t = glm::dot(E2, qv) / det;
    return r;
}

constexpr float kInf = INFINITY;

}  // namespace

TEST_CASE("ray-triangle: t and barycentrics as double precision gives them") {
    Draw draw;
    int checked = 0, inside = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p0 = draw.vec(-1, 1), p1 = draw.vec(-1, 1), p2 = draw.vec(-1, 1);
        const glm::vec3 o = draw.vec(-4, 4);
        // Aim at a point of the triangle's plane, inside or a little outside.
        const float bu = draw(-0.2f, 1.0f), bv = draw(-0.2f, 1.0f - bu + 0.2f);
        const glm::vec3 target = (1.0f - bu - bv) * p0 + bu * p1 + bv * p2;
        const glm::vec3 d = glm::normalize(target - o);
        const Exact e = inDouble(o, d, p0, p1, p2);
        const TriangleHit h = intersectTriangle(o, d, p0, p1, p2, 0.0f, kInf);
        // Well conditioned only: the ray not near the plane, the point not near an edge.
        const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
        if (!e.planeMet || std::fabs(glm::dot(n, d)) < 0.05f) continue;
        const double w = 1.0 - e.u - e.v;
        const double margin = std::fmin(std::fmin(std::fabs(e.u), std::fabs(e.v)), std::fabs(w));
        if (margin < 1e-4) continue;
        ++checked;
        const bool trulyInside = e.u > 0.0 && e.v > 0.0 && w > 0.0;
        CAPTURE(i);
        REQUIRE(h.inside == trulyInside);
        REQUIRE(h.hit == (trulyInside && e.t >= 0.0));
        CHECK(std::fabs(h.t - e.t) <= 1e-5 * std::fmax(1.0, std::fabs(e.t)));
        // The barycentrics as the point they name (a sliver's barycentrics are ill-conditioned
        // along its thin side; the point is not): within 1e-6 of the distance, over the
        // cosine to the plane (measured: at most 1.8e-7 of it).
        const auto at = [&](double u, double v) {
            return (1.0 - u - v) * glm::dvec3(p0) + u * glm::dvec3(p1) + v * glm::dvec3(p2);
        };
        const double scale = std::fmax(1.0, e.t) / std::fabs(glm::dot(n, d));
        CHECK(glm::length(at(h.u, h.v) - at(e.u, e.v)) <= 1e-6 * scale);
        CHECK(std::fabs(h.u - e.u) <= 1e-4);
        CHECK(std::fabs(h.v - e.v) <= 1e-4);
        CHECK(h.frontFace == (glm::dot(glm::cross(p1 - p0, p2 - p0), d) < 0.0f));
        inside += trulyInside;
    }
    CHECK(checked > 15000);
    CHECK(inside > 5000);
}

TEST_CASE("ray-triangle: watertight, a ray through a shared edge or corner hits a triangle") {
    Draw draw;
    SUBCASE("the diagonal of a quad split in two") {
        int rays = 0;
        for (int i = 0; i < 20000; ++i) {
            const glm::vec3 a = draw.vec(-1, 1), b = draw.vec(-1, 1);  // the shared edge
            const glm::vec3 side = draw.vec(-1, 1);
            const glm::vec3 c = side, e = a + b - side;  // c and e on either side of a b
            const float s = draw(0.05f, 0.95f);
            const glm::vec3 onEdge = a + s * (b - a);
            const glm::vec3 o = draw.vec(-4, 4);
            const glm::vec3 d = onEdge - o;
            if (glm::length(d) < 1e-3f) continue;
            ++rays;
            // Both triangles counter-clockwise seen from the same side: a b c and b a e.
            const TriangleHit h1 = intersectTriangle(o, d, a, b, c, 0.0f, kInf);
            const TriangleHit h2 = intersectTriangle(o, d, b, a, e, 0.0f, kInf);
            CAPTURE(i);
            REQUIRE((h1.hit || h2.hit));
        }
        CHECK(rays > 19000);
    }
    SUBCASE("the corner of a fan of six") {
        for (int i = 0; i < 5000; ++i) {
            const glm::vec3 centre = draw.vec(-1, 1);
            const glm::vec3 axis = glm::normalize(draw.vec(-1, 1));
            const glm::vec3 t0 = glm::normalize(glm::cross(axis, glm::vec3(0.3f, 1.0f, 0.2f)));
            const glm::vec3 t1 = glm::cross(axis, t0);
            glm::vec3 rim[6];
            for (int k = 0; k < 6; ++k) {
                const float ang = float(k) * 1.0471976f + draw(-0.3f, 0.3f);
                rim[k] =
                    centre + std::cos(ang) * t0 + std::sin(ang) * t1 + draw(-0.2f, 0.2f) * axis;
            }
            const glm::vec3 o = centre + draw(0.5f, 3.0f) * axis + draw.vec(-0.3f, 0.3f);
            const glm::vec3 d = centre - o;
            bool any = false;
            for (int k = 0; k < 6; ++k)
                any = any ||
                      intersectTriangle(o, d, centre, rim[k], rim[(k + 1) % 6], 0.0f, kInf).hit;
            CAPTURE(i);
            REQUIRE(any);
        }
    }
}

TEST_CASE("ray-triangle: faces, the ray's interval and degenerate cases") {
    const glm::vec3 p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0};  // counter-clockwise seen from +z
    SUBCASE("both faces, told apart") {
        const TriangleHit front =
            intersectTriangle({0.25f, 0.25f, 2}, {0, 0, -1}, p0, p1, p2, 0, kInf);
        const TriangleHit back =
            intersectTriangle({0.25f, 0.25f, -2}, {0, 0, 1}, p0, p1, p2, 0, kInf);
        CHECK(front.hit);
        CHECK(front.frontFace);
        CHECK(back.hit);
        CHECK_FALSE(back.frontFace);
        CHECK(front.t == 2.0f);
        CHECK(front.u == 0.25f);
        CHECK(front.v == 0.25f);
        CHECK(back.t == 2.0f);
    }
    SUBCASE("t in the ray's units, inside [tnear, tfar] only") {
        const TriangleHit h = intersectTriangle({0.5f, 0.25f, 4}, {0, 0, -2}, p0, p1, p2, 0, kInf);
        CHECK(h.t == 2.0f);
        CHECK(h.u == 0.5f);
        CHECK(h.v == 0.25f);
        CHECK(intersectTriangle({0.5f, 0.25f, 4}, {0, 0, -2}, p0, p1, p2, 0, 2.0f).hit);
        CHECK_FALSE(intersectTriangle({0.5f, 0.25f, 4}, {0, 0, -2}, p0, p1, p2, 0, 1.999f).hit);
        CHECK_FALSE(intersectTriangle({0.5f, 0.25f, 4}, {0, 0, -2}, p0, p1, p2, 2.001f, kInf).hit);
        // Behind the origin: the plane is met at negative t, inside, not a hit.
        const TriangleHit behind =
            intersectTriangle({0.2f, 0.2f, 1}, {0, 0, 1}, p0, p1, p2, 0, kInf);
        CHECK(behind.inside);
        CHECK_FALSE(behind.hit);
        CHECK(behind.t == -1.0f);
    }
    SUBCASE("outside: the plane's point, barycentrics outside") {
        const TriangleHit h = intersectTriangle({0.8f, 0.8f, 1}, {0, 0, -1}, p0, p1, p2, 0, kInf);
        CHECK_FALSE(h.hit);
        CHECK_FALSE(h.inside);
        CHECK(h.planeMet);
        CHECK(h.t == 1.0f);
        CHECK(h.u + h.v > 1.0f);
    }
    SUBCASE("edges and corners count") {
        CHECK(intersectTriangle({0.5f, 0.0f, 1}, {0, 0, -1}, p0, p1, p2, 0, kInf).hit);
        CHECK(intersectTriangle({0.5f, 0.5f, 1}, {0, 0, -1}, p0, p1, p2, 0, kInf).hit);
        CHECK(intersectTriangle({1.0f, 0.0f, 1}, {0, 0, -1}, p0, p1, p2, 0, kInf).hit);
        CHECK(intersectTriangle({0.0f, 0.0f, 1}, {0, 0, -1}, p0, p1, p2, 0, kInf).hit);
        CHECK_FALSE(intersectTriangle({0.5f, -1e-6f, 1}, {0, 0, -1}, p0, p1, p2, 0, kInf).hit);
    }
    SUBCASE("a ray in the plane, a degenerate triangle, no direction") {
        const TriangleHit inPlane =
            intersectTriangle({-1, 0.25f, 0}, {1, 0, 0}, p0, p1, p2, 0, kInf);
        const TriangleHit flat =
            intersectTriangle({0.25f, 0.25f, 1}, {0, 0, -1}, p0, p1, {2, 0, 0}, 0, kInf);
        const TriangleHit still =
            intersectTriangle({0.25f, 0.25f, 1}, {0, 0, 0}, p0, p1, p2, 0, kInf);
        for (const TriangleHit& h : {inPlane, flat, still}) {
            CHECK_FALSE(h.hit);
            CHECK_FALSE(h.planeMet);
            CHECK(h.t == 0.0f);
        }
    }
}

}  // namespace ssrt
