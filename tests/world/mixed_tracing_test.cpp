// SSR and SSGI traced in mixed and world mode (renderer/world_stage.h): the same bits on every
// ISA and thread count, and the screen's answers where the screen is asked.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "frame_hash.h"
#include "renderer/renderer.h"
#include "renderer/world_stage.h"
#include "scenes/builtin_scenes.h"
#include "thread_counts.h"
#include "world/embree_world_rays.h"

using namespace ssrt;
using test::frameHash;

namespace {

// A built-in scene and its world rays.
struct WorldScene {
    Scene scene;
    EmbreeScene embree{scene};
    EmbreeWorldRays world{embree};
    explicit WorldScene(const std::string& name) : scene(makeBuiltinScene(name)) {}
};

// `signal`'s rays traced in `mode` (the other's on screen). `keepPlanes` false: only the colour
// is kept, so the frame's memory gives a plane back once its last declared reader has run (the
// PNG render's way).
Frame renderTraced(const Scene& scene, const WorldRays& world, TraceMode mode, Isa isa, int threads,
                   bool keepPlanes = true, TracePass signal = TracePass::Ssr) {
    RenderSettings s;
    s.width = 160;
    s.height = 90;
    s.threads = threads;
    s.isa = isa;
    (signal == TracePass::Ssr ? s.trace.ssrTrace : s.trace.ssgiTrace) = mode;
    s.gbufferPlanes = s.tracePlanes = s.idPlanes = keepPlanes;
    FrameInput in = FrameInput::still(scene);
    in.world = &world;
    return Renderer(s).renderWithoutHistory(scene, in);
}

// Runs fn(signal, mode) for each signal traced in mixed and in world mode (the other on
// screen), captured.
template <class Fn>
void forEachWorldMode(const Fn& fn) {
    for (TracePass signal : {TracePass::Ssr, TracePass::Ssgi})
        for (TraceMode mode : {TraceMode::Mixed, TraceMode::World}) {
            const std::string modeName(traceModeName(mode));
            CAPTURE(modeName);
            const bool ssr = signal == TracePass::Ssr;
            CAPTURE(ssr);
            fn(signal, mode);
        }
}

}  // namespace

TEST_CASE(
    "mixed tracing: mixed and world SSR and SSGI render the same bits on every ISA and thread "
    "count") {
    for (const std::string name : {"cornell", "spheres", "fence"}) {
        CAPTURE(name);
        const WorldScene ws(name);
        const Scene& scene = ws.scene;
        const WorldRays& world = ws.world;
        const uint64_t screen =
            frameHash(renderTraced(scene, world, TraceMode::Screen, Isa::Scalar, 1));
        forEachWorldMode([&](TracePass signal, TraceMode mode) {
            const auto render = [&](Isa isa, int threads) {
                return frameHash(renderTraced(scene, world, mode, isa, threads, true, signal));
            };
            const uint64_t ref = render(Isa::Scalar, 1);
            CHECK(ref != screen);  // the world's answers changed the image
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    const std::string isaStr(isaName(isa));
                    CAPTURE(isaStr);
                    CAPTURE(threads);
                    CHECK(render(isa, threads) == ref);
                }
        });
    }
}

// What a plane's hash is in a frame (0 where the frame does not hold it).
uint64_t layerHash(const Frame& f, std::string_view name) {
    for (const PlaneRef& p : f.layers())
        if (p.name == name) return hashPlane(*p.plane, 0);
    return 0;
}

TEST_CASE("mixed tracing: the colour is the same bits when the frame gives planes back early") {
    // The hidden hits' light reads the shadow map: freed after its last declared reader, it
    // once went to other resources while SSR still read it (a race, and a read after free).
    for (const std::string name : {"cornell", "spheres"}) {
        CAPTURE(name);
        const WorldScene ws(name);
        const Scene& scene = ws.scene;
        const WorldRays& world = ws.world;
        forEachWorldMode([&](TracePass signal, TraceMode mode) {
            const Frame kept = renderTraced(scene, world, mode, Isa::Scalar, 1, true, signal);
            for (int threads : testThreadCounts({1, 2, 8})) {
                CAPTURE(threads);
                const Frame early =
                    renderTraced(scene, world, mode, Isa::Scalar, threads, false, signal);
                for (const char* layer : {"color.R", "color.G", "color.B"}) {
                    CAPTURE(layer);
                    REQUIRE(layerHash(kept, layer) != 0);
                    CHECK(layerHash(early, layer) == layerHash(kept, layer));
                }
            }
        });
    }
}

TEST_CASE("mixed tracing: a mode that needs world rays without them is a clear error") {
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings s;
    s.width = 64;
    s.height = 36;
    s.trace.ssrTrace = TraceMode::Mixed;
    CHECK_THROWS_WITH_AS(Renderer(s).renderWithoutHistory(scene),
                         doctest::Contains("--ssr-trace mixed needs world rays"),
                         std::invalid_argument);
    s.trace.ssrTrace = TraceMode::Screen;
    s.trace.ssgiTrace = TraceMode::World;
    CHECK_THROWS_WITH_AS(Renderer(s).renderWithoutHistory(scene),
                         doctest::Contains("--ssgi-trace world needs world rays"),
                         std::invalid_argument);
}

