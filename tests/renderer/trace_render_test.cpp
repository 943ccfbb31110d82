// The screen-space passes inside the renderer: their planes agree with their counters, and
// reprojected SSR hits read the previous frame of a sequence.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include "plane_compare.h"
#include "renderer/renderer.h"
#include "renderer/trace_pass.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

RenderSettings smallTraced() {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 96;
    rs.shadowMapSize = 256;
    rs.threads = 2;
    // Every pixel traced (the ultra preset): these tests count rays per pixel
    // (tests/trace/trace_layout_test.cpp has the cut layouts').
    rs.trace.ssrLayout = rs.trace.ssgiLayout = TraceLayout::Full;
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
        const Frame f = Renderer(rs).renderWithoutHistory(makeBuiltinScene("cornell"));
        double ssrHits = 0, ssgiHits = 0, ssrSteps = 0;
        bool bounded = true, distanceOnlyOnHits = true;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const float hit = f.plane(Res::SsrHit).at(x, y);
                const float opacity = f.plane(Res::SsrOpacity).at(x, y);
                bounded &= hit >= 0.0f && hit <= 1.0f && opacity >= 0.0f && opacity <= 1.0f;
                distanceOnlyOnHits &=
                    (hit > 0.0f) == (f.plane(Res::SsrHitDistance).at(x, y) > 0.0f);
                const float ssgiHit = f.plane(Res::SsgiHit).at(x, y);
                distanceOnlyOnHits &=
                    (ssgiHit > 0.0f) == (f.plane(Res::SsgiHitDistance).at(x, y) > 0.0f);
                ssrHits += double(hit) * rs.trace.ssrSpp;
                ssgiHits += double(f.plane(Res::SsgiHit).at(x, y)) * rs.trace.ssgiSpp;
                ssrSteps += double(f.plane(Res::SsrSteps).at(x, y)) * rs.trace.ssrSpp;
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
        // (No SSR ray on cornell's walls, roughness 0.9, past the fade's end; no SSGI ray on
        // its mirror, metallic 1.)
        for (const TraceStats* t : {&f.stats.ssr, &f.stats.ssgi}) {
            CHECK(t->rays.hidden > 0);
            // (pixels: summed over the samples, as the others)
            CHECK(t->march.rays + t->rays.belowSurface + t->rays.hidden == t->rays.pixels);
        }
        CHECK(f.stats.ssr.rays.hidden > f.stats.ssgi.rays.hidden);
        CHECK(ssr.laneActive <= ssr.laneSlots);
    }
}

