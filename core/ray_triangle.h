// One ray against one triangle, exactly as ssrt computes it: the watertight test of Woop,
// Benthin and Wald ("Watertight Ray/Triangle Intersection", JCGT 2013). A ray that passes
// through an edge or a vertex shared by two triangles hits at least one of them, never falls
// between; the edge functions fall back to double precision where float gives exactly zero.
//
// Its answer is plain float arithmetic in a fixed order (correctly rounded operations only, no
// FMA: -ffp-contract=off), so it is the same bits on every ISA, compiler and machine. The
// world-space tracer (Embree, world/) decides which triangle a ray hits first; this says where
// (the distance and barycentrics the frame uses), so a frame's bits do not follow Embree's
// run-time kernels.
#pragma once

#include <glm/glm.hpp>

namespace ssrt {

// Where a ray meets a triangle's plane, with the barycentrics of that point:
// p = (1 - u - v) p0 + u p1 + v p2 (Embree's convention) and t along the ray's direction.
struct TriangleHit {
    bool hit = false;     // inside the triangle (edges and corners included) and t in [tnear, tfar]
    bool inside = false;  // inside the triangle, whatever t is
    bool planeMet = false;  // false: the ray lies in the plane (or the triangle is degenerate)
    float t = 0.0f;
    float u = 0.0f, v = 0.0f;
    bool frontFace = false;  // the ray meets the counter-clockwise side (against the normal)
};

// The ray origin + t direction (direction need not be unit; t is in its units) against the
// triangle p0 p1 p2. Both faces count. A triangle whose plane holds the ray (or a degenerate
// one) is missed, with planeMet false and t, u, v 0. Where `inside` is false, t, u and v are
// those of the plane's point (u and v then lie outside [0, 1] or sum past 1).
TriangleHit intersectTriangle(glm::vec3 origin, glm::vec3 direction, glm::vec3 p0, glm::vec3 p1,
                              glm::vec3 p2, float tnear, float tfar);

}  // namespace ssrt
