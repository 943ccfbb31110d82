// `ssrt compare`: one scene and one screen-space setting against the Embree truth. Prints the
// BVH build, the classification of every traced ray per pass with its hit-position error,
// the image error against the reference (overall and per component) and the pass times;
// optionally writes the frame with the reference and the per-pixel checks as EXR layers.
// With --frames or --warmup-frames it renders a sequence (cli/sequence.h), evaluates its last
// frame so, and reports each frame's colour error and flicker (cli/sequence_evaluation.h).
#pragma once

#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "cli/reference_cache.h"
#include "cli/render_command.h"
#include "cli/sequence.h"
#include "truth/evaluation.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

// The largest --reference-spp (and sweep's --embree-spp).
inline constexpr long long kMaxReferenceSpp = 65536;

// What compare and sweep add to the render options: the reference, the checks, the cache.
struct TruthOptions {
    std::string referenceSpp = "64";
    std::string referenceBounces = "full";  // a count, or full (ReferenceSettings::kConverged)
    std::string visibility = "embree";
    std::string pixelTolerance, depthTolerance;  // filled from RayCheckSettings{}
    std::string repeats = "3";
    std::optional<std::string> cacheDir;
    std::optional<std::string> perFrame;  // --per-frame: the per-frame CSV of a sequence
    bool noCache = false;
    bool quiet = false;
    TruthOptions();
};

struct CompareOptions {
    RenderOptions render;
    TruthOptions truth;
    std::optional<std::string> output;  // .exr (frame + reference + checks) or .png
};

// "3 frames after 2 warm-up frames", for progress and headings.
std::string sequenceText(const SequencePlan& plan);
// The render settings compare and sweep start from: 640x360 (a reference renders in seconds).
RenderSettings truthDefaults();
// Where the reference comes from: the cache (--cache-dir, else defaultCacheDir(); none with
// --no-cache) and progress on `err` unless quiet.
ReferenceSource referenceSourceFrom(const TruthOptions& options, std::ostream& err);

// Registers the reference's options (--reference-spp, --reference-bounces, --visibility), the
// cache's and --quiet (`ssrt reference`).
void addReferenceOptions(CLI::App& cmd, TruthOptions& options);
// addReferenceOptions, then the checks' options, --repeats and --per-frame (compare, sweep).
void addTruthOptions(CLI::App& cmd, TruthOptions& options);
// The reference's settings from the options: the truth is all the light (--reference-bounces
// full, the default), whatever the method models, so that every method and setting is judged
// against one image; its maxDistance is the march's, which the caller sets once the scene
// (its diagonal) is known.
ReferenceSettings referenceSettingsFrom(const TruthOptions& options);
// "64 spp, all bounces", "64 spp, one bounce" or "64 spp, N bounces": how compare and sweep
// name a reference.
std::string describeReference(const ReferenceSettings& settings);
// --reference-bounces' value as the CSV's reference_bounces column writes it: full or a count.
std::string bouncesName(int bounces);
EvaluationSettings evaluationSettingsFrom(const TruthOptions& options);

CLI::App* addCompareCommand(CLI::App& app, CompareOptions& options);
int runCompare(const CompareOptions& options, std::ostream& out, std::ostream& err);

// The tables compare prints, for one evaluation (also used by tests).
void printEvaluation(std::ostream& out, const BvhStats& bvh, const Evaluation& ev);
// The same figures for --json, unrounded (docs/truth.md): {bvh, ray_check, image_error,
// pass_times, frame_ms, march_mrays_per_second, embree_mrays_per_second, march_vs_embree}.
nlohmann::ordered_json evaluationJson(const BvhStats& bvh, const Evaluation& ev);

}  // namespace ssrt::cli
