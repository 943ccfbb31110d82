#include "world/embree_world_rays.h"

#include <algorithm>
#include <stdexcept>

#include "core/ray_triangle.h"
#include "world/hit_light.h"

namespace ssrt {

WorldHit exactWorldHit(const EmbreeScene& embree, const WorldRay& ray, const EmbreeHit& hit) {
    WorldHit w;
    if (!hit.hit) return w;
    const std::array<glm::vec3, 3> p = embree.corners(hit.instance, hit.triangle);
    const TriangleHit e =
        intersectTriangle(ray.origin, ray.direction, p[0], p[1], p[2], ray.tnear, ray.tfar);
    w.hit = true;
    w.instance = hit.instance;
    w.triangle = hit.triangle;
    w.frontFace = e.frontFace;
    if (!e.planeMet) {
        // ssrt's test finds the ray in the triangle's plane (Embree met it edge on): the first
        // corner, at its distance along the ray.
        const glm::vec3 q = p[0] - ray.origin;
        w.t = std::clamp((q.x * ray.direction.x + q.y * ray.direction.y) + q.z * ray.direction.z,
                         ray.tnear, ray.tfar);
        return w;
    }
    w.t = std::clamp(e.t, ray.tnear, ray.tfar);
    float u = std::max(e.u, 0.0f), v = std::max(e.v, 0.0f);
    if (u + v > 1.0f) {
        const float s = u + v;
        u = u / s;
        v = v / s;
    }
    w.u = u;
    w.v = v;
    return w;
}

void EmbreeWorldRays::intersect(std::span<const WorldRay> rays, std::span<WorldHit> hits) const {
    if (hits.size() != rays.size())
        throw std::invalid_argument("EmbreeWorldRays::intersect: as many hits as rays");
    // In packets of 16 (Embree's native width with AVX-512; it splits them elsewhere): the
    // same first hits as one ray at a time.
    for (std::size_t i0 = 0; i0 < rays.size(); i0 += 16) {
        const int n = int(std::min<std::size_t>(16, rays.size() - i0));
        glm::vec3 o[16], d[16];
        float tnear[16], tfar[16];
        for (int k = 0; k < n; ++k) {
            const WorldRay& r = rays[i0 + k];
            o[k] = r.origin, d[k] = r.direction, tnear[k] = r.tnear, tfar[k] = r.tfar;
        }
        EmbreeHit found[16];
        embree_.intersect16(n, o, d, tnear, tfar, found);
        for (int k = 0; k < n; ++k) hits[i0 + k] = exactWorldHit(embree_, rays[i0 + k], found[k]);
    }
}

glm::vec3 EmbreeWorldRays::light(const WorldRay& ray, const WorldHit& hit,
                                 const DirectArgs& lighting, bool full) const {
    const worldhit::ShadingContext ctx{&lighting, &embree_, SunVisibility::ShadowMap};
    EmbreeHit h;
    h.hit = hit.hit;
    h.t = hit.t;
    h.instance = hit.instance;
    h.triangle = hit.triangle;
    h.u = hit.u;
    h.v = hit.v;
    return worldhit::hitRadiance(ctx, ray.origin, ray.direction, h, full);
}

bool EmbreeWorldRays::occluded(const WorldRay& ray) const {
    return embree_.occluded(ray.origin, ray.direction, ray.tnear, ray.tfar);
}

}  // namespace ssrt