TEST_CASE("renderer: no ray where the composite hides what it finds, and the image is the same") {
    // Cornell: the walls (roughness 0.9) are past the SSR fade's end (0.7), so their SSR
    // opacity is 0 whatever a ray finds; the mirror (metallic 1) has no diffuse colour to
    // multiply SSGI by. Skipping those rays may change only the SSR reuse resolve of a
    // smoother pixel beside a rough one (it reads its 3x3 neighbours' rays).
    const Scene scene = makeBuiltinScene("cornell");
    for (const SsrResolveMode mode : {SsrResolveMode::Reuse, SsrResolveMode::Mip}) {
        CAPTURE(int(mode));
        RenderSettings skip = smallTraced(), traceAll = smallTraced();
        skip.trace.resolve.mode = traceAll.trace.resolve.mode = mode;
        skip.trace.ssrSpp = traceAll.trace.ssrSpp = 2;
        traceAll.trace.traceHidden = true;
        // The denoiser's kernels reach tens of pixels, past the 3x3 this test sets aside
        // (its own tests: tests/denoise/).
        skip.trace.denoise.enabled = traceAll.trace.denoise.enabled = false;
        const Frame a = Renderer(skip).renderWithoutHistory(scene),
                    b = Renderer(traceAll).renderWithoutHistory(scene);
        const PlaneF& viewZ = a.gbuffer.viewZ;
        const float end = skip.trace.resolve.roughnessFadeEnd;
        const auto isRough = [&](int x, int y) {
            return viewZ.at(x, y) > 0.0f && !(a.gbuffer.roughness.at(x, y) < end);
        };
        const auto isMetal = [&](int x, int y) {
            const float keep = 1.0f - a.gbuffer.metallic.at(x, y);
            return viewZ.at(x, y) > 0.0f && a.gbuffer.albedo[0].at(x, y) * keep == 0.0f &&
                   a.gbuffer.albedo[1].at(x, y) * keep == 0.0f &&
                   a.gbuffer.albedo[2].at(x, y) * keep == 0.0f;
        };
        // The same plane of both frames, by member.
        const auto same = [&](auto member, int x, int y) {
            return std::memcmp(&member(a).at(x, y), &member(b).at(x, y), 4) == 0;
        };
        const auto color = [](int c) {
            return [c](const Frame& f) -> auto& { return f.rgb(Res::Color)[c]; };
        };
        const auto ssrOpacity = [](const Frame& f) -> auto& { return f.plane(Res::SsrOpacity); };
        const auto ssrR = [](const Frame& f) -> auto& { return f.rgb(Res::Ssr)[0]; };
        const auto ssrHit = [](const Frame& f) -> auto& { return f.plane(Res::SsrHit); };
        const auto ssrSteps = [](const Frame& f) -> auto& { return f.plane(Res::SsrSteps); };
        const auto ssgiR = [](const Frame& f) -> auto& { return f.rgb(Res::Ssgi)[0]; };
        const auto ssgiHit = [](const Frame& f) -> auto& { return f.plane(Res::SsgiHit); };
        const auto ssgiSteps = [](const Frame& f) -> auto& { return f.plane(Res::SsgiSteps); };
        uint64_t rough = 0, metal = 0;
        int imageKept = 0, imagePixels = 0, ssrKept = 0, ssrPixels = 0, ssgiKept = 0;
        int hiddenEmpty = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                bool nearRough = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int u = x + dx, v = y + dy;
                        if (u >= 0 && v >= 0 && u < a.width && v < a.height)
                            nearRough |= isRough(u, v);
                    }
                rough += isRough(x, y);
                metal += isMetal(x, y);
                // The image: wherever no smoother pixel borrowed a skipped SSR ray.
                if (isRough(x, y) || !nearRough || mode == SsrResolveMode::Mip) {
                    ++imagePixels;
                    imageKept += same(color(0), x, y) && same(color(1), x, y) &&
                                 same(color(2), x, y) && same(ssrOpacity, x, y);
                }
                // SSR's own planes away from the rough pixels.
                if (!isRough(x, y) && (!nearRough || mode == SsrResolveMode::Mip)) {
                    ++ssrPixels;
                    ssrKept += same(ssrR, x, y) && same(ssrHit, x, y) && same(ssrSteps, x, y);
                }
                // SSGI borrows nothing from neighbours: every pixel with a diffuse colour.
                if (!isMetal(x, y))
                    ssgiKept += same(ssgiR, x, y) && same(ssgiHit, x, y) && same(ssgiSteps, x, y);
                hiddenEmpty += isRough(x, y) && a.plane(Res::SsrOpacity).at(x, y) == 0.0f &&
                               a.plane(Res::SsrHit).at(x, y) == 0.0f;
                hiddenEmpty += isMetal(x, y) && a.rgb(Res::Ssgi)[0].at(x, y) == 0.0f &&
                               a.plane(Res::SsgiHit).at(x, y) == 0.0f;
            }
        CHECK(rough > 1000);
        CHECK(metal > 100);
        CHECK(imagePixels > 10000);
        CHECK(imageKept == imagePixels);
        CHECK(ssrPixels > 1000);
        CHECK(ssrKept == ssrPixels);
        CHECK(ssgiKept == a.width * a.height - int(metal));
        CHECK(hiddenEmpty == int(rough + metal));
        CHECK(a.stats.ssr.rays.hidden == rough * 2);  // two samples
        CHECK(a.stats.ssgi.rays.hidden == metal);
        CHECK(b.stats.ssr.rays.hidden == 0);
        CHECK(b.stats.ssgi.rays.hidden == 0);
        // The hidden pixels' rays are all that is missing (some of the SSR ones would have
        // been rejected below the surface anyway).
        CHECK(a.stats.ssr.march.rays < b.stats.ssr.march.rays);
        CHECK(b.stats.ssr.march.rays - a.stats.ssr.march.rays <= rough * 2);
        CHECK(b.stats.ssgi.march.rays - a.stats.ssgi.march.rays == metal);
    }
}

