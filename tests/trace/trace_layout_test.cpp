// The trace layouts (trace/trace_layout.h, TraceSettings::ssrLayout / ssgiLayout): which
// pixels get rays, that the others cost no march, and that the reconstructed frames keep the
// determinism contract and stay finite where methods fail.
#include "trace/trace_layout.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/isa.h"
#include "frame_hash.h"
#include "renderer/renderer.h"
#include "renderer/screen_quad.h"
#include "scenes/builtin_scenes.h"
#include "thread_counts.h"
#include "trace/ray_gen.h"

using namespace ssrt;

namespace {

RenderSettings smallSettings(TraceLayout ssr, TraceLayout ssgi, int w = 240, int h = 136) {
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.shadowMapSize = 512;
    rs.threads = 2;
    rs.trace.ssrLayout = ssr;
    rs.trace.ssgiLayout = ssgi;
    return rs;
}

// Each pass's ray pdf and direction planes, as the observer saw them (last sample).
struct Batches {
    PlaneF pdf[2], dx[2];
};

Frame renderObserved(const RenderSettings& rs, const Scene& scene, uint32_t frameIndex,
                     Batches& b) {
    const TraceObserver observer = [&](TracePass pass, int, const RayBatch& rays,
                                       const MarchResult&, const HalfFrame*) {
        const int p = pass == TracePass::Ssr ? 0 : 1;
        b.pdf[p] = PlaneF(rays.width(), rays.height());
        b.dx[p] = PlaneF(rays.width(), rays.height());
        for (int y = 0; y < rays.height(); ++y)
            for (int x = 0; x < rays.width(); ++x) {
                b.pdf[p].at(x, y) = rays.pdf.at(x, y);
                b.dx[p].at(x, y) = rays.dx.at(x, y);
            }
    };
    Frame f;
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene, frameIndex), f, &observer);
    return f;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, 4) == 0; }

using test::frameHash;

Scene quadScene() {
    Material m;
    m.roughness = 0.2f;  // below the SSR cut: every pixel wants both rays
    return test::screenQuadScene(m);
}

// The view buildHalfFrame reads: viewZ, normal, albedo, metallic; motion when given.
GBufferView sourceView(const PlaneF& z, const PlaneF n[3], const PlaneF alb[3], const PlaneF& met,
                       const PlaneF* motion = nullptr) {
    return gbufferView("test", z.width(), z.height(),
                       {{kGViewZ, &z},
                        {kGNormalX, &n[0]},
                        {kGNormalY, &n[1]},
                        {kGNormalZ, &n[2]},
                        {kGAlbedoR, &alb[0]},
                        {kGAlbedoG, &alb[1]},
                        {kGAlbedoB, &alb[2]},
                        {kGMetallic, &met},
                        {kGMotionX, motion ? &motion[0] : nullptr},
                        {kGMotionY, motion ? &motion[1] : nullptr}});
}

}  // namespace

