// The frame scheduler (renderer/frame_scheduler.h): passes in the graph's order, the tiled
// passes of one chain fused into one loop over the tiles, whole passes between them.
#include "renderer/frame_scheduler.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "renderer/quality.h"
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
    s.whole(pass::kShading, [&] { order.push_back("shading"); });
    FrameStats stats;
    s.run(stats);
    REQUIRE(order.size() == std::size_t(grid.count()) + 1);
    CHECK(order.back() == "shading");
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
