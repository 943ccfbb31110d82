// A sequence measured against the Embree truth, for `ssrt compare --frames` and `ssrt sweep
// --frames`: each frame's colour error against the reference of its own camera, the flicker
// between consecutive frames of a still camera, and the last frame evaluated in full (ray
// checks, per-part errors, times: truth/evaluation.h).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/reference_cache.h"
#include "cli/sequence.h"
#include "truth/evaluation.h"

namespace ssrt::cli {

// Refuses a frame without a surface pixel (std::runtime_error), as work that could not be
// done: its reference is the same sky, so its relMSE would be 0 and every share 0 %, which
// reads as a perfect result. `compare` and `sweep` both ask before writing anything.
void requireSurface(const Frame& frame);

// One frame's row of the per-frame report.
struct FrameError {
    int frame = 0;            // in the sequence: 0 is the first after the warm-up
    uint32_t frameIndex = 0;  // FrameInput::frameIndex
    bool cut = false;         // at a camera cut: history restarted
    double relMse = 0.0;      // the exposed colour against this frame's reference
    // frameFlicker against the frame rendered before it (the last warm-up frame for frame 0),
    // when both look from the same camera; none where the camera moved, at a cut, and for the
    // first frame rendered. A moving camera's frames differ by motion as well as noise, and
    // telling the two apart needs reprojection, which is the denoiser's business: not guessed.
    std::optional<double> flicker;
};

struct SequenceEvaluation {
    Evaluation last;                 // the last frame, as compare prints it
    ReferenceImage reference;        // the last frame's
    std::vector<FrameError> frames;  // one per frame of the sequence, the warm-up left out
};

// What the evaluation needs besides the sequence and its settings.
struct TruthContext {
    const EmbreeScene& embree;
    const Scene& scene;
    ReferenceSettings reference;  // maxDistance included
    ReferenceSource source;
    EvaluationSettings evaluation;
    std::ostream* progress = nullptr;  // a line per frame of a sequence; null: quiet
};

// Flicker between two frames of a still camera: the mean absolute change of the exposed
// colour over the mean reference colour,
//   sum over pixels and RGB of |current - previous| / sum over pixels and RGB of reference,
// summed in double in row order (the same bits every run). 0 for equal frames; a NaN in
// either frame makes it NaN; none when the reference is black.
std::optional<double> frameFlicker(const PlaneF (&current)[3], const PlaneF (&previous)[3],
                                   const PlaneF (&reference)[3]);

// Renders the sequence with `settings` (one Renderer, one history) and evaluates it.
// References are rendered over `referenceRender` (its SSR sampler; see referenceFor), one per
// camera: frame i's at its camera and frame index, unless frame i-1 looked from the same
// camera, whose reference then serves it (a still camera: one, frame 0's, as a single-frame
// compare has). A single frame without warm-up is evaluate() itself (timed repeats without
// history); otherwise the last frame is evaluateSequenceFrame() with the pass times of the
// frames before it (warm-up included, at most evaluation.repeats frames in all).
SequenceEvaluation evaluateSequence(const TruthContext& truth, const FrameSequence& sequence,
                                    const RenderSettings& settings,
                                    const RenderSettings& referenceRender, Frame& frame);

// The per-frame table (frame, frame index, relMSE, flicker, cut) for the terminal.
void printFrameErrors(std::ostream& out, const std::vector<FrameError>& frames);
// The per-frame CSV: the header line, and one line per frame; with `setting`, a first column
// naming the row of sweep's CSV the frames belong to (0 = its first setting).
std::string frameErrorsCsvHeader(bool withSetting);
// The per-frame table for --json: [{frame, frame_index, cut, rel_mse, flicker (null: none)}].
nlohmann::ordered_json frameErrorsJson(const std::vector<FrameError>& frames);
std::string frameErrorsCsvRows(const std::vector<FrameError>& frames,
                               std::optional<int> setting = std::nullopt);

}  // namespace ssrt::cli