TEST_CASE("checkerboard: one phase traced with the full layout's rays, the other cut and counted") {
    const Scene scene = makeBuiltinScene("cornell");
    for (uint32_t frame : {0u, 1u}) {
        CAPTURE(frame);
        Batches full, cb;
        const Frame ff =
            renderObserved(smallSettings(TraceLayout::Full, TraceLayout::Full), scene, frame, full);
        const Frame fc = renderObserved(
            smallSettings(TraceLayout::Checkerboard, TraceLayout::Checkerboard), scene, frame, cb);
        const TraceStats* stats[2] = {&fc.stats.ssr, &fc.stats.ssgi};
        const uint32_t phase[2] = {kSsrCheckerboardPhase, kSsgiCheckerboardPhase};
        for (int p = 0; p < 2; ++p) {
            CAPTURE(p);
            uint64_t traced = 0, cut = 0;
            bool sameRays = true, cutMarked = true, noRayElsewhere = true;
            for (int y = 0; y < ff.height; ++y)
                for (int x = 0; x < ff.width; ++x) {
                    const float a = full.pdf[p].at(x, y), c = cb.pdf[p].at(x, y);
                    if (checkerboardTraced(x, y, frame, phase[p])) {
                        sameRays &=
                            sameBits(a, c) && sameBits(full.dx[p].at(x, y), cb.dx[p].at(x, y));
                        traced += c > 0.0f;
                    } else {
                        if (a > 0.0f) cutMarked &= c == kPdfLayoutCut;
                        noRayElsewhere &= !(c > 0.0f);
                        cut += c == kPdfLayoutCut;
                    }
                }
            CHECK(sameRays);
            CHECK(cutMarked);
            CHECK(noRayElsewhere);
            // Only the traced phase reaches the march; the cut pixels are counted.
            CHECK(stats[p]->march.rays == traced);
            CHECK(stats[p]->rays.cut == cut);
            CHECK(stats[p]->rays.rays == traced);
            CHECK(cut > 0);
        }
        // SSR and SSGI opposite: no pixel gets both rays in one frame.
        bool disjoint = true;
        for (int y = 0; y < ff.height; ++y)
            for (int x = 0; x < ff.width; ++x)
                disjoint &= !(cb.pdf[0].at(x, y) > 0.0f && cb.pdf[1].at(x, y) > 0.0f);
        CHECK(disjoint);
    }
    // The phases alternate per frame.
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 4; ++y) {
            CHECK(checkerboardTraced(x, y, 0, kSsrCheckerboardPhase) !=
                  checkerboardTraced(x, y, 1, kSsrCheckerboardPhase));
            CHECK(checkerboardTraced(x, y, 7, kSsrCheckerboardPhase) !=
                  checkerboardTraced(x, y, 7, kSsgiCheckerboardPhase));
        }
}

TEST_CASE("checkerboard marches half the pixels, half resolution a quarter (screen-filling quad)") {
    const Scene scene = quadScene();
    const int w = 64, h = 64;  // (the quad fills a square view)
    const uint64_t pixels = uint64_t(w * h);
    for (uint32_t frame : {0u, 1u, 2u, 3u}) {
        CAPTURE(frame);
        Batches b;
        const Frame full = renderObserved(smallSettings(TraceLayout::Full, TraceLayout::Full, w, h),
                                          scene, frame, b);
        REQUIRE(full.stats.ssgi.rays.pixels == pixels);
        CHECK(full.stats.ssgi.march.rays == pixels);
        CHECK(full.stats.ssr.march.rays + full.stats.ssr.rays.belowSurface == pixels);
        const Frame cb = renderObserved(
            smallSettings(TraceLayout::Checkerboard, TraceLayout::Checkerboard, w, h), scene, frame,
            b);
        CHECK(cb.stats.ssgi.march.rays == pixels / 2);
        CHECK(cb.stats.ssgi.rays.cut == pixels / 2);
        CHECK(cb.stats.ssr.march.rays + cb.stats.ssr.rays.belowSurface == pixels / 2);
        CHECK(cb.stats.ssr.rays.cut == pixels / 2);
        const Frame half = renderObserved(
            smallSettings(TraceLayout::Checkerboard, TraceLayout::Half, w, h), scene, frame, b);
        CHECK(half.stats.ssgi.march.rays == pixels / 4);
        CHECK(half.stats.ssgi.rays.cut == pixels - pixels / 4);
        CHECK(half.stats.ssgi.rays.pixels == pixels);
    }
}

