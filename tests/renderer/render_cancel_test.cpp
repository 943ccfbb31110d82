// FrameInput::cancel (renderer/render_cancel.h): a raised flag stops the render between passes
// with RenderCancelled; one never raised changes no bit.
#include "renderer/render_cancel.h"

#include <doctest/doctest.h>

#include <atomic>

#include "frame_hash.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

RenderSettings small() {
    RenderSettings s;
    s.width = 96;
    s.height = 54;
    s.threads = 2;
    return s;
}

}  // namespace

TEST_CASE("render cancel: a flag never raised changes no bit, one raised stops the frame") {
    const Scene scene = makeBuiltinScene("cornell");
    const Renderer renderer(small());
    FrameInput input = FrameInput::still(scene);
    const uint64_t plain = test::frameHash(renderer.renderWithoutHistory(scene, input));
    std::atomic<bool> flag{false};
    input.cancel = &flag;
    CHECK(test::frameHash(renderer.renderWithoutHistory(scene, input)) == plain);
    // Raised before the frame: no pass runs.
    flag = true;
    Frame frame;
    CHECK_THROWS_AS(renderer.renderWithoutHistory(scene, input, frame), RenderCancelled);
    CHECK(frame.stats.passes.empty());
}

TEST_CASE("render cancel: raised while SSR traces, the frame stops before its next pass") {
    const Scene scene = makeBuiltinScene("cornell");
    const Renderer renderer(small());
    FrameInput input = FrameInput::still(scene);
    std::atomic<bool> flag{false};
    input.cancel = &flag;
    int batches = 0;
    // (The observer sees each traced batch: the flag goes up inside the SSR pass.)
    const TraceObserver raise = [&](TracePass pass, int, const RayBatch&, const MarchResult&,
                                    const HalfFrame*) {
        if (pass == TracePass::Ssr) flag = true;
        ++batches;
    };
    FrameHistory history;
    Frame frame;
    CHECK_THROWS_AS(renderer.render(scene, input, history, frame, &raise), RenderCancelled);
    CHECK(batches > 0);
    // SSR ran (it was raised inside it); nothing after it did.
    bool ssr = false, composite = false;
    for (const PassTime& p : frame.stats.passes) {
        ssr |= p.name.starts_with("ssr");
        composite |= p.name == "composite";
    }
    CHECK(ssr);
    CHECK_FALSE(composite);
    CHECK_FALSE(history.valid);
}
