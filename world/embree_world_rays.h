// The screen-space passes' world rays (trace/world_rays.h) traced by Embree: Embree picks the
// triangle a ray meets first, ssrt's exact test (core/ray_triangle.h) says where on it, so a
// frame's bits follow ssrt's arithmetic, not the kernels Embree chose for this CPU.
#pragma once

#include "trace/world_rays.h"
#include "world/embree_scene.h"

namespace ssrt {

// Embree's hit made exact: t, u and v from intersectTriangle on the hit triangle's corners
// (EmbreeScene::corners). Where the two tests part at an edge (Embree's in the instance's own
// space says inside, ssrt's in world space a hair outside), the point is the plane's, its
// barycentrics clamped to 0 and scaled to sum to at most 1, and t kept inside the ray's interval. A
// ray in the triangle's plane (met edge on) takes the first corner.
WorldHit exactWorldHit(const EmbreeScene& embree, const WorldRay& ray, const EmbreeHit& hit);

class EmbreeWorldRays final : public WorldRays {
public:
    // Traces `embree`'s scene, which must outlive this.
    explicit EmbreeWorldRays(const EmbreeScene& embree) : embree_(embree) {}

    void intersect(std::span<const WorldRay> rays, std::span<WorldHit> hits) const override;
    bool occluded(const WorldRay& ray) const override;
    glm::vec3 light(const WorldRay& ray, const WorldHit& hit, const DirectArgs& lighting,
                    bool full) const override;

private:
    const EmbreeScene& embree_;
};

}  // namespace ssrt
