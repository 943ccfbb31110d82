#include "cli/compare_command.h"

#include <CLI/CLI.hpp>
#include <functional>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/interrupt.h"
#include "cli/json_output.h"
#include "cli/options.h"
#include "cli/reference_cache.h"
#include "cli/sequence.h"
#include "cli/sequence_evaluation.h"
#include "io/image_io.h"
#include "world/embree_world_rays.h"

namespace ssrt::cli {

namespace {

constexpr int kLabel = 22, kValue = 13;

std::string formatFloat(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::optional<ReferenceSettings::Visibility> parseVisibility(std::string_view s) {
    if (s == "embree") return ReferenceSettings::Visibility::Embree;
    if (s == "shadowmap") return ReferenceSettings::Visibility::ShadowMap;
    return std::nullopt;
}

// One row of the ray-check table: its label (the JSON key is jsonKey(label)), its value for
// a pass that ran, and the decimals the text gives it (an integer prints whole).
struct CheckRow {
    std::string label;
    std::function<Json(const RayCheckTable&)> value;
    int decimals = 0;
};

// The ray-check table's rows, in order: rays, each class's share, the hit errors' quantiles.
std::vector<CheckRow> checkRows() {
    std::vector<CheckRow> rows = {{"rays", [](const RayCheckTable& t) { return Json(t.rays); }}};
    for (int c = 1; c < kRayClassCount; ++c) {
        const RayClass rc = RayClass(c);
        rows.push_back({std::string(rayClassName(rc)) + " %",
                        [rc](const RayCheckTable& t) { return Json(100.0 * t.share(rc)); }, 2});
    }
    // How the rays were answered (mixed and world tracing): on screen (the march, or in mixed
    // the hits the proof holds) or in world space, and how often each disagrees with Embree.
    const auto percent = [](uint64_t n, uint64_t of) {
        return of ? 100.0 * double(n) / double(of) : 0.0;
    };
    rows.push_back({"world rays %",
                    [=](const RayCheckTable& t) { return Json(percent(t.worldRays(), t.rays)); },
                    2});
    rows.push_back(
        {"screen false hit %",
         [](const RayCheckTable& t) { return Json(100.0 * t.screenShare(RayClass::FalseHit)); },
         3});
    rows.push_back({"world not agreed %",
                    [=](const RayCheckTable& t) {
                        const uint64_t agreed =
                            t.world[int(RayClass::Agreed)] + t.world[int(RayClass::TrueMiss)];
                        return Json(percent(t.worldRays() - agreed, t.worldRays()));
                    },
                    3});
    const auto err = [&](const char* label, bool pixels, double q) {
        rows.push_back({label,
                        [=](const RayCheckTable& t) {
                            return Json(
                                RayCheckTable::quantile(pixels ? t.pixelError : t.depthError, q));
                        },
                        3});
    };
    err("hit error px, p50", true, 0.5);
    err("hit error px, p95", true, 0.95);
    err("hit error px, max", true, 1.0);
    err("depth error rel, p50", false, 0.5);
    err("depth error rel, p95", false, 0.95);
    return rows;
}

// The ray-check table: one column per pass that ran.
void printChecks(std::ostream& out, const Evaluation& ev) {
    const RayCheckTable* tables[2] = {ev.ssr ? &ev.ssrCheck : nullptr,
                                      ev.ssgi ? &ev.ssgiCheck : nullptr};
    out << std::left << std::setw(kLabel + 2) << "ray check (Embree)" << std::right
        << std::setw(kValue) << "ssr" << std::setw(kValue) << "ssgi"
        << "\n";
    for (const CheckRow& r : checkRows()) {
        out << "  " << std::left << std::setw(kLabel) << r.label << std::right;
        for (const RayCheckTable* t : tables) {
            out << std::setw(kValue);
            if (!t) out << "-";
            else if (const Json v = r.value(*t); v.is_number_float())
                out << std::fixed << std::setprecision(r.decimals) << v.get<double>();
            else out << v.dump();
        }
        out << "\n";
    }
    out << std::defaultfloat;
}

// One pass's column of the ray-check table: {key: value}; null for a pass that did not run.
Json checksJson(bool ran, const RayCheckTable& t) {
    if (!ran) return nullptr;
    Json out = Json::object();
    for (const CheckRow& r : checkRows()) out[jsonKey(r.label)] = r.value(t);
    return out;
}

void printErrors(std::ostream& out, const ErrorTable& e) {
    out << std::left << std::setw(kLabel + 2) << "image error" << std::right << std::setw(kValue)
        << "relMSE" << std::setw(kValue) << "RMSE" << std::setw(kValue) << "non-finite"
        << "\n";
    const auto row = [&](const char* label, const ImageError& x) {
        out << "  " << std::left << std::setw(kLabel) << label << std::right << std::scientific
            << std::setprecision(3) << std::setw(kValue) << x.relMse << std::setw(kValue) << x.rmse
            << std::defaultfloat << std::setw(kValue) << x.nonFinite << "\n";
    };
    row("color (exposed)", e.color);
    if (e.parts) {
        row("direct", e.direct);
        row("specular", e.specular);
        row("diffuse", e.diffuse);
    }
    out << "  relMSE = mean over pixels and RGB of (I - R)^2 / (R^2 + 0.01)\n";
}

// Beside the error against all the light: the frame against the one-bounce reference (the
// method's error within its model) and that reference against the full one (the model's
// own error, which no one-bounce method can remove). relMSE is not additive, so the total
// is not their sum; each says which of the two to work on.
void printModelErrors(std::ostream& out, const ErrorTable& method, const ErrorTable& model) {
    out << std::left << std::setw(kLabel + 2) << "one-bounce model" << std::right
        << std::setw(kValue) << "method" << std::setw(kValue) << "model"
        << "\n";
    const auto row = [&](const char* label, const ImageError& a, const ImageError& b) {
        out << "  " << std::left << std::setw(kLabel) << label << std::right << std::scientific
            << std::setprecision(3) << std::setw(kValue) << a.relMse << std::setw(kValue)
            << b.relMse << std::defaultfloat << "\n";
    };
    row("color (exposed)", method.color, model.color);
    if (method.parts) {
        row("direct", method.direct, model.direct);
        row("specular", method.specular, model.specular);
        row("diffuse", method.diffuse, model.diffuse);
    }
    out << "  relMSE; method: the frame against the one-bounce reference; model: the one-bounce "
           "reference against all bounces'\n";
}

// A pass without a checked ray is warned about: the frame is still judged by the other pass
// and the image error (a frame without surface is refused: requireSurface).
// `hidden`: where the pass draws no ray because the composite would not show what it found.
void warnUnchecked(std::ostream& err, const char* pass, const char* flag, const char* hidden,
                   bool on, const RayCheckTable& check, const RayGenStats& gen) {
    if (!on) {
        err << "ssrt: warning: " << pass << " is off (" << flag
            << "): none of its rays is checked\n";
        return;
    }
    if (check.rays > 0) return;
    err << "ssrt: warning: " << pass << " traced no ray, so none is checked (its shares read 0 %): "
        << "of " << gen.pixels << " surface pixels " << gen.hidden << " are " << hidden << ", "
        << gen.belowSurface << " drew a ray below the surface\n";
}

// The reference as extra layers of the frame (the first sample's checks are its own already:
// Res::SsrCheck, Res::SsgiCheck).
void appendTruthPlanes(Frame& frame, const ReferenceImage& ref) {
    const char* suffix[3] = {".R", ".G", ".B"};
    for (int c = 0; c < 3; ++c) {
        frame.extraLayers.push_back({std::string("ref.color") + suffix[c], ref.color[c].clone()});
        frame.extraLayers.push_back({std::string("ref.ssr") + suffix[c], ref.ssr[c].clone()});
        frame.extraLayers.push_back({std::string("ref.ssgi") + suffix[c], ref.ssgi[c].clone()});
    }
}

}  // namespace

std::string sequenceText(const SequencePlan& plan) {
    return plural(plan.frames, "frame") +
           (plan.warmup > 0 ? " after " + plural(plan.warmup, "warm-up frame") : std::string());
}

RenderSettings truthDefaults() {
    RenderSettings d;
    d.width = 640;
    d.height = 360;
    return d;
}

ReferenceSource referenceSourceFrom(const TruthOptions& o, std::ostream& err) {
    ReferenceSource source;
    source.progress = o.quiet ? nullptr : &err;
    source.warnings = &err;
    if (!o.noCache) {
        const std::string dir = o.cacheDir ? *o.cacheDir : defaultCacheDir();
        if (!dir.empty()) source.cacheDir = dir;
    }
    return source;
}

TruthOptions::TruthOptions() {
    const RayCheckSettings d;
    pixelTolerance = formatFloat(d.pixelTolerance);
    depthTolerance = formatFloat(d.depthTolerance);
}

namespace {

void addTruthOption(CLI::App& cmd, const std::string& flags, std::string& value,
                    const std::string& type, const std::string& help) {
    cmd.add_option(flags, value, help)->type_name(type)->capture_default_str()->group("Truth");
}

}  // namespace

void addReferenceOptions(CLI::App& cmd, TruthOptions& o) {
    const auto add = [&](const std::string& flags, std::string& value, const std::string& type,
                         const std::string& help) {
        addTruthOption(cmd, flags, value, type, help);
    };
    add("--reference-spp", o.referenceSpp, "INT",
        "Rays per pixel of the reference image for each of SSR and SSGI, 1 to " +
            std::to_string(kMaxReferenceSpp));
    add("--reference-bounces", o.referenceBounces, "INT|full",
        "Diffuse bounces of the reference's SSGI paths: full (all the light: each path goes on "
        "until its throughput is below 0.1 %), or 1 to " +
            std::to_string(ReferenceSettings::kMaxBounces) +
            " (1 is one-bounce SSGI's own model; N matches N frames of --ssgi-feedback). With "
            "full, compare also reports the frame against the one-bounce reference and that "
            "reference's own error, so the method's error and the one-bounce model's are told "
            "apart");
    add("--visibility", o.visibility, "KIND",
        "Sun visibility in the reference: embree (shadow rays, the truth) or shadowmap (the "
        "frame's own shadow map, to isolate the tracing errors)");
    cmd.add_option_function<std::string>(
           "--cache-dir", [&o](const std::string& v) { o.cacheDir = v; },
           "Where reference images are cached, by a hash of the scene and settings (a folder "
           "many processes and machines may share)")
        ->type_name("DIR")
        ->default_str("$SSRT_CACHE_DIR, else $XDG_CACHE_HOME/ssrt, else ~/.cache/ssrt")
        ->group("Truth");
    cmd.add_flag("--no-cache", o.noCache, "Render the reference even if cached, and keep no copy")
        ->group("Truth");
    cmd.add_flag("-q,--quiet", o.quiet, "No progress lines on stderr (warnings still print)");
}

void addTruthOptions(CLI::App& cmd, TruthOptions& o) {
    addReferenceOptions(cmd, o);
    const auto add = [&](const std::string& flags, std::string& value, const std::string& type,
                         const std::string& help) {
        addTruthOption(cmd, flags, value, type, help);
    };
    add("--pixel-tolerance", o.pixelTolerance, "FLOAT",
        "Pixels between a march hit and the true hit's projection for an agreed hit, > 0");
    add("--depth-tolerance", o.depthTolerance, "FLOAT",
        "Relative view depth for an agreed hit and for a true hit to count as visible, in (0, 1)");
    add("--repeats", o.repeats, "INT",
        "Timed renders per setting; each pass's median is reported, 1 to 1000");
    cmd.add_option_function<std::string>(
           "--per-frame", [&o](const std::string& v) { o.perFrame = v; },
           "Also write each frame's colour relMSE and flicker to this CSV (columns frame, "
           "frame_index, cut, relmse, flicker; sweep adds setting, its CSV's row from 0)")
        ->type_name("FILE.csv")
        ->group("Truth");
}

ReferenceSettings referenceSettingsFrom(const TruthOptions& o) {
    ReferenceSettings r;
    r.spp = int(parseInteger("--reference-spp", o.referenceSpp, 1, kMaxReferenceSpp));
    r.bounces = o.referenceBounces == "full"
                    ? ReferenceSettings::kConverged
                    : int(parseInteger("--reference-bounces", o.referenceBounces, 1,
                                       ReferenceSettings::kMaxBounces));
    r.visibility = parseChoice("--visibility", o.visibility, parseVisibility, "embree, shadowmap");
    r.validate();
    return r;
}

std::string bouncesName(int bounces) {
    return bounces == ReferenceSettings::kConverged ? "full" : std::to_string(bounces);
}

std::string describeReference(const ReferenceSettings& r) {
    const std::string bounces = r.bounces == ReferenceSettings::kConverged ? "all bounces"
                                : r.bounces == 1                           ? "one bounce"
                                                 : std::to_string(r.bounces) + " bounces";
    return std::to_string(r.spp) + " spp, " + bounces;
}

EvaluationSettings evaluationSettingsFrom(const TruthOptions& o) {
    EvaluationSettings e;
    e.repeats = int(parseInteger("--repeats", o.repeats, 1, 1000));
    e.check.pixelTolerance = parsePositive("--pixel-tolerance", o.pixelTolerance);
    e.check.depthTolerance = parsePositive("--depth-tolerance", o.depthTolerance);
    if (e.check.depthTolerance >= 1.0f)
        badValue("--depth-tolerance", o.depthTolerance, "a number in (0, 1)");
    e.validate();
    return e;
}

CLI::App* addCompareCommand(CLI::App& app, CompareOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "Check one screen-space setting against the Embree truth: every traced ray classified, "
        "the image against a converged reference (cached), per-pass times");
    addSceneOptions(*cmd, o.render, truthDefaults());
    addTraceOptions(*cmd, o.render);
    addTruthOptions(*cmd, o.truth);
    addSequenceOptions(*cmd, o.render,
                       "a sequence along the shot's camera path (or of the still camera), "
                       "history carried; the last frame is evaluated in full, each frame's "
                       "colour relMSE and flicker reported (a reference per camera: use a low "
                       "--reference-spp on a moving path)");
    cmd->add_option_function<std::string>(
           "-o,--output", [&o](const std::string& v) { o.output = v; },
           "Also write the frame: .exr with every plane plus the reference (ref.*) and the "
           "per-pixel checks of the first sample (ssrCheck.class, .pixelError, .depthError, "
           ".trueT: Embree's hit distance, 0 for none; ssgiCheck.*; class: 1 agreed, 2 false hit, "
           "3 missed on screen, 4 true miss, 5 "
           "off-screen truth, 0 no ray: a pixel that traced none, such as a checkerboard's "
           "other phase or, for the half layout, a block's unchosen pixels; the half layout's "
           "ray is at its block's chosen pixel, its pixel error in full-resolution pixels), or "
           ".png")
        ->type_name("FILE");
    addImageOutputOptions(*cmd, o.render);
    cmd->add_flag("--json", o.render.json,
                  "Print the report as one JSON document on stdout instead of its tables "
                  "(docs/truth.md gives its keys); warnings and progress stay on stderr");
    return cmd;
}

namespace {

// The one-bounce reference of the evaluated frame, when the reference is not one already.
std::optional<ReferenceImage> oneBounceReference(const TruthContext& t, const FrameInput& input,
                                                 const RenderSettings& settings) {
    if (t.reference.bounces == 1) return std::nullopt;
    ReferenceSettings one = t.reference;
    one.bounces = 1;
    bool fromCache = false;
    ReferenceImage image =
        referenceFor(t.embree, t.scene, input, settings, one, t.source, fromCache);
    if (t.progress)
        *t.progress << "reference: " << (fromCache ? "from the cache" : "rendered") << " ("
                    << describeReference(one) << ", for the model's error)\n";
    return image;
}

// What was compared, for --json: the text's heading line as keys.
Json setupJson(const std::string& scene, const RenderSettings& settings,
               const ReferenceSettings& reference, const std::string& visibility,
               const SequencePlan& plan) {
    const TraceSettings& t = settings.trace;
    const bool sequenceRun = plan.frames > 1 || plan.warmup > 0;
    return {{"scene", scene},
            {"width", settings.width},
            {"height", settings.height},
            {"marcher", marcherName(t.marcher)},
            {"ssr", t.ssr ? Json({{"method", ssrMethodName(t.ssrMethod)}, {"spp", t.ssrSpp}})
                          : Json(nullptr)},
            {"ssgi", t.ssgi ? Json({{"spp", t.ssgiSpp}}) : Json(nullptr)},
            {"trace_hidden", t.traceHidden},
            {"ssgi_feedback", t.ssgiFeedback},
            {"reference",
             {{"spp", reference.spp},
              {"bounces", bouncesName(reference.bounces)},
              {"visibility", visibility}}},
            {"evaluated_frame", sequenceRun ? Json(plan.frames - 1) : Json(nullptr)},
            {"frames", plan.frames},
            {"warmup_frames", plan.warmup}};
}

}  // namespace

int runCompare(const CompareOptions& o, std::ostream& out, std::ostream& err) {
    const InterruptScope interruptible;  // stops between frames and reference tiles
    SceneRequest request = loadSceneRequest(o.render, truthDefaults());
    const RenderSettings& settings = request.settings;
    if (!settings.trace.any())
        throw std::invalid_argument("--no-ssr and --no-ssgi together leave nothing to compare");
    const SequencePlan plan = sequencePlanFrom(o.render, request);
    ReferenceSettings refSettings = referenceSettingsFrom(o.truth);
    refSettings.cancel = interruptFlag();
    const EvaluationSettings evalSettings = evaluationSettingsFrom(o.truth);
    if (o.output) checkWritable(*o.output);
    const FrameWriteOptions writeOptions =
        o.output ? writeOptionsFrom(o.render, settings, *o.output, err) : FrameWriteOptions{};
    if (o.truth.perFrame) checkCsvPath("--per-frame", *o.truth.perFrame);
    loadScene(request, err);
    const Scene& scene = request.scene;
    refSettings.maxDistance = marchLengths(settings.trace.march, scene.diagonal()).maxDistance;
    std::ostream* progress = o.truth.quiet ? nullptr : &err;
    const bool sequenceRun = plan.frames > 1 || plan.warmup > 0;
    if (progress)
        *progress << "comparing " << request.name << " " << settings.width << "x" << settings.height
                  << (sequenceRun ? ", " + sequenceText(plan) : std::string()) << " on "
                  << isaName(request.isa) << ", " << plural(threadsFor(settings), "thread")
                  << "...\n";

    const EmbreeScene embree(scene);
    const TruthContext truth{embree,       scene,   refSettings, referenceSourceFrom(o.truth, err),
                             evalSettings, progress};
    FrameSequence sequence(request, plan);
    // A signal traced in mixed or world mode traces its world rays on the truth's scene.
    const EmbreeWorldRays worldRays(embree);
    sequence.useWorld(&worldRays);
    Frame frame;
    // (Everything is written once the comparison is done: a stopped one writes nothing.)
    SequenceEvaluation result;
    std::optional<ReferenceImage> oneBounce;
    try {
        result = evaluateSequence(truth, sequence, settings, settings, frame);
        requireSurface(frame);
        oneBounce = oneBounceReference(truth, sequence.input(sequence.steps() - 1), settings);
    } catch (const ReferenceCancelled&) {
        throw Interrupted(
            "part of the comparison (nothing written: compare writes its files when it is done)");
    }
    const Evaluation& ev = result.last;
    warnUnchecked(err, "ssr", "--no-ssr", "past the roughness fade", ev.ssr, ev.ssrCheck,
                  ev.stats.ssr.rays);
    warnUnchecked(err, "ssgi", "--no-ssgi", "without diffuse colour", ev.ssgi, ev.ssgiCheck,
                  ev.stats.ssgi.rays);
    if (o.render.json) {
        Json document = setupJson(request.name, settings, refSettings, o.truth.visibility, plan);
        document.update(evaluationJson(embree.stats(), ev));
        document["one_bounce"] =
            oneBounce
                ? Json({{"method", errorTableJson(imageErrors(frame, *oneBounce))},
                        {"model", errorTableJson(referenceErrors(*oneBounce, result.reference))}})
                : Json(nullptr);
        document["per_frame"] = sequenceRun ? frameErrorsJson(result.frames) : Json(nullptr);
        printJson(out, document);
    } else {
        out << request.name << " " << settings.width << "x" << settings.height << ", marcher "
            << marcherName(settings.trace.marcher) << ", ssr "
            << (settings.trace.ssr ? std::string(ssrMethodName(settings.trace.ssrMethod)) + " x" +
                                         std::to_string(settings.trace.ssrSpp)
                                   : std::string("off"))
            << ", ssgi "
            << (settings.trace.ssgi ? "x" + std::to_string(settings.trace.ssgiSpp) : "off")
            << (settings.trace.traceHidden ? ", hidden rays traced" : "")
            << (settings.trace.ssgiFeedback ? ", ssgi feedback" : "") << ", reference "
            << describeReference(refSettings)
            << (sequenceRun
                    ? "; frame " + std::to_string(plan.frames - 1) + " of " + sequenceText(plan)
                    : std::string())
            << "\n\n";
        printEvaluation(out, embree.stats(), ev);
        if (oneBounce) {
            out << "\n";
            printModelErrors(out, imageErrors(frame, *oneBounce),
                             referenceErrors(*oneBounce, result.reference));
        }
        if (sequenceRun) {
            out << "\nper frame\n";
            printFrameErrors(out, result.frames);
        }
    }
    if (o.truth.perFrame) {
        writeTextFile(*o.truth.perFrame,
                      frameErrorsCsvHeader(false) + frameErrorsCsvRows(result.frames));
        if (progress) *progress << "wrote " << *o.truth.perFrame << "\n";
    }
    if (o.output) {
        appendTruthPlanes(frame, result.reference);
        writeFrame(*o.output, frame, writeOptions);
        if (progress) *progress << "wrote " << *o.output << "\n";
    }
    return kExitOk;
}

void printEvaluation(std::ostream& out, const BvhStats& bvh, const Evaluation& ev) {
    std::ios saved(nullptr);
    saved.copyfmt(out);
    out << "BVH (Embree 3): " << bvh.triangles << " triangles, " << bvh.meshes << " meshes, "
        << bvh.instances << " instances, built in " << std::fixed << std::setprecision(1)
        << bvh.buildMs << " ms, " << std::setprecision(2) << double(bvh.bytes) / (1 << 20)
        << " MiB\n\n"
        << std::defaultfloat;
    printChecks(out, ev);
    out << "\n";
    printErrors(out, ev.error);
    out << "\n"
        << std::left << std::setw(kLabel + 2) << "pass (median)" << std::right << std::setw(kValue)
        << "ms"
        << "\n"
        << std::fixed << std::setprecision(3);
    for (const PassTime& p : ev.passes)
        out << "  " << std::left << std::setw(kLabel) << p.name << std::right << std::setw(kValue)
            << p.ms << "\n";
    out << "  " << std::left << std::setw(kLabel) << "frame" << std::right << std::setw(kValue)
        << ev.frameMs << "\n\n"
        << std::setprecision(2) << "rays per second: march " << ev.marchMraysPerSecond
        << " M, Embree " << ev.embreeMraysPerSecond << " M on the same rays (march / Embree "
        << std::setprecision(3) << ev.marchVsEmbree() << ")\n";
    out.copyfmt(saved);
}

Json evaluationJson(const BvhStats& bvh, const Evaluation& ev) {
    Json passes = Json::object();
    for (const PassTime& p : ev.passes) passes[p.name] = p.ms;
    return {
        {"bvh",
         {{"triangles", bvh.triangles},
          {"meshes", bvh.meshes},
          {"instances", bvh.instances},
          {"build_ms", bvh.buildMs},
          {"bytes", bvh.bytes}}},
        {"ray_check",
         {{"ssr", checksJson(ev.ssr, ev.ssrCheck)}, {"ssgi", checksJson(ev.ssgi, ev.ssgiCheck)}}},
        {"image_error", errorTableJson(ev.error)},
        {"pass_times", std::move(passes)},
        {"frame_ms", ev.frameMs},
        {"march_mrays_per_second", ev.marchMraysPerSecond},
        {"embree_mrays_per_second", ev.embreeMraysPerSecond},
        {"march_vs_embree", ev.marchVsEmbree()}};
}

}  // namespace ssrt::cli
