#include "cli/sequence_evaluation.h"

#include <cmath>
#include <deque>
#include <iomanip>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "cli/compare_command.h"
#include "cli/json_output.h"

namespace ssrt::cli {

void requireSurface(const Frame& frame) {
    const PlaneF& viewZ = frame.gbuffer.viewZ;
    for (int y = 0; y < viewZ.height(); ++y)
        for (int x = 0; x < viewZ.width(); ++x)
            if (viewZ.at(x, y) > 0.0f) return;
    throw std::runtime_error(
        "the frame shows no surface (every pixel is sky): there is no ray to check and the "
        "image error would be the sky's against itself; aim the camera at the scene");
}

namespace {

void clonePlanes(std::span<const PlaneF, 3> from, PlaneF (&to)[3]) {
    for (int c = 0; c < 3; ++c) to[c] = from[c].clone();
}

double colorRelMse(const Frame& frame, const ReferenceImage& ref) {
    const auto imageRgb = frame.rgb(Res::Color);
    const PlaneF* image[3] = {&imageRgb[0], &imageRgb[1], &imageRgb[2]};
    const PlaneF* reference[3] = {&ref.color[0], &ref.color[1], &ref.color[2]};
    return imageError(image, reference).relMse;
}

// The reference of the frame `input` describes, or `current` itself when `input` looks from
// the camera `current` was rendered for.
struct FrameReference {
    bool valid = false;
    Camera camera;
    ReferenceImage image;
};

// `frame` names the sequence's frame in the progress line (none: a single frame).
void updateReference(const TruthContext& t, const FrameInput& input,
                     const RenderSettings& referenceRender, std::optional<int> frame,
                     FrameReference& current) {
    if (current.valid && sameCamera(current.camera, input.camera)) return;
    bool fromCache = false;
    current.image =
        referenceFor(t.embree, t.scene, input, referenceRender, t.reference, t.source, fromCache);
    current.camera = input.camera;
    current.valid = true;
    if (!t.progress) return;
    *t.progress << "reference: " << (fromCache ? "from the cache" : "rendered") << " ("
                << describeReference(t.reference) << ")";
    if (frame)
        *t.progress << " for frame " << *frame << " (frame index " << input.frameIndex << ")";
    *t.progress << "\n";
}

}  // namespace

std::optional<double> frameFlicker(std::span<const PlaneF, 3> current, const PlaneF (&previous)[3],
                                   const PlaneF (&reference)[3]) {
    double change = 0.0, level = 0.0;
    for (int c = 0; c < 3; ++c) {
        const PlaneF &a = current[c], &b = previous[c], &r = reference[c];
        for (int y = 0; y < a.height(); ++y) {
            const float *pa = a.row(y), *pb = b.row(y), *pr = r.row(y);
            for (int x = 0; x < a.width(); ++x) {
                change += std::fabs(double(pa[x]) - double(pb[x]));
                level += double(pr[x]);
            }
        }
    }
    if (!(level > 0.0)) return std::nullopt;
    return change / level;
}

SequenceEvaluation evaluateSequence(const TruthContext& t, const FrameSequence& sequence,
                                    const RenderSettings& settings,
                                    const RenderSettings& referenceRender, Frame& frame) {
    SequenceEvaluation out;
    FrameReference reference;
    const SequencePlan& plan = sequence.plan();
    if (plan.frames == 1 && plan.warmup == 0) {
        // One frame: exactly what compare did before sequences (timed repeats, no history).
        const FrameInput input = sequence.input(0);
        updateReference(t, input, referenceRender, std::nullopt, reference);
        out.last =
            evaluate(t.embree, t.scene, input, settings, reference.image, t.evaluation, frame);
        out.frames.push_back({0, input.frameIndex, false, out.last.error.color.relMse, {}});
        out.reference = std::move(reference.image);
        return out;
    }

    const Renderer renderer(settings);
    FrameHistory history;
    std::deque<std::vector<PassTime>> runs;  // the pass times of the frames just before
    const std::size_t earlier = std::size_t(t.evaluation.repeats - 1);
    PlaneF previous[3];
    for (int step = 0; step < sequence.steps(); ++step) {
        // The reference's cancel flag (ssrt sweep's interrupt) stops the frames between too.
        if (t.reference.cancel && t.reference.cancel->load()) throw ReferenceCancelled();
        const FrameInput input = sequence.input(step);
        const int i = sequence.frameOf(step);
        const bool last = step == sequence.steps() - 1;
        if (!sequence.isWarmup(step)) updateReference(t, input, referenceRender, i, reference);
        if (last) {
            const std::vector<std::vector<PassTime>> earlierRuns(runs.begin(), runs.end());
            out.last = evaluateSequenceFrame(t.embree, t.scene, input, settings, reference.image,
                                             t.evaluation, earlierRuns, history, frame);
        } else {
            renderer.render(t.scene, input, history, frame);
            runs.push_back(frame.stats.passes);
            if (runs.size() > earlier) runs.pop_front();
        }
        if (!sequence.isWarmup(step)) {
            FrameError row{
                i, input.frameIndex, input.resetHistory, colorRelMse(frame, reference.image), {}};
            if (sequence.stillSincePrevious(step))
                row.flicker = frameFlicker(frame.rgb(Res::Color), previous, reference.image.color);
            out.frames.push_back(row);
        }
        if (t.progress) {
            if (sequence.isWarmup(step)) {
                *t.progress << "warm-up " << (step + 1) << "/" << plan.warmup << "\n";
            } else {
                const FrameError& row = out.frames.back();
                *t.progress << "frame " << (i + 1) << "/" << plan.frames << ": relMSE "
                            << row.relMse;
                if (row.flicker) *t.progress << ", flicker " << *row.flicker;
                *t.progress << (row.cut ? " (camera cut)" : "") << "\n";
            }
        }
        if (!last) clonePlanes(frame.rgb(Res::Color), previous);
    }
    out.reference = std::move(reference.image);
    return out;
}

void printFrameErrors(std::ostream& out, const std::vector<FrameError>& frames) {
    std::ios saved(nullptr);
    saved.copyfmt(out);
    out << std::right << std::setw(7) << "frame" << std::setw(12) << "index" << std::setw(13)
        << "relMSE" << std::setw(13) << "flicker"
        << "\n";
    for (const FrameError& f : frames) {
        out << std::setw(7) << f.frame << std::setw(12) << f.frameIndex << std::scientific
            << std::setprecision(3) << std::setw(13) << f.relMse << std::setw(13);
        if (f.flicker) out << *f.flicker;
        else out << "-";
        out << std::defaultfloat << (f.cut ? "  camera cut" : "") << "\n";
    }
    out << "  flicker = sum |frame - previous frame| / sum reference, over pixels and RGB (a "
           "still camera only)\n";
    out.copyfmt(saved);
}

Json frameErrorsJson(const std::vector<FrameError>& frames) {
    Json rows = Json::array();
    for (const FrameError& f : frames)
        rows.push_back({{"frame", f.frame},
                        {"frame_index", f.frameIndex},
                        {"cut", f.cut},
                        {"rel_mse", f.relMse},
                        {"flicker", f.flicker ? Json(*f.flicker) : Json(nullptr)}});
    return rows;
}

std::string frameErrorsCsvHeader(bool withSetting) {
    return std::string(withSetting ? "setting," : "") + "frame,frame_index,cut,relmse,flicker\n";
}

std::string frameErrorsCsvRows(const std::vector<FrameError>& frames, std::optional<int> setting) {
    std::ostringstream s;
    s << std::setprecision(9);
    for (const FrameError& f : frames) {
        if (setting) s << *setting << ',';
        s << f.frame << ',' << f.frameIndex << ',' << (f.cut ? 1 : 0) << ',' << f.relMse << ',';
        if (f.flicker) s << *f.flicker;
        s << "\n";
    }
    return s.str();
}

}  // namespace ssrt::cli
