// The shadow map of the directional light: an orthographic depth-only raster pass fitted to
// the scene's bounds.
#pragma once

#include <glm/glm.hpp>

#include "raster/raster.h"

namespace ssrt {

struct ShadowMap {
    PlaneF depth;                   // depth key 1 - z01: larger is nearer the light
    glm::mat4 lightViewProj{1.0f};  // of points measured from Scene::origin()
    float depthRange = 1.0f;        // world units spanned by the key's [0, 1]
    float texelSize = 1.0f;         // world units per texel (the larger of x and y)
};

// Light view and orthographic projection enclosing the scene's bounds (with a margin), about
// their centre (Scene::origin(), the view's origin).
RasterView fitShadowView(const Scene& scene, int size, float& depthRange, float& texelSize);

// Renders into `out`, reusing its depth plane when the size is right.
void renderShadowMap(const Scene& scene, int size, const RasterOptions& options, ShadowMap& out,
                     RasterStats& stats, RasterTimes* times = nullptr);

}  // namespace ssrt