TEST_CASE("renderer: reprojected SSR hits read the previous frame of a sequence") {
    const Scene scene = makeBuiltinScene("spheres");
    RenderSettings current = smallTraced(), reprojected = smallTraced();
    reprojected.trace.resolve.radiance = HitRadiance::Reprojected;
    const Renderer rc(current), rr(reprojected);
    FrameInput input = FrameInput::still(scene);
    input.previousCamera = input.camera;
    Frame a, b;
    FrameHistory ha, hb;
    // The first frame has no previous one: reprojected falls back to the current frame.
    rc.render(scene, input, ha, a);
    rr.render(scene, input, hb, b);
    CHECK(test::sameBits(a.rgb(Res::Ssr)[0], b.rgb(Res::Ssr)[0]));
    // Only what the next frame reads is committed.
    CHECK_FALSE(ha.valid);
    REQUIRE(hb.valid);
    CHECK(test::sameBits(hb.color[0], b.rgb(Res::Color)[0]));
    // The second reads last frame's composite (SSR and SSGI included) instead of this
    // frame's direct light, so the reflections change while the G-buffer does not.
    rc.render(scene, input, ha, a);
    rr.render(scene, input, hb, b);
    CHECK(test::sameBits(a.gbuffer.viewZ, b.gbuffer.viewZ));
    CHECK_FALSE(test::sameBits(a.rgb(Res::Ssr)[0], b.rgb(Res::Ssr)[0]));
    const PlaneF second = b.rgb(Res::Ssr)[0].clone();
    // The same history given again gives the same frame (nothing else is kept); a reset, and
    // a frame without history, give the first frame's bits.
    FrameHistory replay;
    rr.render(scene, input, replay, b);  // commits the first frame again
    rr.render(scene, input, replay, b);
    CHECK(test::sameBits(b.rgb(Res::Ssr)[0], second));
    FrameInput cut = input;
    cut.resetHistory = true;
    rr.render(scene, cut, replay, b);
    CHECK(
        test::sameBits(a.rgb(Res::Ssr)[0], rc.renderWithoutHistory(scene, input).rgb(Res::Ssr)[0]));
    const Frame still = rr.renderWithoutHistory(scene, input);
    CHECK(test::sameBits(b.rgb(Res::Ssr)[0], still.rgb(Res::Ssr)[0]));
    // A history of another size is not read.
    RenderSettings wider = reprojected;
    wider.width += 8;
    FrameHistory other;
    Renderer(wider).render(scene, input, other, b);
    rr.render(scene, input, other, b);
    CHECK(test::sameBits(b.rgb(Res::Ssr)[0], still.rgb(Res::Ssr)[0]));
}

