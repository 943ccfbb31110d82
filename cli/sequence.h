// The frames a command renders, in order: warm-up frames (rendered, neither written nor
// evaluated), then the sequence's frames along the shot's camera path or of the still camera,
// one history carried from each frame to the next and restarted at a camera cut. `render`
// writes the sequence's frames; `compare` and `sweep` evaluate its last.
#pragma once

#include <cstdint>
#include <string>

#include "cli/options.h"
#include "renderer/renderer.h"
#include "scenes/camera_path.h"
#include "scenes/scene.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

struct SequencePlan {
    int frames = 1;  // the sequence's frames: written (render) or evaluated, the last (compare)
    int warmup = 0;  // rendered before frame 0, from its camera, and not written
};

// Registers --frames and --warmup-frames; `framesHelp` says what the command does with them.
void addSequenceOptions(CLI::App& cmd, RenderOptions& options, const std::string& framesHelp);

// --frames and --warmup-frames, else the shot's render.frames and render.warmupFrames, else 1
// and 0; checks that the last frame's index fits in 32 bits. Throws std::invalid_argument
// naming the option and the value.
SequencePlan sequencePlanFrom(const RenderOptions& options, const SceneRequest& request);

// Equal in every field (a still camera: nothing moved between two frames).
bool sameCamera(const Camera& a, const Camera& b);

// The input of each step of a plan; step s in [0, steps()) is warm-up frame s while
// s < warmup, else sequence frame i = s - warmup.
//   frame index  firstFrame - warmup + s, modulo 2^32: the warm-up frames take the indices just
//                before the first frame's, as if the sequence had started `warmup` frames
//                earlier, so their random numbers are never a written frame's, and warm-up K
//                then frames N give the bits of the last N of K + N frames from firstFrame - K.
//   camera       frame i's: the path at frameTime(i, frames); a warm-up frame's: frame 0's (a
//                still camera converging); without a path the scene's camera throughout.
//   previous     the previous step's camera; step 0's the scene's previous camera without a
//                path, else its own camera.
//   cut          frame i > 0 with a cut of the path in (t(i-1), t(i)]: resetHistory, and the
//                previous camera is its own (no motion vectors across the cut).
class FrameSequence {
public:
    // Keeps references to the request's scene and path (loadScene has run).
    FrameSequence(const SceneRequest& request, SequencePlan plan);

    const SequencePlan& plan() const { return plan_; }
    int steps() const { return plan_.warmup + plan_.frames; }
    bool isWarmup(int step) const { return step < plan_.warmup; }
    int frameOf(int step) const { return step - plan_.warmup; }  // negative while warming up
    FrameInput input(int step) const;
    // The world rays every input names (FrameInput::world); null: none.
    void useWorld(const WorldRays* world) { world_ = world; }
    // The step looks from the previous step's camera and is not at a cut (step 0: false): the
    // two images differ only by noise, so their difference is flicker.
    bool stillSincePrevious(int step) const;

private:
    Camera cameraAt(int step) const;
    bool cutAt(int step) const;

    const Scene& scene_;
    const CameraPath& path_;
    uint32_t firstFrame_ = 0;
    SequencePlan plan_;
    const WorldRays* world_ = nullptr;
};

}  // namespace ssrt::cli