TEST_CASE("mixed tracing: world mode marches no SSR ray and traces every one in world space") {
    const WorldScene ws("spheres");
    const Scene& scene = ws.scene;
    const WorldRays& world = ws.world;
    const Frame mixed = renderTraced(scene, world, TraceMode::Mixed, Isa::Scalar, 2);
    const Frame all = renderTraced(scene, world, TraceMode::World, Isa::Scalar, 2);
    const TraceStats& m = mixed.stats.ssr;
    const TraceStats& w = all.stats.ssr;
    REQUIRE(w.rays.rays > 0);
    CHECK(w.march.rays == 0);
    CHECK(w.march.steps == 0);
    CHECK(w.world.proven == 0);
    CHECK(w.world.sent == w.rays.rays);
    CHECK(w.world.shown + w.world.hidden + w.world.missed == w.world.sent);
    // Mixed marches them all and sends the rest on.
    CHECK(m.march.rays == m.rays.rays);
    CHECK(m.world.proven > 0);
    CHECK(m.world.proven + m.world.sent == m.rays.rays);
    // SSGI still marches in both (on screen), and not where it is traced in world space.
    CHECK(all.stats.ssgi.march.rays > 0);
    const Frame ssgiAll =
        renderTraced(scene, world, TraceMode::World, Isa::Scalar, 2, true, TracePass::Ssgi);
    const TraceStats& g = ssgiAll.stats.ssgi;
    REQUIRE(g.rays.rays > 0);
    CHECK(g.march.rays == 0);
    CHECK(g.world.sent == g.rays.rays);
    CHECK(ssgiAll.stats.ssr.march.rays > 0);
}

TEST_CASE("mixed tracing: a certain hit near the frame's edge is not faded") {
    // The screen fades its hits toward the border (it cannot see past it); mixed and world
    // keep each whole (trace/ssr_resolve.h: edgeFadeLength 0). Cornell's mirror sphere and
    // floor reflect what lies near the frame's bottom.
    const WorldScene ws("cornell");
    const Scene& scene = ws.scene;
    const WorldRays& world = ws.world;
    const auto faded = [&](TraceMode mode) {
        RenderSettings s;
        s.width = 160;
        s.height = 90;
        s.trace.ssrTrace = mode;
        s.trace.ssrLayout = TraceLayout::Full;       // every pixel its own ray, nothing filled in
        s.trace.resolve.mode = SsrResolveMode::Mip;  // opacity = the hit's fade x roughness's
        s.trace.denoise.enabled = false;
        FrameInput in = FrameInput::still(scene);
        in.world = &world;
        const Frame f = Renderer(s).renderWithoutHistory(scene, in);
        int hits = 0, fadedHits = 0;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                if (f.plane(Res::SsrHit).at(x, y) != 1.0f) continue;
                if (!(f.gbuffer.roughness.at(x, y) < s.trace.resolve.roughnessFadeStart)) continue;
                ++hits;
                fadedHits += f.plane(Res::SsrOpacity).at(x, y) < 1.0f;
            }
        CHECK(hits > 1000);
        return fadedHits;
    };
    CHECK(faded(TraceMode::Screen) > 100);
    CHECK(faded(TraceMode::Mixed) == 0);
    CHECK(faded(TraceMode::World) == 0);
}

TEST_CASE(
    "mixed tracing: the tile classifier sends the tiles that proved little straight to world "
    "space, the same bits on every ISA and thread count") {
    // A still sequence: frame 0 marches every tile; from frame 1 a tile whose proof held for
    // few of its rays skips its march (renderer/world_stage.h: MixedTileClassifier), except on its
    // probe frame; every ray is still answered, by the proof or by Embree.
    const WorldScene ws("spheres");
    const Scene& scene = ws.scene;
    const auto sequence = [&](Isa isa, int threads, std::vector<Frame>& frames, uint32_t count) {
        RenderSettings s;
        s.width = 160;
        s.height = 90;
        s.threads = threads;
        s.isa = isa;
        s.trace.ssrTrace = s.trace.ssgiTrace = TraceMode::Mixed;
        const Renderer renderer(s);
        FrameHistory history;
        frames.clear();
        for (uint32_t i = 0; i < count; ++i) {
            FrameInput in = FrameInput::still(scene, i);
            in.world = &ws.world;
            frames.push_back(renderer.render(scene, in, history));
        }
    };
    // (Nine frames: each tile probes once in kMixedProbeFrames.)
    std::vector<Frame> ref;
    sequence(Isa::Scalar, 1, ref, 1 + kMixedProbeFrames);
    for (const TraceStats* st : {&ref[0].stats.ssr, &ref[0].stats.ssgi}) {
        CHECK(st->march.rays == st->rays.rays);  // (no history yet: every tile marched)
        CHECK(st->world.proven + st->world.sent == st->rays.rays);
    }
    uint64_t marched[2] = {0, 0}, traced[2] = {0, 0};
    for (std::size_t f = 1; f < ref.size(); ++f) {
        CAPTURE(f);
        for (int p = 0; p < 2; ++p) {
            const TraceStats& st = p ? ref[f].stats.ssgi : ref[f].stats.ssr;
            REQUIRE(st.rays.rays > 0);
            CHECK(st.march.rays < st.rays.rays);
            CHECK(st.world.proven + st.world.sent == st.rays.rays);
            marched[p] += st.march.rays;
            traced[p] += st.rays.rays;
        }
    }
    // Most tiles prove little here; each marched again on its probe frame.
    for (int p = 0; p < 2; ++p) {
        CAPTURE(p);
        CHECK(marched[p] < traced[p] / 4);
        CHECK(marched[p] > 0);
    }
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 2, 8})) {
            const std::string isaStr(isaName(isa));
            CAPTURE(isaStr);
            CAPTURE(threads);
            std::vector<Frame> frames;
            sequence(isa, threads, frames, 3);
            for (int f = 0; f < 3; ++f) CHECK(frameHash(frames[f]) == frameHash(ref[f]));
        }
}