TEST_CASE("half resolution: the chosen pixel of each block rotates over the four, picked exactly") {
    bool seen[2][2] = {};
    for (uint32_t f = 0; f < 4; ++f) seen[halfOffset(f).y][halfOffset(f).x] = true;
    CHECK((seen[0][0] && seen[0][1] && seen[1][0] && seen[1][1]));
    CHECK(halfOffset(5).x == halfOffset(1).x);
    // Odd sizes: the edge blocks take the nearest pixel inside.
    const int w = 7, h = 5;
    TraceCamera cam;
    cam.width = w, cam.height = h;
    PlaneF z(w, h), n[3] = {PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)}, alb[3], met(w, h);
    PlaneU16 light[3];  // f16, as the direct pass's
    for (int c = 0; c < 3; ++c) alb[c] = PlaneF(w, h), light[c] = PlaneU16(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) z.at(x, y) = 1.0f + float(y * w + x);
    const HalfFrameSource src{sourceView(z, n, alb, met),
                              false,
                              {viewOf(light[0], "hitLight.R"), viewOf(light[1], "hitLight.G"),
                               viewOf(light[2], "hitLight.B")}};
    for (uint32_t f = 0; f < 4; ++f) {
        HalfFrame hf;
        buildHalfFrame(cam, src, f, hf, 2);
        REQUIRE(hf.camera.width == 4);
        REQUIRE(hf.camera.height == 3);
        const PixelOffset o = halfOffset(f);
        bool picked = true;
        for (int hy = 0; hy < 3; ++hy)
            for (int hx = 0; hx < 4; ++hx) {
                const int x = std::min(2 * hx + o.x, w - 1), y = std::min(2 * hy + o.y, h - 1);
                picked &= hf.viewZ.at(hx, hy) == z.at(x, y);
            }
        CHECK(picked);
        // Every pixel is a surface: the cut ones are all but the distinct chosen ones.
        uint64_t chosen = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const PixelOffset s = halfSource(x / 2, y / 2, o, w, h);
                chosen += s.x == x && s.y == y;
            }
        CHECK(hf.cutPixels == uint64_t(w * h) - chosen);
    }
}

// A half frame's pixel holds its block's chosen pixel, off the half pixel's centre: its rays
// start at that pixel's own surface point (TraceCamera::pointX), where the truth traces them,
// not at the half pixel's centre at that depth (off a sloped surface).
TEST_CASE("half resolution: SSGI rays start at the chosen pixel's surface point") {
    const Scene scene = makeBuiltinScene("cornell");
    const RenderSettings rs = smallSettings(TraceLayout::Checkerboard, TraceLayout::Half);
    for (uint32_t f = 0; f < 4; ++f) {
        CAPTURE(f);
        int checked = 0;
        float worst = 0.0f;
        Frame frame;
        const TraceObserver observer = [&](TracePass pass, int, const RayBatch& rays,
                                           const MarchResult&, const HalfFrame* half) {
            if (pass != TracePass::Ssgi) return;
            REQUIRE(half);
            const TraceCamera& c = frame.camera;
            for (int hy = 0; hy < rays.height(); ++hy)
                for (int hx = 0; hx < rays.width(); ++hx) {
                    if (!(rays.pdf.at(hx, hy) > 0.0f)) continue;
                    const PixelOffset p = halfSource(hx, hy, half->offset, c.width, c.height);
                    const float z = frame.gbuffer.viewZ.at(p.x, p.y);
                    const float want[3] = {
                        (2.0f * (float(p.x) + 0.5f) / float(c.width) - 1.0f) * c.tanHalfX * z,
                        (1.0f - 2.0f * (float(p.y) + 0.5f) / float(c.height)) * c.tanHalfY * z, -z};
                    const float got[3] = {rays.ox.at(hx, hy), rays.oy.at(hx, hy),
                                          rays.oz.at(hx, hy)};
                    for (int k = 0; k < 3; ++k)
                        worst = std::max(worst, std::abs(got[k] - want[k]) / z);
                    ++checked;
                }
        };
        Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene, f), frame, &observer);
        CHECK(checked > 1000);
        CHECK(worst < 1e-5f);  // (the half pixel's centre is a quarter of a pixel off: 1e-3)
    }
}