// The trace passes run tile by tile (trace/tile_chain.h) unless an observer asks for the frame's
// rays and march results, when they run stage by stage over the frame: the two give the same
// bits and the same counters, for every marcher, layout, resolve mode and sample count, on a
// frame whose size is not a whole number of tiles. (The half layout's SSGI is observed on the
// half frame's batches.)
TEST_CASE("renderer: the trace passes tile by tile give the stage-by-stage bits") {
    const Scene scene = makeBuiltinScene("spheres");
    struct Case {
        Marcher marcher;
        TraceLayout layout, ssgiLayout;
        SsrResolveMode mode;
        int spp;
    };
    using L = TraceLayout;
    using M = SsrResolveMode;
    for (const Case k : {Case{Marcher::HiZ, L::Checkerboard, L::Full, M::Reuse, 1},
                         Case{Marcher::Dda, L::Full, L::Checkerboard, M::Reuse, 2},
                         Case{Marcher::Linear, L::Checkerboard, L::Half, M::Mip, 1},
                         Case{Marcher::HiZ, L::Full, L::Half, M::Mip, 3}}) {
        CAPTURE(marcherName(k.marcher));
        CAPTURE(k.spp);
        RenderSettings rs = smallTraced();
        rs.width = 150;  // the last tile column is 22 pixels wide, not a lane multiple
        // 6 tile rows, the last 10 pixels tall: the SSR resolve's ring of kChainRingTileRows
        // tile rows (trace/tile_chain.h) wraps round in the tile chain.
        rs.height = 330;
        rs.trace.marcher = k.marcher;
        rs.trace.ssrLayout = k.layout;
        rs.trace.ssgiLayout = k.ssgiLayout;
        rs.trace.ssgiSpp = k.spp;
        rs.trace.resolve.mode = k.mode;
        rs.trace.ssrSpp = k.spp;
        const Renderer r(rs);
        int observed[2] = {};
        const TraceObserver seeRays = [&](TracePass pass, int, const RayBatch&, const MarchResult&,
                                          const HalfFrame*) {
            ++observed[pass == TracePass::Ssr ? 0 : 1];
        };
        Frame tiled, staged;
        r.renderWithoutHistory(scene, FrameInput::still(scene), tiled);
        r.renderWithoutHistory(scene, FrameInput::still(scene), staged, &seeRays);
        CHECK(observed[0] == k.spp);
        CHECK(observed[1] == k.spp);
        for (const Res id :
             {Res::Ssr, Res::SsrOpacity, Res::SsrHit, Res::SsrHitDistance, Res::SsrSteps,
              Res::Color, Res::Ssgi, Res::SsgiHit, Res::SsgiHitDistance})
            for (int ch = 0; ch < resourceDecl(id).channelCount(); ++ch)
                CHECK(test::sameBits(tiled.plane(id, ch), staged.plane(id, ch)));
        for (const auto pass : {&FrameStats::ssr, &FrameStats::ssgi}) {
            const TraceStats &sa = tiled.stats.*pass, &sb = staged.stats.*pass;
            CHECK(sa.rays.rays == sb.rays.rays);
            CHECK(sa.rays.pixels == sb.rays.pixels);
            CHECK(sa.rays.cut == sb.rays.cut);
            CHECK(sa.rays.hidden == sb.rays.hidden);
            CHECK(sa.march.rays == sb.march.rays);
            CHECK(sa.march.steps == sb.march.steps);
            CHECK(sa.march.laneActive == sb.march.laneActive);
            for (int e = 0; e < kMarchEndCount; ++e) CHECK(sa.march.ends[e] == sb.march.ends[e]);
            CHECK(sa.march.stepHistogram == sb.march.stepHistogram);
        }
    }
}

