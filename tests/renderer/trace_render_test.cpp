// The screen-space passes inside the renderer: their planes agree with their counters, and
// reprojected SSR hits read the previous frame of a sequence.
#include <doctest/doctest.h>

#include <cmath>

#include "plane_compare.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

RenderSettings smallTraced() {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 96;
    rs.shadowMapSize = 256;
    rs.threads = 2;
    return rs;
}

}  // namespace

TEST_CASE("renderer: trace planes agree with the trace counters") {
    for (const Marcher m : {Marcher::Linear, Marcher::Dda, Marcher::HiZ}) {
        CAPTURE(marcherName(m));
        RenderSettings rs = smallTraced();
        rs.trace.marcher = m;
        rs.trace.ssrSpp = 3;
        rs.trace.ssgiSpp = 2;
        const Frame f = Renderer(rs).render(makeBuiltinScene("cornell"));
        double ssrHits = 0, ssgiHits = 0, ssrSteps = 0;
        bool bounded = true, distanceOnlyOnHits = true;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const float hit = f.plane("ssrHit").at(x, y);
                const float opacity = f.plane("ssrOpacity").at(x, y);
                bounded &= hit >= 0.0f && hit <= 1.0f && opacity >= 0.0f && opacity <= 1.0f;
                distanceOnlyOnHits &= (hit > 0.0f) == (f.plane("ssrHitDistance").at(x, y) > 0.0f);
                ssrHits += double(hit) * rs.trace.ssrSpp;
                ssgiHits += double(f.plane("ssgiHit").at(x, y)) * rs.trace.ssgiSpp;
                ssrSteps += double(f.plane("ssrSteps").at(x, y)) * rs.trace.ssrSpp;
            }
        CHECK(bounded);
        CHECK(distanceOnlyOnHits);
        const MarchStats& ssr = f.stats.ssr.march;
        CHECK(f.stats.ssr.spp == 3);
        CHECK(ssr.ends[int(MarchEnd::Hit)] > 0);
        CHECK(std::llround(ssrHits) == int64_t(ssr.ends[int(MarchEnd::Hit)]));
        CHECK(std::llround(ssgiHits) == int64_t(f.stats.ssgi.march.ends[int(MarchEnd::Hit)]));
        CHECK(ssrSteps == doctest::Approx(double(ssr.steps)).epsilon(1e-5));
        // Every traced ray ends one way; rays never exceed the samples of surface pixels.
        uint64_t ended = 0;
        for (int e = 0; e < kMarchEndCount; ++e) ended += ssr.ends[e];
        CHECK(ended == ssr.rays);
        CHECK(ssr.rays + f.stats.ssr.rays.belowSurface == f.stats.ssr.rays.pixels);
        CHECK(ssr.laneActive <= ssr.laneSlots);
    }
}

TEST_CASE("renderer: reprojected SSR hits read the previous frame of a sequence") {
    const Scene scene = makeBuiltinScene("spheres");
    RenderSettings current = smallTraced(), reprojected = smallTraced();
    reprojected.trace.resolve.radiance = HitRadiance::Reprojected;
    Frame a, b;
    // The first frame has no previous one: reprojected falls back to the current frame.
    Renderer(current).render(scene, scene.camera, scene.camera, a);
    Renderer(reprojected).render(scene, scene.camera, scene.camera, b);
    CHECK(test::sameBits(a.plane("ssr.R"), b.plane("ssr.R")));
    // The second reads last frame's composite (SSR and SSGI included) instead of this
    // frame's direct light, so the reflections change while the G-buffer does not.
    Renderer(current).render(scene, scene.camera, scene.camera, a);
    Renderer(reprojected).render(scene, scene.camera, scene.camera, b);
    CHECK(test::sameBits(a.plane("viewZ"), b.plane("viewZ")));
    CHECK_FALSE(test::sameBits(a.plane("ssr.R"), b.plane("ssr.R")));
}
