#include "core/ray_triangle.h"

#include <cmath>
#include <utility>

namespace ssrt {

namespace {

// The three edge functions of the sheared triangle: e0 weighs p0, e1 p1, e2 p2.
struct Edges {
    float e0, e1, e2;
};

Edges edgeFunctions(float ax, float ay, float bx, float by, float cx, float cy) {
    Edges e{cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax};
    // A zero in float may be a sign lost to rounding: the paper's fallback decides it in double,
    // where the products of two floats are exact.
    if (e.e0 == 0.0f || e.e1 == 0.0f || e.e2 == 0.0f) {
        const auto d = [](float x) { return double(x); };
        e.e0 = float(d(cx) * d(by) - d(cy) * d(bx));
        e.e1 = float(d(ax) * d(cy) - d(ay) * d(cx));
        e.e2 = float(d(bx) * d(ay) - d(by) * d(ax));
    }
    return e;
}

}  // namespace

TriangleHit intersectTriangle(glm::vec3 origin, glm::vec3 direction, glm::vec3 p0, glm::vec3 p1,
                              glm::vec3 p2, float tnear, float tfar) {
    TriangleHit r;
    // Shear so that the ray runs along +z: kz is the direction's largest axis (the first on a
    // tie), kx and ky the others, swapped where the ray runs along -kz to keep the winding.
    const glm::vec3 ad = glm::abs(direction);
    const int kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
    if (direction[kz] == 0.0f) return r;
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (direction[kz] < 0.0f) std::swap(kx, ky);
    const float sx = direction[kx] / direction[kz];
    const float sy = direction[ky] / direction[kz];
    const float sz = 1.0f / direction[kz];

    const glm::vec3 a = p0 - origin, b = p1 - origin, c = p2 - origin;
    const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
    const Edges e = edgeFunctions(ax, ay, bx, by, cx, cy);
    const float det = e.e0 + e.e1 + e.e2;
    if (det == 0.0f || !std::isfinite(det)) return r;  // the plane holds the ray, or degenerate

    r.planeMet = true;
    const float tScaled = (e.e0 * (sz * a[kz]) + e.e1 * (sz * b[kz])) + e.e2 * (sz * c[kz]);
    // One division for the three (the paper's rcpDet): divisions are most of a scalar test's
    // latency.
    const float invDet = 1.0f / det;
    r.t = tScaled * invDet;
    r.u = e.e1 * invDet;
    r.v = e.e2 * invDet;
    const bool negative = e.e0 < 0.0f || e.e1 < 0.0f || e.e2 < 0.0f;
    const bool positive = e.e0 > 0.0f || e.e1 > 0.0f || e.e2 > 0.0f;
    r.inside = !(negative && positive);
    r.hit = r.inside && r.t >= tnear && r.t <= tfar;
    const glm::vec3 e01 = p1 - p0, e02 = p2 - p0;
    const glm::vec3 n{e01.y * e02.z - e01.z * e02.y, e01.z * e02.x - e01.x * e02.z,
                      e01.x * e02.y - e01.y * e02.x};
    r.frontFace = (direction.x * n.x + direction.y * n.y) + direction.z * n.z < 0.0f;
    return r;
}

}  // namespace ssrt