TEST_CASE("half resolution: the denoiser's guides are each block's first pixel, every frame") {
    // The chosen pixel rotates; the guides (depth, normal, motion in half pixels) stay at the
    // block's pixel (0, 0), so the denoiser's history sees one surface frame after frame; and
    // without motion in the source they are not made.
    const int w = 7, h = 5;
    TraceCamera cam;
    cam.width = w, cam.height = h;
    PlaneF z(w, h), n[3] = {PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)}, alb[3], met(w, h);
    PlaneF motion[2] = {PlaneF(w, h), PlaneF(w, h)};
    PlaneU16 light[3];
    for (int c = 0; c < 3; ++c) alb[c] = PlaneF(w, h), light[c] = PlaneU16(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            z.at(x, y) = 1.0f + float(y * w + x);
            n[1].at(x, y) = float(x);
            motion[0].at(x, y) = 3.0f * float(x);
            motion[1].at(x, y) = -float(y);
        }
    HalfFrameSource src{sourceView(z, n, alb, met, motion),
                        true,
                        {viewOf(light[0], "hitLight.R"), viewOf(light[1], "hitLight.G"),
                         viewOf(light[2], "hitLight.B")}};
    for (uint32_t f = 0; f < 4; ++f) {
        CAPTURE(f);
        HalfFrame hf;
        buildHalfFrame(cam, src, f, hf, 2);
        bool first = true;
        for (int hy = 0; hy < 3; ++hy)
            for (int hx = 0; hx < 4; ++hx) {
                const int x = std::min(2 * hx, w - 1), y = std::min(2 * hy, h - 1);
                first &= hf.guide.viewZ.at(hx, hy) == z.at(x, y);
                first &= hf.guide.normal[1].at(hx, hy) == n[1].at(x, y);
                first &= hf.guide.motion[0].at(hx, hy) == 0.5f * motion[0].at(x, y);
                first &= hf.guide.motion[1].at(hx, hy) == 0.5f * motion[1].at(x, y);
            }
        CHECK(first);
    }
    src.guides = false;
    HalfFrame none;
    buildHalfFrame(cam, src, 1, none, 1);
    CHECK(none.guide.viewZ.empty());
    CHECK(none.guide.motion[0].empty());
    CHECK(!none.viewZ.empty());
    // Its view: the half frame's planes at its size.
    const GBufferView hv = none.view();
    CHECK(hv.width == 4);
    CHECK(hv.height == 3);
    CHECK(hv.viewZ == none.viewZ.row(0));
    CHECK(hv.metallic == none.metallic.row(0));
    CHECK(hv.roughness == nullptr);
    // Guides need motion, and the source must be of the camera's size.
    src.guides = true;
    src.g.motion[1] = nullptr;
    CHECK_THROWS_AS(buildHalfFrame(cam, src, 1, none, 1), std::invalid_argument);
    src.guides = false;
    TraceCamera wider = cam;
    wider.width = w + 1;
    CHECK_THROWS_AS(buildHalfFrame(wider, src, 1, none, 1), std::invalid_argument);
}

