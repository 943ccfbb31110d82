// The frame scheduler (renderer/frame_scheduler.h): passes in the graph's order, the tiled
// passes of one chain fused into one loop over the tiles, whole passes between them.
#include "renderer/frame_scheduler.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "renderer/frame_memory.h"
#include "renderer/quality.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

CompiledGraph mediumGraph() {
    RenderSettings s;
    s.width = 200;
    s.height = 130;      // 4 x 3 tiles
    s.idPlanes = false;  // (the id pass would run between the resolve and the shading)
    return compileFrameGraph({s, SceneFacts::of(makeBuiltinScene("cornell")), false, false});
}

}  // namespace

TEST_CASE("frame scheduler: a chain's tiled passes run tile by tile, together") {
    const CompiledGraph g = mediumGraph();
    REQUIRE(g.runs(pass::kResolve));
    REQUIRE(g.runs(pass::kShading));
    const TileGrid grid(g.width, g.height);
    std::vector<std::string> order;
    FrameScheduler s(g, grid, 1);
    // Registered out of order: the graph's order decides.
    s.tiled(
        pass::kShading, [&](int t) { order.push_back("shade " + std::to_string(t)); },
        [&] { order.push_back("shade set-up"); });
    s.whole(pass::kShadow, [&] { order.push_back("shadow"); });
    s.tiled(
        pass::kResolve, [&](int t) { order.push_back("resolve " + std::to_string(t)); },
        [&] { order.push_back("resolve set-up"); });
    FrameStats stats;
    s.run(stats);
    std::vector<std::string> expected = {"shadow", "resolve set-up", "shade set-up"};
    for (int t = 0; t < grid.count(); ++t) {
        expected.push_back("resolve " + std::to_string(t));
        expected.push_back("shade " + std::to_string(t));
    }
    CHECK(order == expected);
    // A time for each tiled pass (the whole ones time themselves).
    REQUIRE(stats.passes.size() == 2);
    CHECK(stats.passes[0].name == "resolve");
    CHECK(stats.passes[1].name == "shading");
}

TEST_CASE("frame scheduler: a whole pass between two tiled ones ends the loop") {
    const CompiledGraph g = mediumGraph();
    const TileGrid grid(g.width, g.height);
    std::vector<std::string> order;
    FrameScheduler s(g, grid, 1);
    s.tiled(pass::kResolve, [&](int t) { order.push_back("resolve " + std::to_string(t)); });
    s.whole(pass::kHiZ, [&] { order.push_back("hi-z"); });
    s.tiled(pass::kShading, [&](int t) { order.push_back("shade " + std::to_string(t)); });
    FrameStats stats;
    s.run(stats);
    REQUIRE(order.size() == std::size_t(2 * grid.count()) + 1);
    // (The graph chains the resolve and the shading; the hi-z runs after both.)
    CHECK(order.back() == "hi-z");
    // A pass given otherwise than declared (the shading is tiled, the shadow whole).
    FrameScheduler wrong(g, grid, 1);
    wrong.whole(pass::kShading, [] {});
    CHECK_THROWS_AS(wrong.run(stats), std::logic_error);
    FrameScheduler wrong2(g, grid, 1);
    wrong2.tiled(pass::kShadow, [](int) {});
    CHECK_THROWS_AS(wrong2.run(stats), std::logic_error);
}

TEST_CASE("frame scheduler: a pass the graph does not know is a programming error") {
    const CompiledGraph g = mediumGraph();
    FrameScheduler s(g, TileGrid(g.width, g.height), 1);
    s.whole("no such pass", [] {});
    FrameStats stats;
    CHECK_THROWS_AS(s.run(stats), std::logic_error);
    FrameScheduler twice(g, TileGrid(g.width, g.height), 1);
    twice.whole(pass::kShadow, [] {});
    CHECK_THROWS_AS(twice.tiled(pass::kShadow, [](int) {}), std::logic_error);
}

