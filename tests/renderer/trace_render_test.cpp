// The screen-space passes inside the renderer: their planes agree with their counters, and
// reprojected SSR hits read the previous frame of a sequence.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

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
        // (Cornell's walls, roughness 0.9, are past the fade's end: no ray there.)
        CHECK(f.stats.ssr.rays.faded > 0);
        CHECK(ssr.rays + f.stats.ssr.rays.belowSurface + f.stats.ssr.rays.faded ==
              f.stats.ssr.rays.pixels);
        CHECK(f.stats.ssgi.rays.faded == 0);
        CHECK(ssr.laneActive <= ssr.laneSlots);
    }
}

TEST_CASE(
    "renderer: no SSR ray where the roughness fade hides it, and the image is the same there") {
    // Cornell's walls (roughness 0.9) are past the fade's end (0.7): their SSR opacity is 0
    // whatever a ray finds, so skipping their rays may change only the reuse resolve of a
    // smoother pixel beside them (it reads its 3x3 neighbours' rays).
    const Scene scene = makeBuiltinScene("cornell");
    for (const SsrResolveMode mode : {SsrResolveMode::Reuse, SsrResolveMode::Mip}) {
        CAPTURE(int(mode));
        RenderSettings skip = smallTraced(), traceAll = smallTraced();
        skip.trace.resolve.mode = traceAll.trace.resolve.mode = mode;
        skip.trace.ssrSpp = traceAll.trace.ssrSpp = 2;
        traceAll.trace.ssrTraceFaded = true;
        const Frame a = Renderer(skip).render(scene), b = Renderer(traceAll).render(scene);
        const PlaneF& rough = a.plane("roughness");
        const PlaneF& viewZ = a.plane("viewZ");
        const float end = skip.trace.resolve.roughnessFadeEnd;
        const auto isRough = [&](int x, int y) {
            return viewZ.at(x, y) > 0.0f && !(rough.at(x, y) < end);
        };
        uint64_t rougher = 0;
        int roughSame = 0, roughPixels = 0, farSame = 0, farPixels = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                bool nearRough = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int u = x + dx, v = y + dy;
                        if (u >= 0 && v >= 0 && u < a.width && v < a.height)
                            nearRough |= isRough(u, v);
                    }
                bool same = true;
                for (const char* p : {"color.R", "color.G", "color.B", "ssrOpacity"})
                    same &= std::memcmp(&a.plane(p).at(x, y), &b.plane(p).at(x, y), 4) == 0;
                if (isRough(x, y)) {
                    ++rougher;
                    ++roughPixels;
                    roughSame += same && a.plane("ssrOpacity").at(x, y) == 0.0f &&
                                 a.plane("ssrHit").at(x, y) == 0.0f;
                } else if (!nearRough || mode == SsrResolveMode::Mip) {
                    ++farPixels;
                    for (const char* p : {"ssr.R", "ssr.G", "ssr.B", "ssrHit", "ssrSteps"})
                        same &= std::memcmp(&a.plane(p).at(x, y), &b.plane(p).at(x, y), 4) == 0;
                    farSame += same;
                }
            }
        CHECK(roughPixels > 1000);
        CHECK(roughSame == roughPixels);
        CHECK(farPixels > 1000);
        CHECK(farSame == farPixels);
        CHECK(a.stats.ssr.rays.faded == rougher * 2);  // two samples
        CHECK(b.stats.ssr.rays.faded == 0);
        // The rough pixels' rays are all that is missing (some of them would have been
        // rejected below the surface anyway).
        CHECK(a.stats.ssr.march.rays < b.stats.ssr.march.rays);
        CHECK(b.stats.ssr.march.rays - a.stats.ssr.march.rays <= rougher * 2);
        CHECK(a.stats.ssr.rays.pixels == b.stats.ssr.rays.pixels);
        for (const char* p : {"ssgi.R", "ssgiHit", "ssgiSteps"})
            CHECK(test::sameBits(a.plane(p), b.plane(p)));
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
