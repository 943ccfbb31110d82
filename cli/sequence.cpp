#include "cli/sequence.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <stdexcept>

#include "scenes/shot.h"

namespace ssrt::cli {

void addSequenceOptions(CLI::App& cmd, RenderOptions& o, const std::string& framesHelp) {
    // Remembered only when typed, so that the shot decides otherwise.
    cmd.add_option_function<std::string>(
           "--frames", [&o](const std::string& v) { o.frames = v; },
           "Frames, 1 to " + std::to_string(kMaxShotFrames) + ": " + framesHelp)
        ->type_name("INT")
        ->default_str("1");
    cmd.add_option_function<std::string>(
           "--warmup-frames", [&o](const std::string& v) { o.warmupFrames = v; },
           "Frames rendered before the first, 0 to " + std::to_string(kMaxShotFrames) +
               ", from the first frame's camera, carrying history, neither written nor "
               "evaluated (a still camera converging); their frame indices are the ones just "
               "before --frame's, modulo 2^32")
        ->type_name("INT")
        ->default_str("0");
}

SequencePlan sequencePlanFrom(const RenderOptions& o, const SceneRequest& request) {
    SequencePlan plan;
    const std::optional<Shot>& shot = request.shot;
    if (shot && shot->render.frames) plan.frames = *shot->render.frames;
    if (shot && shot->render.warmupFrames) plan.warmup = *shot->render.warmupFrames;
    if (o.frames) plan.frames = int(parseInteger("--frames", *o.frames, 1, kMaxShotFrames));
    if (o.warmupFrames)
        plan.warmup = int(parseInteger("--warmup-frames", *o.warmupFrames, 0, kMaxShotFrames));
    if (request.firstFrame + uint64_t(plan.frames - 1) > uint64_t(kMaxFrame))
        throw std::invalid_argument("--frame: " + std::to_string(request.firstFrame) + " + " +
                                    std::to_string(plan.frames) + " frames passes " +
                                    std::to_string(kMaxFrame));
    return plan;
}

bool sameCamera(const Camera& a, const Camera& b) {
    return a.position == b.position && a.target == b.target && a.up == b.up && a.fovY == b.fovY &&
           a.nearZ == b.nearZ && a.farZ == b.farZ;
}

FrameSequence::FrameSequence(const SceneRequest& request, SequencePlan plan)
    : scene_(request.scene), path_(request.path), firstFrame_(request.firstFrame), plan_(plan) {}

Camera FrameSequence::cameraAt(int step) const {
    if (path_.empty()) return scene_.camera;
    const int i = std::max(frameOf(step), 0);
    return path_.at(path_.frameTime(i, plan_.frames), scene_.camera);
}

bool FrameSequence::cutAt(int step) const {
    const int i = frameOf(step);
    if (i < 1 || path_.empty()) return false;
    return path_.cutBetween(path_.frameTime(i - 1, plan_.frames), path_.frameTime(i, plan_.frames));
}

FrameInput FrameSequence::input(int step) const {
    FrameInput in;
    in.world = world_;
    // Unsigned arithmetic wraps: warm-up frames before frame index 0 count down from 2^32 - 1.
    in.frameIndex = firstFrame_ - uint32_t(plan_.warmup) + uint32_t(step);
    in.camera = cameraAt(step);
    if (cutAt(step)) {
        in.resetHistory = true;
        in.previousCamera = in.camera;
    } else if (step > 0) {
        in.previousCamera = cameraAt(step - 1);
    } else {
        in.previousCamera = path_.empty() ? scene_.previousCamera : in.camera;
    }
    return in;
}

bool FrameSequence::stillSincePrevious(int step) const {
    return step > 0 && !cutAt(step) && sameCamera(cameraAt(step), cameraAt(step - 1));
}

}  // namespace ssrt::cli
