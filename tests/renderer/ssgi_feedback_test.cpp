// Multi-bounce diffuse in the renderer (TraceSettings::ssgiFeedback): what a frame commits,
// that a still camera's diffuse light rises frame over frame, that the first frame, a reset
// and a size change give one bounce to the bit, and that a sequence stays finite (sky
// included) and keeps its bits on every ISA and thread count.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "plane_compare.h"
#include "renderer/renderer.h"
#include "renderer/trace_pass.h"
#include "scenes/builtin_scenes.h"
#include "thread_counts.h"

using namespace ssrt;
using test::sameBits;

namespace {

RenderSettings smallFeedback(bool feedback) {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 96;
    rs.shadowMapSize = 256;
    rs.threads = 2;
    rs.trace.ssgiFeedback = feedback;
    return rs;
}

double meanOf(std::span<const PlaneF, 3> p) {
    double s = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < p[c].height(); ++y)
            for (int x = 0; x < p[c].width(); ++x) s += p[c].at(x, y);
    return s / (3.0 * p[0].width() * p[0].height());
}

bool allFinite(const Frame& f) {
    for (const PlaneRef& l : f.layers())
        for (int y = 0; y < l.plane->height(); ++y)
            for (int x = 0; x < l.plane->width(); ++x)
                if (!std::isfinite(l.plane->at(x, y))) return false;
    return true;
}

bool sameImage(const Frame& a, const Frame& b) {
    for (int c = 0; c < 3; ++c)
        if (!sameBits(a.rgb(Res::Color)[c], b.rgb(Res::Color)[c]) ||
            !sameBits(a.rgb(Res::Ssgi)[c], b.rgb(Res::Ssgi)[c]))
            return false;
    return true;
}

}  // namespace

TEST_CASE("ssgi feedback: each frame of a still camera adds a bounce -- the first has one") {
    const Scene scene = makeBuiltinScene("cornell");
    FrameInput input = FrameInput::still(scene);
    const Renderer one(smallFeedback(false)), fed(smallFeedback(true));
    const Frame single = one.renderWithoutHistory(scene, input);
    FrameHistory history;
    Frame f;
    std::vector<double> mean;
    for (int k = 0; k < 6; ++k) {
        input.frameIndex = uint32_t(k);  // fresh rays each frame, as a sequence has them
        fed.render(scene, input, history, f);
        if (k == 0) {
            // Nothing to read yet: today's one bounce, to the bit.
            CHECK(sameImage(f, single));
        }
        // What is committed: the composite's colour and the incoming diffuse light it read
        // (the denoiser's).
        REQUIRE(history.valid);
        for (int c = 0; c < 3; ++c) {
            CHECK(sameBits(history.color[c], f.rgb(Res::Color)[c]));
            CHECK(sameBits(history.diffuse[c], f.rgb(Res::DenoisedDiffuse)[c]));
        }
        mean.push_back(meanOf(f.rgb(Res::Ssgi)));
        MESSAGE("frame " << k << ": mean incoming diffuse " << mean.back());
    }
    // The second frame adds the second bounce (cornell's walls reflect about half): far more
    // than the frame-to-frame noise of a 1-ray mean over 15360 pixels; later frames stay
    // there and settle. (What is fed back is the denoised diffuse, whose history still holds
    // the earlier frames' fewer bounces, so frame 2 need not exceed frame 1: 0.209, 0.241,
    // 0.238, 0.237, 0.240, 0.239 here.)
    for (int k = 1; k < 6; ++k) CHECK(mean[k] > 1.05 * mean[0]);
    CHECK(std::abs(mean[5] - mean[4]) < 0.25 * (mean[1] - mean[0]));
    // Without feedback nothing is committed, as before.
    FrameHistory none;
    one.render(scene, input, none, f);
    CHECK_FALSE(none.valid);
    CHECK(none.diffuse[0].empty());
}

