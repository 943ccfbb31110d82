// Helpers for raster tests: triangles given in pixel coordinates, rasterized through the
// real front end (an orthographic view whose clip space is the screen).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "raster/raster.h"
#include "scenes/scene.h"

namespace ssrt::test {

struct PixelTri {
    glm::vec2 a, b, c;   // pixel coordinates, y down
    float depth = 0.5f;  // z01 (smaller is nearer)
};

struct RasterResult {
    VisibilityBuffer vb;
    RasterStats stats;
};

// One mesh, one instance, double-sided: every triangle is drawn whatever its winding.
inline Scene sceneFromPixelTris(const std::vector<PixelTri>& tris, int w, int h) {
    Scene s;
    Mesh m;
    auto ndc = [&](glm::vec2 p, float z) {
        return glm::vec3(2.0f * p.x / float(w) - 1.0f, 1.0f - 2.0f * p.y / float(h),
                         2.0f * z - 1.0f);
    };
    for (const PixelTri& t : tris) {
        for (glm::vec2 p : {t.a, t.b, t.c}) {
            m.indices.push_back(uint32_t(m.positions.size()));
            m.positions.push_back(ndc(p, t.depth));
            m.normals.push_back({0.0f, 0.0f, 1.0f});
        }
    }
    s.meshes.push_back(std::move(m));
    Material mat;
    mat.doubleSided = true;
    s.materials.push_back(mat);
    s.instances.push_back(Instance{});
    return s;
}

inline RasterResult rasterPixelTris(const std::vector<PixelTri>& tris, int w, int h,
                                    Isa isa = Isa::Scalar, int threads = 1) {
    const Scene scene = sceneFromPixelTris(tris, w, h);
    RasterView view;
    view.viewProj = glm::mat4(1.0f);
    view.width = w;
    view.height = h;
    view.perspective = false;
    RasterOptions o;
    o.isa = isa;
    o.threads = threads;
    RasterResult r;
    const TransformedVertices tv = transformVertices(scene, view, threads);
    r.vb = rasterize(scene, tv, view, o, r.stats);
    return r;
}

inline int coveredCount(const VisibilityBuffer& vb) {
    int n = 0;
    for (int y = 0; y < vb.ids.height(); ++y)
        for (int x = 0; x < vb.ids.width(); ++x) n += vb.ids.at(x, y) != kNoPrimitive;
    return n;
}

}  // namespace ssrt::test
