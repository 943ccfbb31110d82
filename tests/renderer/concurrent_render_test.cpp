// Embedding the renderer in a threaded tool: renderers on 8 threads at once, each with its own
// scene, sequence and history, give the bits each gives alone; a history or frame handed to a
// second render call while one is using it is refused with a clear error, never raced on.
#include <doctest/doctest.h>

#include <barrier>
#include <cstdint>
#include <exception>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "frame_hash.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

using test::frameHash;

RenderSettings small(int threads) {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 90;
    rs.shadowMapSize = 256;
    rs.threads = threads;
    return rs;
}

// The scene's camera turned about its target by `degrees` around the up axis.
Camera orbit(const Camera& c, float degrees) {
    Camera out = c;
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), c.up);
    out.position = c.target + glm::vec3(turn * glm::vec4(c.position - c.target, 0.0f));
    return out;
}

// One embedding tool's work: a few frames of a scene along an orbit, one history throughout,
// with a Renderer of its own; the hash of every frame.
struct Job {
    std::string scene;
    int threads;  // the renderer's own (0: TBB's default)
};

std::vector<uint64_t> renderSequence(const Job& job) {
    const Scene scene = makeBuiltinScene(job.scene);
    const Renderer renderer(small(job.threads));
    Frame frame;
    FrameHistory history;
    FrameInput input;
    std::vector<uint64_t> hashes;
    for (int i = 0; i < 3; ++i) {
        input.previousCamera = i > 0 ? input.camera : scene.camera;
        input.camera = orbit(scene.camera, 2.0f * float(i));
        input.frameIndex = uint32_t(i);
        renderer.render(scene, input, history, frame);
        hashes.push_back(frameHash(frame));
    }
    return hashes;
}

// What `call` throws, as std::logic_error's message; "" when it returns.
std::string logicErrorOf(const std::function<void()>& call) {
    try {
        call();
    } catch (const std::logic_error& e) {
        return e.what();
    }
    return "";
}

// Runs `attempt` on a second thread while this one is inside a render call with `history` and
// `frame`: the call's observer (on this thread, after the first march) lets the other thread
// go and waits until its attempt has returned, so the two certainly overlap. Returns whether
// they did.
bool whileRendering(FrameHistory& history, Frame& frame, const std::function<void()>& attempt) {
    const Scene scene = makeBuiltinScene("cornell");
    const Renderer renderer(small(2));
    std::barrier sync(2);
    bool overlapped = false;
    std::thread other([&] {
        sync.arrive_and_wait();  // the render call is under way
        attempt();
        sync.arrive_and_wait();  // done: let it finish
    });
    const TraceObserver observer = [&](TracePass, int, const RayBatch&, const MarchResult&,
                                       const HalfFrame*) {
        if (overlapped) return;
        overlapped = true;
        sync.arrive_and_wait();
        sync.arrive_and_wait();
    };
    std::exception_ptr failed;
    try {
        renderer.render(scene, FrameInput::still(scene), history, frame, &observer);
    } catch (...) {
        failed = std::current_exception();
    }
    if (!overlapped) {  // no traced sample (or a failure before one): let the other one through
        sync.arrive_and_wait();
        sync.arrive_and_wait();
    }
    other.join();
    if (failed) std::rethrow_exception(failed);
    return overlapped;
}

}  // namespace

TEST_CASE("concurrent render: 8 renderers on 8 threads give the bits each gives alone") {
    // The built-in scenes (eight: each once), on renderers of TBB's default, 1 and 2 threads.
    std::vector<Job> jobs;
    const std::vector<BuiltinSceneInfo>& scenes = builtinScenes();
    for (int i = 0; i < 8; ++i)
        jobs.push_back({scenes[std::size_t(i) % scenes.size()].name, i % 3});
    std::vector<std::vector<uint64_t>> alone;
    for (const Job& job : jobs) alone.push_back(renderSequence(job));

    std::vector<std::vector<uint64_t>> together(jobs.size());
    std::barrier start(std::ptrdiff_t(jobs.size()));
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < jobs.size(); ++i)
        threads.emplace_back([&, i] {
            start.arrive_and_wait();  // all at once
            together[i] = renderSequence(jobs[i]);
        });
    for (std::thread& t : threads) t.join();
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        CAPTURE(jobs[i].scene);
        CAPTURE(jobs[i].threads);
        CHECK(together[i] == alone[i]);
    }
}

TEST_CASE("concurrent render: a history another render call is using is refused") {
    const Scene scene = makeBuiltinScene("spheres");
    const Renderer renderer(small(1));
    FrameHistory history;
    Frame frame;
    std::string error;
    CHECK(whileRendering(history, frame, [&] {
        Frame own;
        error =
            logicErrorOf([&] { renderer.render(scene, FrameInput::still(scene), history, own); });
    }));
    CHECK(error ==
          "render: the FrameHistory is in use by another render call (a history carries one "
          "sequence, one frame at a time)");
    // Let go when that call returned: the next frame of the sequence renders.
    CHECK(logicErrorOf([&] {
              renderer.render(scene, FrameInput::still(scene, 1), history, frame);
          }).empty());
}

TEST_CASE("concurrent render: a frame another render call is using is refused") {
    const Scene scene = makeBuiltinScene("spheres");
    const Renderer renderer(small(1));
    FrameHistory history;
    Frame frame;
    std::string withHistory, without;
    CHECK(whileRendering(history, frame, [&] {
        FrameHistory own;
        withHistory =
            logicErrorOf([&] { renderer.render(scene, FrameInput::still(scene), own, frame); });
        without = logicErrorOf(
            [&] { renderer.renderWithoutHistory(scene, FrameInput::still(scene), frame); });
    }));
    const std::string expected =
        "render: the Frame is in use by another render call (give each thread a Frame of its own)";
    CHECK(withHistory == expected);
    CHECK(without == expected);
    CHECK(logicErrorOf([&] {
              renderer.renderWithoutHistory(scene, FrameInput::still(scene), frame);
          }).empty());
}

TEST_CASE("concurrent render: a call that throws lets its history and frame go") {
    const Scene scene = makeBuiltinScene("cornell");
    const Renderer renderer(small(2));
    FrameHistory history;
    Frame frame;
    const TraceObserver fails = [](TracePass, int, const RayBatch&, const MarchResult&,
                                   const HalfFrame*) { throw std::runtime_error("observer"); };
    CHECK_THROWS_AS(renderer.render(scene, FrameInput::still(scene), history, frame, &fails),
                    std::runtime_error);
    CHECK(logicErrorOf([&] {
              renderer.render(scene, FrameInput::still(scene), history, frame);
          }).empty());
}