TEST_CASE("ssgi feedback: a reset and a size change give one bounce -- finite with a sky") {
    const Scene scene = makeBuiltinScene("cornell");
    const FrameInput input = FrameInput::still(scene);
    const Renderer one(smallFeedback(false)), fed(smallFeedback(true));
    const Frame single = one.renderWithoutHistory(scene, input);
    FrameHistory history;
    Frame f;
    fed.render(scene, input, history, f);
    fed.render(scene, input, history, f);
    CHECK_FALSE(sameImage(f, single));
    FrameInput cut = input;
    cut.resetHistory = true;
    fed.render(scene, cut, history, f);
    CHECK(sameImage(f, single));
    CHECK(allFinite(f));
    // Another size commits its own planes; the first renderer then has none to read.
    RenderSettings wider = smallFeedback(true);
    wider.width += 8;
    wider.height -= 8;
    Frame w;
    Renderer(wider).render(scene, input, history, w);
    CHECK(history.diffuse[0].width() == wider.width);
    CHECK(allFinite(w));
    fed.render(scene, input, history, f);
    CHECK(sameImage(f, single));
    // Under an open sky (misses bring the sky into the history), on a moving camera: finite.
    const Scene sky = makeBuiltinScene("spheres");
    FrameInput moving = FrameInput::still(sky);
    FrameHistory skyHistory;
    for (int k = 0; k < 4; ++k) {
        moving.frameIndex = uint32_t(k);
        moving.previousCamera = moving.camera;
        moving.camera.position += glm::vec3(0.05f, 0.0f, 0.0f);
        fed.render(sky, moving, skyHistory, f);
        CHECK(allFinite(f));
    }
}

TEST_CASE("ssgi feedback: a sequence has the same bits on every ISA and thread count") {
    const Scene scene = makeBuiltinScene("cornell");
    FrameInput input = FrameInput::still(scene);
    const auto sequence = [&](Isa isa, int threads) {
        RenderSettings rs = smallFeedback(true);
        rs.width = 96;
        rs.height = 64;
        rs.isa = isa;
        rs.threads = threads;
        const Renderer r(rs);
        FrameHistory h;
        Frame f;
        for (uint32_t k = 0; k < 3; ++k) {
            input.frameIndex = k;
            r.render(scene, input, h, f);
        }
        return f;
    };
    const Frame ref = sequence(Isa::Scalar, 1);
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 3})) {
            CAPTURE(isaName(isa));
            CAPTURE(threads);
            CHECK(sameImage(sequence(isa, threads), ref));
        }
}

TEST_CASE("ssgi feedback: a NaN in a frame is not committed -- the next frames stay finite") {
    // A bad input (a NaN in a vertex, a texture, a light) can make one frame non-finite; the
    // history must not keep it, or every later frame would reflect it back (SSGI feedback,
    // SSR's reprojected radiance).
    const Scene scene = makeBuiltinScene("cornell");
    const FrameInput input = FrameInput::still(scene);
    const RenderSettings rs = smallFeedback(true);
    const Renderer fed(rs);
    FrameHistory history;
    Frame f;
    fed.render(scene, input, history, f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::span<PlaneF, 3> denoised = f.rgb(Res::DenoisedDiffuse);
    const std::span<PlaneF, 3> diffuse = denoised[0].empty() ? f.rgb(Res::Ssgi) : denoised;
    for (int c = 0; c < 3; ++c) {
        f.rgb(Res::Color)[c].at(40, 30) = nan;
        f.rgb(Res::Color)[c].at(41, 30) = inf;
        diffuse[c].at(40, 30) = nan;
        diffuse[c].at(41, 30) = -inf;
    }
    // (The graph of a frame that keeps its history, as the renderer compiles it.)
    commitHistory(compileFrameGraph({rs, SceneFacts::of(scene), true, true}), f, history);
    for (int c = 0; c < 3; ++c) {
        CHECK(history.color[c].at(40, 30) == 0.0f);
        CHECK(history.color[c].at(41, 30) == 0.0f);
        CHECK(history.diffuse[c].at(40, 30) == 0.0f);
        CHECK(history.diffuse[c].at(41, 30) == 0.0f);
        CHECK(history.color[c].at(42, 30) == f.rgb(Res::Color)[c].at(42, 30));  // the rest as is
    }
    for (int k = 1; k < 4; ++k) {
        FrameInput next = input;
        next.frameIndex = uint32_t(k);
        fed.render(scene, next, history, f);
        CHECK(allFinite(f));
    }
}
