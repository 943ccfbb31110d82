// The embeddable entry point: a Renderer built once from immutable settings renders a whole
// sequence, frame by frame: scene + per-frame input (+ the caller's history) in, a Frame of
// typed planes (renderer/frame.h) out.
#pragma once

#include <cstdint>
#include <functional>

#include "renderer/frame.h"
#include "renderer/render_cancel.h"
#include "renderer/settings.h"
#include "scenes/scene.h"

namespace ssrt {

// The screen-space pass a traced sample belongs to.
enum class TracePass { Ssr, Ssgi };

// Sees every sample's rays and what the march found, right after the march and before the
// resolve, on the thread that called render(), in pass then sample order. Its time is not in
// any pass time. `ssrt compare` hands them to Embree (truth/ray_check.h), so the
// truth is asked about the very rays that were marched. `half` is null where the batches are
// the frame's pixels (the full and checkerboard layouts); with SSGI's half-resolution layout
// it is the half frame they were generated and marched on (its camera and chosen pixels,
// trace/trace_layout.h).
using TraceObserver = std::function<void(TracePass pass, int sample, const RayBatch& rays,
                                         const MarchResult& march, const HalfFrame* half)>;

// What changes from one frame of a sequence to the next; the settings do not.
struct FrameInput {
    uint32_t frameIndex = 0;  // feeds the counter-based RNG (core/rng.h)
    Camera camera;
    Camera previousCamera;      // where the camera was last frame: motion vectors
    bool resetHistory = false;  // a cut: the history is not read (and is replaced)
    // false: the history is read but left as it was, for a frame no later frame reads (the
    // last of a sequence): the same image, without making the new history.
    bool replaceHistory = true;
    // Optional: a flag read between the frame's passes; raised, the render stops at the next
    // and throws RenderCancelled (renderer/render_cancel.h). Not part of the image.
    const std::atomic<bool>* cancel = nullptr;
    // The scene's world rays (trace/world_rays.h; world/embree_world_rays.h makes them from
    // the same scene): needed by a signal traced in mixed or world mode, else unread.
    const WorldRays* world = nullptr;

    // The scene's own cameras.
    static FrameInput still(const Scene& scene, uint32_t frameIndex = 0) {
        return {frameIndex, scene.camera, scene.previousCamera, false, true};
    }
};

class Renderer {
public:
    explicit Renderer(RenderSettings settings = {});

    const RenderSettings& settings() const { return settings_; }

    // One frame of a sequence. Reads `history` (unless input.resetHistory, or it is not of
    // this frame's size) and, after the composite, commits this frame's into it when the
    // settings read it again (SSR with HitRadiance::Reprojected, SSGI with ssgiFeedback). Renders
    // into `frame`, reusing its planes and scratch buffers when their sizes match. Safe to call
    // from several threads at once with different frames and histories; a frame or history
    // another call is using is refused (std::logic_error naming it), never raced on. `observer`
    // (optional) sees every traced sample. The planes: renderer/frame.h.
    void render(const Scene& scene, const FrameInput& input, FrameHistory& history, Frame& frame,
                const TraceObserver* observer = nullptr) const;
    Frame render(const Scene& scene, const FrameInput& input, FrameHistory& history) const;

    // A frame that neither reads nor leaves a history (a still, or each frame on its own).
    void renderWithoutHistory(const Scene& scene, const FrameInput& input, Frame& frame,
                              const TraceObserver* observer = nullptr) const;
    Frame renderWithoutHistory(const Scene& scene, const FrameInput& input) const;
    Frame renderWithoutHistory(const Scene& scene) const {
        return renderWithoutHistory(scene, FrameInput::still(scene));
    }

private:
    void renderFrame(const Scene& scene, const FrameInput& input, FrameHistory* history,
                     Frame& frame, const TraceObserver* observer) const;

    RenderSettings settings_;
};

}  // namespace ssrt
