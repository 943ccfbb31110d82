// World-space rays for the screen-space passes: what a pass asks of a ray tracer over the
// scene when the screen cannot prove a ray's answer (mixed tracing) or is not asked (world
// tracing). The core library only declares it, so it builds and renders without Embree;
// world/ implements it with Embree (world/embree_world_rays.h).
//
// The contract that keeps frames deterministic: the tracer only chooses which triangle a ray
// meets first; where on it (t, u, v) is ssrt's own exact test (core/ray_triangle.h) on the
// triangle's corners, the same bits whatever kernels the tracer ran. Two triangles met at the
// very same distance (coincident or touching surfaces) remain the tracer's choice.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string_view>
#include <vector>

#include "shading/direct_kernel.h"

namespace ssrt {

// How a signal's rays are answered: screen (the march alone), mixed (the march where it proves
// its hit, trace/hit_proof.h; world rays for the rest), world (every ray in world space, the
// screen's light reused where a hit lands on a visible pixel).
enum class TraceMode { Screen, Mixed, World };
inline constexpr int kTraceModeCount = 3;
inline std::string_view traceModeName(TraceMode m) {
    switch (m) {
        case TraceMode::Screen: return "screen";
        case TraceMode::Mixed: return "mixed";
        case TraceMode::World: return "world";
    }
    return "?";
}

// What a signal's world stage did with its rays (renderer/world_stage.h), summed over a frame.
struct WorldRayStats {
    uint64_t proven = 0;  // march hits the proof holds (mixed): screen hits at their exact point
    uint64_t sent = 0;    // rays traced in world space
    uint64_t shown = 0;   // of those, hits a pixel shows: screen hits there
    uint64_t hidden = 0;  // hits no pixel shows (off the frame, or behind nearer surfaces)
    uint64_t missed = 0;  // nothing within the march's maximum distance
    void add(const WorldRayStats& o) {
        proven += o.proven, sent += o.sent, shown += o.shown, hidden += o.hidden,
            missed += o.missed;
    }
};

// Positions measured from the scene's origin (Scene::origin(), as every pass measures them);
// a unit direction; the interval of t searched.
struct WorldRay {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float tnear = 0.0f;
    float tfar = INFINITY;
};

// The first hit of a world ray: its instance (Scene::instances) and that instance's mesh's
// triangle, the distance and barycentrics, p = (1 - u - v) p0 + u p1 + v p2.
struct WorldHit {
    bool hit = false;
    bool frontFace = false;  // the ray meets the triangle's counter-clockwise side
    float t = 0.0f;
    uint32_t instance = 0, triangle = 0;
    float u = 0.0f, v = 0.0f;
};

// A world hit no pixel shows, lit at the hit (WorldRays::light): the signal's resolve takes
// its light from here instead of a pixel's (SsrResolver::setHit, SsgiArgs::lit).
struct WorldLit {
    int x, y;            // the ray's pixel in its batch's frame (the half frame's for SSGI's)
    glm::vec3 radiance;  // before the exposure
    glm::vec3 point;     // the hit in view space
};

// Mixed tracing's tile classifier's memory (renderer/world_stage.h, MixedTileClassifier): per tile
// of a signal's grid, the share of its rays the proof held the last time the tile was marched
// (-1: it had no ray).
struct MixedTiles {
    int tilesX = 0, tilesY = 0;
    std::vector<float> proven;
};

class WorldRays {
public:
    virtual ~WorldRays() = default;
    // The first hit of each ray (hits.size() == rays.size()). Both faces of every triangle count;
    // a point an alpha cut-out removes (scenes/material_alpha.h) does not. Thread-safe.
    virtual void intersect(std::span<const WorldRay> rays, std::span<WorldHit> hits) const = 0;
    // Whether anything lies on the ray within its interval (shadow rays). Thread-safe.
    virtual bool occluded(const WorldRay& ray) const = 0;
    // The light leaving a hit back along the ray, by the direct pass's model with its
    // lighting set-up (the sun through the frame's shadow map, the sky, emission): full, the
    // whole direct colour (a reflection's); otherwise the SSGI bounce's Lambert part of the sun
    // plus emission. Radiance before the exposure. Thread-safe.
    virtual glm::vec3 light(const WorldRay& ray, const WorldHit& hit, const DirectArgs& lighting,
                            bool full) const = 0;
};

}  // namespace ssrt