TEST_CASE("trace layouts: the same bits for every ISA and thread count, frame after frame") {
    struct Case {
        const char* scene;
        TraceLayout ssr, ssgi;
        Marcher marcher;
    };
    const Case cases[] = {
        {"cornell", TraceLayout::Checkerboard, TraceLayout::Checkerboard, Marcher::HiZ},
        {"cornell", TraceLayout::Checkerboard, TraceLayout::Half, Marcher::HiZ},
        {"spheres", TraceLayout::Full, TraceLayout::Half, Marcher::Dda},
        {"corridor", TraceLayout::Checkerboard, TraceLayout::Half, Marcher::Linear},
    };
    for (const Case& c : cases) {
        const std::string ssr(traceLayoutName(c.ssr)), ssgi(traceLayoutName(c.ssgi));
        const std::string scene = c.scene;
        CAPTURE(scene);
        CAPTURE(ssr);
        CAPTURE(ssgi);
        const Scene s = makeBuiltinScene(c.scene);
        for (uint32_t frame : {0u, 1u}) {
            CAPTURE(frame);
            RenderSettings rs = smallSettings(c.ssr, c.ssgi);
            rs.trace.marcher = c.marcher;
            rs.trace.ssgiSpp = 2;  // the half frame's accumulation too
            rs.isa = Isa::Scalar;
            rs.threads = 1;
            const uint64_t ref =
                frameHash(Renderer(rs).renderWithoutHistory(s, FrameInput::still(s, frame)));
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    const std::string isaStr(isaName(isa));
                    CAPTURE(isaStr);
                    CAPTURE(threads);
                    rs.isa = isa;
                    rs.threads = threads;
                    CHECK(frameHash(Renderer(rs).renderWithoutHistory(
                              s, FrameInput::still(s, frame))) == ref);
                }
        }
    }
}

TEST_CASE("trace layouts: every plane finite on the failure scenes, odd sizes included") {
    for (const auto& info : builtinScenes()) {
        const Scene scene = makeBuiltinScene(info.name);
        for (TraceLayout ssgi : {TraceLayout::Checkerboard, TraceLayout::Half})
            for (Marcher m : {Marcher::HiZ, Marcher::Dda})
                for (int w : {240, 161}) {
                    const std::string name = info.name, layout(traceLayoutName(ssgi));
                    CAPTURE(name);
                    CAPTURE(layout);
                    CAPTURE(w);
                    RenderSettings rs =
                        smallSettings(TraceLayout::Checkerboard, ssgi, w, w == 240 ? 136 : 91);
                    rs.trace.marcher = m;
                    const Frame f =
                        Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene, 1));
                    for (const PlaneRef& p : f.layers()) {
                        CAPTURE(p.name);
                        bool finite = true;
                        for (int y = 0; y < f.height; ++y)
                            for (int x = 0; x < f.width; ++x)
                                finite &= std::isfinite(p.plane->at(x, y));
                        CHECK(finite);
                    }
                    // The reconstructed planes stay in their ranges.
                    bool inRange = true;
                    for (int y = 0; y < f.height; ++y)
                        for (int x = 0; x < f.width; ++x) {
                            const float o = f.plane(Res::SsrOpacity).at(x, y);
                            const float hs = f.plane(Res::SsgiHit).at(x, y);
                            inRange &= o >= 0.0f && o <= 1.0f && hs >= 0.0f && hs <= 1.0f &&
                                       f.plane(Res::SsgiHitDistance).at(x, y) >= 0.0f &&
                                       f.rgb(Res::Ssgi)[0].at(x, y) >= 0.0f;
                        }
                    CHECK(inRange);
                }
    }
}

namespace {

// A wall facing the camera (view = world) at depth 2, roughness 0.2 (mirror rays: none
// rejected below the surface), with motion `mx` pixels
// (previous minus current position) everywhere, and the last frame's history lengths
// `frames(x, y)`: the thinned checkerboard's inputs.
struct ThinnedWall {
    static constexpr int w = 70, h = 36;  // not a multiple of the lane width or the tile
    TraceCamera camera;
    PlaneF viewZ{w, h, 2.0f}, normal[3]{{w, h, 0.0f}, {w, h, 0.0f}, {w, h, 1.0f}},
        roughness{w, h, 0.2f}, motion[2]{{w, h, 0.0f}, {w, h, 0.0f}}, history{w, h, 0.0f};

