// A small rendered frame of a built-in scene with its Embree BVH, for the reference tests.
#pragma once

#include <string>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "truth/reference_image.h"
#include "world/embree_scene.h"

namespace ssrt::test {

// A 512-texel shadow map keeps the small frames fast; shadowMapSize 0 keeps the default.
inline RenderSettings referenceRigSettings(int width, int height, int threads, bool trace,
                                           int shadowMapSize = 512) {
    RenderSettings rs;
    rs.width = width;
    rs.height = height;
    rs.threads = threads;
    if (shadowMapSize > 0) rs.shadowMapSize = shadowMapSize;
    rs.trace.ssr = trace;
    rs.trace.ssgi = trace;
    return rs;
}

// Members in construction order: the BVH keeps a reference to the scene.
struct ReferenceRig {
    Scene scene;
    Renderer renderer;
    Frame frame;
    EmbreeScene embree;

    explicit ReferenceRig(const std::string& name, int width = 96, int height = 54, int threads = 0,
                          bool trace = true, int shadowMapSize = 512)
        : scene(makeBuiltinScene(name)),
          renderer(referenceRigSettings(width, height, threads, trace, shadowMapSize)),
          frame(renderer.renderWithoutHistory(scene)),
          embree(scene) {}

    ReferenceImage reference(
        int spp, ReferenceSettings::Visibility v = ReferenceSettings::Visibility::Embree) const {
        ReferenceSettings s;
        s.spp = spp;
        s.visibility = v;
        return renderReference(embree, renderer, frame, s);
    }
};

}  // namespace ssrt::test