TEST_CASE("frame scheduler: a chain's finishes run after its last tile, on the chain's own tiles") {
    const CompiledGraph g = mediumGraph();
    const TileGrid frameGrid(g.width, g.height);
    const TileGrid small(40, 20);  // 1 x 1 tile
    std::vector<std::string> order;
    FrameScheduler s(g, frameGrid, 1);
    s.tiled(
        pass::kResolve, [&](int t) { order.push_back("resolve " + std::to_string(t)); },
        [&] { order.push_back("resolve set-up"); }, [&] { order.push_back("resolve finish"); },
        &small);
    s.tiled(
        pass::kShading, [&](int t) { order.push_back("shade " + std::to_string(t)); }, {},
        [&] { order.push_back("shade finish"); }, &small);
    FrameStats stats;
    s.run(stats);
    const std::vector<std::string> expected = {"resolve set-up", "resolve 0", "shade 0",
                                               "resolve finish", "shade finish"};
    CHECK(order == expected);
    // The second pass of the loop is marked as fused with the first.
    REQUIRE(stats.passes.size() == 2);
    CHECK_FALSE(stats.passes[0].fused);
    CHECK(stats.passes[1].fused);
    // Passes of one chain on different tiles cannot share a loop.
    FrameScheduler mixed(g, frameGrid, 1);
    mixed.tiled(
        pass::kResolve, [](int) {}, {}, {}, &small);
    mixed.tiled(pass::kShading, [](int) {});
    CHECK_THROWS_AS(mixed.run(stats), std::logic_error);
}

TEST_CASE("frame scheduler: the denoiser's passes share the loops the frame graph chains") {
    const Scene scene = makeBuiltinScene("cornell");
    for (const TraceLayout layout : {TraceLayout::Full, TraceLayout::Half}) {
        CAPTURE(int(layout));
        RenderSettings s;
        applyQuality(Quality::Medium, s);
        s.width = 96;
        s.height = 64;
        s.shadowMapSize = 128;
        s.trace.ssgiLayout = layout;
        const Renderer renderer(s);
        FrameHistory history;
        Frame frame;
        renderer.render(scene, FrameInput::still(scene, 0), history, frame);
        renderer.render(scene, FrameInput::still(scene, 1), history, frame);
        const auto fused = [&](std::string_view name) {
            for (const PassTime& p : frame.stats.passes)
                if (p.name == name) return p.fused;
            FAIL("no pass " << name);
            return false;
        };
        // The front end hands the temporal pass its output at the pixel, and the history's
        // commit follows the post-blur (the half frame's passes are timed under the same names).
        CHECK_FALSE(fused("denoise front end"));
        CHECK(fused("denoise temporal"));
        CHECK(fused("denoise history"));
        // The composite follows them in the same loop (with the half frame's upsample inside it).
        CHECK(fused("composite"));
        // The spatial passes read their neighbours: each has a loop of its own.
        CHECK_FALSE(fused("denoise history fix"));
        CHECK_FALSE(fused("denoise blur"));
    }
}

TEST_CASE(
    "frame scheduler: with the frame's memory, a chain's planes live from its set-ups to "
    "its finishes") {
    RenderSettings settings;
    settings.width = 200;
    settings.height = 130;
    settings.idPlanes = settings.gbufferPlanes = false;  // (a PNG's: the G-buffer transient)
    const CompiledGraph g =
        compileFrameGraph({settings, SceneFacts::of(makeBuiltinScene("cornell")), false, false});
    const GraphResource* materialId = g.find(Res::MaterialId);
    REQUIRE(materialId);
    REQUIRE(g.passes[std::size_t(materialId->last)].decl->name == pass::kShading);
    Frame frame;
    FrameMemory memory(g, frame, false);
    FrameScheduler s(g, TileGrid(g.width, g.height), 1, nullptr, &memory);
    bool takenAtSetUp = false, heldAtFinish = false;
    s.whole(pass::kShadow, [] {});
    s.whole(
        pass::kVisibility, [] {}, pass::kBackFaces);
    s.tiled(
        pass::kResolve, [](int) {},
        [&] {
            takenAtSetUp = frame.gbuffer.materialId.width() == g.width &&
                           frame.gbuffer.materialId.height() == g.height;
        });
    s.tiled(
        pass::kShading, [](int) {}, {}, [&] { heldAtFinish = !frame.gbuffer.materialId.empty(); });
    FrameStats stats;
    s.run(stats);
    CHECK(takenAtSetUp);
    CHECK(heldAtFinish);
    // Its last reader's chain has run: back to the pool.
    CHECK(frame.gbuffer.materialId.empty());
}