    ThinnedWall() {
        camera.width = w;
        camera.height = h;
        camera.tanHalfY = 0.5f;
        camera.tanHalfX = 0.5f * float(w) / float(h);
        const float identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        std::copy_n(identity, 9, camera.viewToWorld);
        // Long (10 frames) on the left half, short (2) on the right.
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) history.at(x, y) = x < w / 2 ? 10.0f : 2.0f;
    }
    GBufferView g() const {
        return gbufferView("test", w, h,
                           {{kGViewZ, &viewZ},
                            {kGNormalX, &normal[0]},
                            {kGNormalY, &normal[1]},
                            {kGNormalZ, &normal[2]},
                            {kGRoughness, &roughness},
                            {kGMotionX, &motion[0]},
                            {kGMotionY, &motion[1]}});
    }
    RayGenStats rays(uint32_t frame, RayBatch& out, Isa isa = Isa::Scalar, int threads = 1) const {
        RayGenCheckerboard cb{true, kSsrCheckerboardPhase, viewOf(history, "history"), 8.0f};
        return generateSpecularRays(isa, SsrMethod::Mirror, frame, 0, camera, g(), out, threads,
                                    std::numeric_limits<float>::infinity(), cb);
    }
};

}  // namespace

TEST_CASE("thinned checkerboard: a long history traces one pixel of a block a frame, in turn") {
    ThinnedWall s;
    std::vector<int> raysAt(std::size_t(s.w * s.h), 0);
    for (uint32_t frame = 0; frame < 4; ++frame) {
        CAPTURE(frame);
        RayBatch rays;
        const RayGenStats st = s.rays(frame, rays);
        uint64_t sparse = 0, cut = 0, traced = 0;
        bool asLaidOut = true;
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) {
                const float pdf = rays.pdf.at(x, y);
                const bool phase = checkerboardTraced(x, y, frame, kSsrCheckerboardPhase);
                const bool thinned =
                    phase && x < s.w / 2 && uint32_t(x & 1) != sparseBlockPick(frame);
                const bool ray = phase && !thinned;
                asLaidOut &= ray ? pdf > 0.0f : pdf == kPdfLayoutCut;
                sparse += thinned;
                cut += !ray;
                traced += ray;
                raysAt[std::size_t(y * s.w + x)] += pdf > 0.0f;
            }
        CHECK(asLaidOut);
        CHECK(st.sparse == sparse);
        CHECK(st.cut == cut);
        CHECK(st.rays == traced);
        CHECK(sparse > 0);
    }
    // Over four frames: a ray for each pixel of the long half once, of the short half twice.
    bool turns = true;
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x)
            turns &= raysAt[std::size_t(y * s.w + x)] == (x < s.w / 2 ? 1 : 2);
    CHECK(turns);
}

TEST_CASE("thinned checkerboard: the history is read where the motion says the pixel was") {
    ThinnedWall s;
    RayBatch rays;
    // Every pixel came from half a frame to its right: the left half finds the short history,
    // the right half none (off the frame).
    s.motion[0].fill(float(s.w / 2));
    CHECK(s.rays(0, rays).sparse == 0);
    // From the left: the right half finds the long history, the left half none.
    s.motion[0].fill(-float(s.w / 2));
    const RayGenStats st = s.rays(0, rays);
    CHECK(st.sparse > 0);
    bool rightOnly = true;
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w / 2; ++x)
            rightOnly &= rays.pdf.at(x, y) != kPdfLayoutCut || !checkerboardTraced(x, y, 0, 0);
    CHECK(rightOnly);
    // A NaN motion finds no history.
    s.motion[0].fill(std::nanf(""));
    CHECK(s.rays(0, rays).sparse == 0);
}

TEST_CASE("thinned checkerboard: every ISA and thread count gives the same rays") {
    ThinnedWall s;
    s.motion[1].fill(0.6f);
    RayBatch ref;
    s.rays(5, ref);
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 3})) {
            CAPTURE(std::string(isaName(isa)));
            CAPTURE(threads);
            RayBatch got;
            s.rays(5, got, isa, threads);
            CHECK(hashPlane(got.pdf) == hashPlane(ref.pdf));
            CHECK(hashPlane(got.dx) == hashPlane(ref.dx));
        }
}
