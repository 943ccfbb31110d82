// The clocks behind `ssrt render --stats` (renderer/pass_timer.h). Only how the figures add
// up is checked, never a duration.
#include "renderer/pass_timer.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <string>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

double sumOf(const FrameStats& stats) {
    return std::accumulate(stats.passes.begin(), stats.passes.end(), 0.0,
                           [](double s, const PassTime& p) { return s + p.ms; });
}

bool hasPass(const FrameStats& stats, const std::string& name) {
    return std::any_of(stats.passes.begin(), stats.passes.end(),
                       [&](const PassTime& p) { return p.name == name; });
}

}  // namespace

TEST_CASE("stage clock: the stages that ran get one line each, summing to the wall time") {
    const char* const names[3] = {"a", "b", "c"};
    StageClock clock(4, 3);
    volatile float sink = 0.0f;
    clock.addSetUp(0, [&] { sink = sink + 1.0f; });
    for (int tile = 0; tile < 4; ++tile) {
        clock.time(tile, 0, [&] {
            for (int i = 0; i < 1000; ++i) sink = sink + 1.0f;
        });
        clock.time(tile, 2, [&] { sink = sink + 1.0f; });
    }
    const bool ran[3] = {true, false, true};
    FrameStats stats;
    clock.report(10.0, names, ran, stats);
    REQUIRE(stats.passes.size() == 2);
    CHECK(stats.passes[0].name == "a");
    CHECK(stats.passes[1].name == "c");
    CHECK(sumOf(stats) == doctest::Approx(10.0));
    for (const PassTime& p : stats.passes) CHECK(p.ms >= 0.0);
}

TEST_CASE("stage clock: a loop the clock does not see is shared equally") {
    const char* const names[2] = {"a", "b"};
    const StageClock clock(2, 2);
    const bool ran[2] = {true, true};
    FrameStats stats;
    clock.report(4.0, names, ran, stats);
    REQUIRE(stats.passes.size() == 2);
    CHECK(stats.passes[0].ms == doctest::Approx(2.0));
    CHECK(stats.passes[1].ms == doctest::Approx(2.0));
}

TEST_CASE("renderer: the fused surface stages keep their pass lines") {
    const Scene scene = makeBuiltinScene("cornell");  // untextured: no texture stage
    RenderSettings rs;
    rs.width = 24;
    rs.height = 16;
    rs.shadowMapSize = 32;
    const Frame f = Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene));
    for (const char* name : {"resolve", "ids", "shading"}) CHECK(hasPass(f.stats, name));
    CHECK_FALSE(hasPass(f.stats, "textures"));
    rs.idPlanes = false;
    const Frame g = Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene));
    CHECK_FALSE(hasPass(g.stats, "ids"));
    CHECK(hasPass(g.stats, "shading"));
}
