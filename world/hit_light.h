// The light of a world-space hit, one point at a time: the direct pass's model
// (shading/direct_lanes.h, L = float: the very template the kernel runs) at any world point
// and view direction, with the sun's visibility from an Embree shadow ray or the frame's
// shadow map. The truth's reference image (truth/reference_image.h) lights its paths with it;
// it lives here, below the truth, so that the renderer's world-space rays can light theirs
// with the same code.
#pragma once

#include <glm/glm.hpp>

#include "shading/direct_kernel.h"
#include "shading/direct_lanes.h"
#include "world/embree_scene.h"

namespace ssrt {

// Where the sun's visibility at a point comes from: an Embree shadow ray, or the frame's own
// shadow map (which isolates the tracing's errors from the shadow map's).
enum class SunVisibility { Embree, ShadowMap };

namespace worldhit {

using PointSurface = shade::Surface<float>;

// What the shading of one pass needs: the direct pass's lighting set-up (with the frame's
// camera), the BVH and the visibility to use.
struct ShadingContext {
    const DirectArgs* lighting = nullptr;
    const EmbreeScene* embree = nullptr;
    SunVisibility visibility = SunVisibility::Embree;
};

// The surface a G-buffer pixel shows, as the direct kernel reconstructs it (the same float
// operations: the point is camPos + dirWorld viewZ, the view the reversed unit camera ray).
// Reads the DirectArgs' G-buffer pointers; viewZ must be > 0.
PointSurface pixelSurface(const DirectArgs& a, int x, int y);

// 1 when nothing lies between `origin` (already off the surface) and the sun, else 0.
float embreeSunVisibility(const ShadingContext& c, glm::vec3 origin);

// The sun's visibility at s: 0 when s faces away from the light; otherwise the chosen
// source, the Embree shadow ray leaving from `offsetOrigin` (a point off the surface along
// the geometric normal, on the viewer's side).
float sunVisibility(const ShadingContext& c, const PointSurface& s, glm::vec3 offsetOrigin);

// Radiance leaving a traced hit towards the ray's origin. full: the whole direct-pass colour
// ((sun + sky diffuse) + split-sum specular + emission, as the direct pass's `color`, without
// the Kulla-Conty factor, which `color` never has); otherwise the SSGI bounce's Lambert part
// of the sun plus emission (trace/ssgi.h). A back face of a single-sided material is black
// (the rasterizer culls it: light does not leave it).
glm::vec3 hitRadiance(const ShadingContext& c, glm::vec3 origin, glm::vec3 dir,
                      const EmbreeHit& hit, bool full);

// A hit of a diffuse path (the SSGI rays, and the further bounces of ReferenceSettings::
// bounces): the light it sends back along the ray in the SSGI model (hitRadiance's, full =
// false: the Lambert part of the sun with the chosen visibility, plus emission), and what the
// next bounce leaves from. A back face of a single-sided material is black and reflects
// nothing (reflectance 0 ends the path).
struct DiffuseVertex {
    glm::vec3 radiance{0.0f};
    // albedo (1 - metallic) occlusion: the share of its incoming light it reflects, as the
    // composite weighs SSGI (with cosine-sampled rays f_r cos / pdf is exactly this)
    glm::vec3 reflectance{0.0f};
    glm::vec3 origin{0.0f};                       // the hit stepped epsilon off, on the ray's side
    glm::vec3 normal{0.0f, 1.0f, 0.0f};           // shading normal, turned to the ray's side
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f};  // likewise
};
DiffuseVertex diffuseVertex(const ShadingContext& c, glm::vec3 origin, glm::vec3 dir,
                            const EmbreeHit& hit);

// The sky along a unit world direction (a ray that missed).
glm::vec3 missRadiance(const ShadingContext& c, glm::vec3 dir);

}  // namespace worldhit
}  // namespace ssrt
