// One screen-space setting measured on both axes: its time (per pass, median over repeated
// renders) and its accuracy (every ray it marched checked by Embree, its image against the
// reference, per component). What `ssrt compare` prints and each row of `ssrt sweep`.
#pragma once

#include <vector>

#include "renderer/renderer.h"
#include "truth/image_error.h"
#include "truth/ray_check.h"
#include "truth/reference_image.h"
#include "world/embree_scene.h"

namespace ssrt {

// Image error of the frame against the reference: the exposed colour, and the parts before
// exposure (reference_image.h, FrameParts) so a user sees which part is wrong.
struct ErrorTable {
    ImageError color, direct, specular, diffuse;
    bool parts = false;  // direct, specular and diffuse measured (not with both passes off)
};

// The frame's exposed colour against the reference's, and its parts when it has them.
ErrorTable imageErrors(const Frame& frame, const ReferenceImage& reference);
// One reference against another, every part (`ssrt compare`'s model error: the one-bounce
// reference against the full one is what no one-bounce method can get right).
ErrorTable referenceErrors(const ReferenceImage& image, const ReferenceImage& reference);

struct EvaluationSettings {
    int repeats = 3;         // timed renders (the median of each pass is kept), >= 1
    RayCheckSettings check;  // maxDistance is taken from the render settings
    bool planes = true;      // the frame's check planes (Res::SsrCheck, Res::SsgiCheck): sample 0's
    void validate() const;   // throws std::invalid_argument naming the field
};

struct Evaluation {
    std::vector<PassTime> passes;  // median ms per pass over the repeats, in frame order
    double frameMs = 0.0;          // median over the repeats of the sum of the passes
    FrameStats stats;              // of the checked render (counters)
    bool ssr = false, ssgi = false;
    RayCheckTable ssrCheck, ssgiCheck;  // every sample's rays, errors sorted
    ErrorTable error;
    double marchMraysPerSecond = 0.0;   // rays marched (both passes) / march time (medians)
    double embreeMraysPerSecond = 0.0;  // the same rays / Embree's traversal time
    double marchVsEmbree() const {      // > 1: screen space is the faster per ray
        return embreeMraysPerSecond > 0.0 ? marchMraysPerSecond / embreeMraysPerSecond : 0.0;
    }
};

// Renders `repeats` timed frames (no checks), then one more whose traced samples Embree
// checks (the same rays: rendering is deterministic); compares its image with `reference`.
// `frame` receives the checked render. The Embree checks run on settings.threads workers.
Evaluation evaluate(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                    const RenderSettings& settings, const ReferenceImage& reference,
                    const EvaluationSettings& evalSettings, Frame& frame);

// The same for one frame of a sequence (ssrt compare --frames): `history` holds what the
// frames before it committed, and this frame, rendered once with it, commits into it as
// Renderer::render does. A history cannot be read twice, so there are no timed repeats: the
// pass times are the median over `earlierRuns` (the pass times of the frames just before, as
// the caller rendered them) and this frame's own.
Evaluation evaluateSequenceFrame(const EmbreeScene& embree, const Scene& scene,
                                 const FrameInput& input, const RenderSettings& settings,
                                 const ReferenceImage& reference,
                                 const EvaluationSettings& evalSettings,
                                 const std::vector<std::vector<PassTime>>& earlierRuns,
                                 FrameHistory& history, Frame& frame);

// The world-space alternative measured as a method of its own (ssrt sweep --embree-spp): the
// frame with its SSR and SSGI traced by Embree instead of marched, `world.spp` rays each
// (renderReference over the frame: nothing guessed, no denoiser), beside the screen-space
// settings on the error-against-time chart. Its passes are those of the frame that stay
// (raster, G-buffer, direct light: both trace passes off), medians of `repeats` renders, and
// kEmbreeTracePass (renderReference's whole time, the median of `repeats`); frameMs is their
// sum. Its error is its image's against `reference`, overall and per part; no ray checks
// (nothing is marched). Its random numbers are those of `input`'s frame index: give it
// another index than the reference's, or its rays are the reference's first samples and its
// error is biased low.
inline constexpr const char* kEmbreeTracePass = "embree trace";
Evaluation evaluateEmbreeMethod(const EmbreeScene& embree, const Scene& scene,
                                const FrameInput& input, const RenderSettings& settings,
                                const ReferenceSettings& world, const ReferenceImage& reference,
                                const EvaluationSettings& evalSettings);

}  // namespace ssrt