// Without a file to show the full-resolution planes (renderer/trace_pass.h): the direct pass
// writes SSGI's hit light straight into the half frame (hitLightAtHalf), the denoised
// half-resolution diffuse is brought to the frame inside the composite, tile by tile
// (diffuseUpsampledInComposite), and the traced signals are pooled (tracedSignalsPooled). The
// half frame and the image are the same bits either way, over the four chosen-pixel offsets,
// and the frame's planes are not made.
TEST_CASE("renderer: SSGI's half frame without full-resolution planes gives the same image") {
    const Scene scene = makeBuiltinScene("corridor");
    RenderSettings rs = smallTraced();
    rs.width = 150;  // tiles of 64 and a last column of 22
    rs.height = 70;
    rs.trace.ssgiLayout = TraceLayout::Half;
    rs.trace.ssrLayout = TraceLayout::Checkerboard;
    RenderSettings shown = rs;
    shown.debugPlanes = true;
    rs.debugPlanes = false;
    REQUIRE(diffuseUpsampledInComposite(rs));
    REQUIRE_FALSE(diffuseUpsampledInComposite(shown));
    REQUIRE(hitLightAtHalf(rs));
    REQUIRE_FALSE(hitLightAtHalf(shown));
    rs.height = shown.height = 71;  // an odd size: the last row of blocks is cut
    FrameHistory ha, hb;
    Frame a, b;
    FrameInput input = FrameInput::still(scene);
    for (int frame = 0; frame < 4; ++frame) {  // a first frame, then three with history
        input.frameIndex = uint32_t(frame);
        Renderer(rs).render(scene, input, ha, a);
        Renderer(shown).render(scene, input, hb, b);
        const HalfFrame &fa = a.scratch.half.frame, &fb = b.scratch.half.frame;
        for (int ch = 0; ch < 3; ++ch) CHECK(test::sameBits(fa.hitLight[ch], fb.hitLight[ch]));
        CHECK(a.direct.hitLight[0].empty());
        CHECK_FALSE(b.direct.hitLight[0].empty());
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(test::sameBits(a.rgb(Res::Color)[ch], b.rgb(Res::Color)[ch]));
            CHECK(test::sameBits(a.rgb(Res::Display)[ch], b.rgb(Res::Display)[ch]));
        }
        CHECK(a.rgb(Res::DenoisedDiffuse)[0].empty());
        CHECK_FALSE(b.rgb(Res::DenoisedDiffuse)[0].empty());
        // SSR's planes went back to the pool once the denoiser read them, and its passes
        // reused them: the frame holds less in all for not showing them.
        CHECK(a.rgb(Res::Ssr)[0].empty());
        CHECK_FALSE(b.rgb(Res::Ssr)[0].empty());
        const auto total = [](const Frame& f) {
            std::size_t n = 0;
            for (const MemoryUse& m : f.stats.memory)
                if (m.name != std::string_view("free plane memory")) n += m.bytes;
            return n;
        };
        CHECK(total(a) < total(b));
    }
}

TEST_CASE(
    "renderer: SSR's checkerboard thins where the denoiser's history is long, not after a cut") {
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings rs = smallTraced();
    rs.trace.ssrLayout = TraceLayout::Checkerboard;
    rs.trace.ssrSparseFrames = 3;
    RenderSettings full = rs;
    full.trace.ssrSparseFrames = TraceSettings::kSparseOff;
    FrameInput input = FrameInput::still(scene);
    input.previousCamera = input.camera;
    FrameHistory h, hFull;
    Frame f, g;
    for (uint32_t i = 0; i < 6; ++i) {
        input.frameIndex = i;
        Renderer(rs).render(scene, input, h, f);
        Renderer(full).render(scene, input, hFull, g);
        CAPTURE(i);
        CHECK(g.stats.ssr.rays.sparse == 0);
        // Frame i reads a history of i frames: the fourth is the first thinned.
        if (i < 3) {
            CHECK(f.stats.ssr.rays.sparse == 0);
            CHECK(test::sameBits(f.rgb(Res::Color)[0], g.rgb(Res::Color)[0]));
        } else {
            CHECK(f.stats.ssr.rays.sparse > 0);
            CHECK(f.stats.ssr.rays.rays < g.stats.ssr.rays.rays);
            CHECK(f.stats.ssr.rays.cut == g.stats.ssr.rays.cut + f.stats.ssr.rays.sparse);
        }
    }
    bool finite = true;
    for (const PlaneF& p : f.rgb(Res::Ssr))
        for (int y = 0; y < p.height(); ++y)
            for (int x = 0; x < p.width(); ++x) finite &= std::isfinite(p.at(x, y));
    CHECK(finite);
    // A cut reads no history: the full checkerboard.
    input.resetHistory = true;
    Renderer(rs).render(scene, input, h, f);
    CHECK(f.stats.ssr.rays.sparse == 0);
}
