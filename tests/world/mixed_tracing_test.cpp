// SSR traced in mixed and world mode (renderer/world_stage.h): the same bits on every ISA and
// thread count, and the screen's answers where the screen is asked.
#include <doctest/doctest.h>

#include <string>

#include "frame_hash.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "thread_counts.h"
#include "world/embree_world_rays.h"

using namespace ssrt;
using test::frameHash;

namespace {

Frame renderTraced(const Scene& scene, const WorldRays& world, TraceMode mode, Isa isa,
                   int threads) {
    RenderSettings s;
    s.width = 160;
    s.height = 90;
    s.threads = threads;
    s.isa = isa;
    s.trace.ssrTrace = mode;
    FrameInput in = FrameInput::still(scene);
    in.world = &world;
    return Renderer(s).renderWithoutHistory(scene, in);
}

}  // namespace

TEST_CASE("mixed tracing: mixed and world SSR render the same bits on every ISA and thread count") {
    for (const std::string name : {"cornell", "spheres", "fence"}) {
        CAPTURE(name);
        const Scene scene = makeBuiltinScene(name);
        const EmbreeScene embree(scene);
        const EmbreeWorldRays world(embree);
        for (TraceMode mode : {TraceMode::Mixed, TraceMode::World}) {
            const std::string modeName(traceModeName(mode));
            CAPTURE(modeName);
            const uint64_t ref = frameHash(renderTraced(scene, world, mode, Isa::Scalar, 1));
            const uint64_t screen =
                frameHash(renderTraced(scene, world, TraceMode::Screen, Isa::Scalar, 1));
            CHECK(ref != screen);  // the world's answers changed the image
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    const std::string isaStr(isaName(isa));
                    CAPTURE(isaStr);
                    CAPTURE(threads);
                    CHECK(frameHash(renderTraced(scene, world, mode, isa, threads)) == ref);
                }
        }
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
}
