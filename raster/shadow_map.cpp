#include "raster/shadow_map.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace ssrt {

RasterView fitShadowView(const Scene& scene, int size, float& depthRange, float& texelSize) {
    const Bounds bounds = scene.bounds();
    const glm::vec3 lo = bounds.lo, hi = bounds.hi;
    const glm::vec3 center = bounds.centre();  // Scene::origin()
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    glm::vec3 dir = scene.light.direction;
    dir = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0.0f, -1.0f, 0.0f);
    const glm::vec3 up = std::fabs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    // Light view space about the centre, which is Scene::origin(): the map takes points
    // measured from it (RasterView::origin), precise wherever the scene is.
    const glm::mat4 view = glm::lookAt(-dir * (2.0f * radius), glm::vec3(0.0f), up);
    // Bounds of the box corners in light view space.
    glm::vec3 vlo(1e30f), vhi(-1e30f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        const glm::vec3 v =
            glm::vec3(view * glm::vec4(glm::vec3(glm::dvec3(corner) - glm::dvec3(center)), 1.0f));
        vlo = glm::min(vlo, v);
        vhi = glm::max(vhi, v);
    }
    // A margin so that nothing lands exactly on the far plane (depth key 0 = cleared).
    const float margin = 0.01f * radius;
    vlo -= glm::vec3(margin);
    vhi += glm::vec3(margin);
    const glm::mat4 proj = glm::ortho(vlo.x, vhi.x, vlo.y, vhi.y, -vhi.z, -vlo.z);
    depthRange = vhi.z - vlo.z;
    texelSize = std::max(vhi.x - vlo.x, vhi.y - vlo.y) / float(size);
    RasterView rv;
    rv.viewProj = proj * view;
    rv.origin = center;
    rv.width = rv.height = size;
    rv.perspective = false;
    rv.faces = Faces::All;  // every face casts a shadow
    return rv;
}

void renderShadowMap(const Scene& scene, int size, const RasterOptions& options, ShadowMap& sm,
                     RasterStats& stats, RasterTimes* times) {
    const RasterView view = fitShadowView(scene, size, sm.depthRange, sm.texelSize);
    sm.lightViewProj = view.viewProj;
    const TransformedVertices tv = transformVertices(scene, view, options.threads);
    RasterOptions o = options;
    o.writeIds = false;
    o.clearDepth = 0.0f;
    VisibilityBuffer vb;
    vb.depth = std::move(sm.depth);
    rasterize(scene, tv, view, o, vb, stats, times);
    sm.depth = std::move(vb.depth);
}

}  // namespace ssrt
