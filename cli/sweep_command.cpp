#include "cli/sweep_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/interrupt.h"
#include "cli/options.h"
#include "cli/reference_cache.h"
#include "cli/sequence.h"
#include "cli/sequence_evaluation.h"
#include "cli/shard.h"
#include "io/image_io.h"
#include "renderer/quality.h"
#include "world/embree_world_rays.h"

namespace ssrt::cli {

namespace {

// The passes a frame can have, in frame order (renderer.cpp and trace_pass.cpp name them).
const char* const kPasses[] = {
    "shadow",      "geometry",    "visibility",    "resolve",   "textures",      "ids",
    "environment", "shading",     "back faces",    "hi-z",      "thin features", "ssr rays",
    "ssr march",   "ssr resolve", "ssr world",     "ssgi rays", "ssgi march",    "ssgi resolve",
    "ssgi world",  "composite",   kEmbreeTracePass};

std::string columnName(std::string s) {
    for (char& c : s)
        if (c == ' ' || c == '-') c = '_';
    return s;
}

// One point of the chart: a setting of the grid, a quality preset, or the Embree method.
struct Point {
    bool traced = true;  // false: the "off" marcher (both passes off, the environment's light)
    std::optional<Quality> preset;  // a quality preset's settings (the fields below: its own)
    int embreeSpp = 0;              // > 0: SSR and SSGI traced by Embree, this many rays each
    Marcher marcher = Marcher::HiZ;
    int maxSteps = 0, ssrSpp = 1, ssgiSpp = 1;
    SsrMethod ssrMethod = SsrMethod::VndfBounded;
    float thickness = 0.0f;
    bool backFaces = false;  // MarchSettings::backFaces
    bool feedback = false;   // TraceSettings::ssgiFeedback
    SsrResolveMode resolve = SsrResolveMode::Reuse;
    TraceMode ssrTrace = TraceMode::Screen;   // TraceSettings::ssrTrace
    TraceMode ssgiTrace = TraceMode::Screen;  // TraceSettings::ssgiTrace

    static Point off() {
        Point p;
        p.traced = false;
        return p;
    }
    static Point ofPreset(Quality q) {
        Point p;
        p.preset = q;
        return p;
    }
    static Point ofEmbree(int spp) {
        Point p = off();
        p.embreeSpp = spp;
        return p;
    }
};

template <class T, class F>
std::vector<T> parseEach(const std::string& option, const std::string& text, F parse) {
    std::vector<T> out;
    for (const std::string& item : splitList(option, text)) out.push_back(parse(item));
    return out;
}

// The same for a list that may be left empty (none of those points).
template <class T, class F>
std::vector<T> parseOptional(const std::string& option, const std::string& text, F parse) {
    return text.empty() ? std::vector<T>{} : parseEach<T>(option, text, parse);
}

// Each list item is checked against its setting's range in the field table
// (renderer/settings_fields.h), as the render command's single values are.
template <class T>
std::vector<T> parseField(const char* option, const char* key, const std::string& text) {
    const FieldInfo& f = renderField(key);
    return parseEach<T>(option, text, [&](const std::string& s) {
        return static_cast<T>(static_cast<int>(parseFieldText(f, option, s)));
    });
}

std::vector<Point> grid(const SweepOptions& o) {
    const auto marchers = parseEach<std::optional<Marcher>>(
        "--marchers", o.marchers, [](const std::string& s) -> std::optional<Marcher> {
            if (s == "off") return std::nullopt;
            const FieldInfo& f = renderField("marcher");
            const int i = f.choiceIndex(s);
            if (i < 0) badValue("--marchers", s, "one of off, " + f.choiceList());
            return Marcher(i);
        });
    const auto steps = parseField<int>("--max-steps", "maxSteps", o.maxSteps);
    const auto methods = parseField<SsrMethod>("--ssr-methods", "ssrMethod", o.ssrMethods);
    const auto ssrSpp = parseField<int>("--ssr-spp", "ssrSpp", o.ssrSpp);
    const auto ssgiSpp = parseField<int>("--ssgi-spp", "ssgiSpp", o.ssgiSpp);
    const auto thickness = parseEach<float>("--thickness", o.thickness, [](const std::string& s) {
        return float(parseFieldText(renderField("thickness"), "--thickness", s));
    });
    const auto backFaces = parseEach<bool>("--back-faces", o.backFaces, [](const std::string& s) {
        if (s != "on" && s != "off") badValue("--back-faces", s, "on or off");
        return s == "on";
    });
    const auto feedback = parseEach<bool>("--ssgi-feedback", o.feedback, [](const std::string& s) {
        if (s != "on" && s != "off") badValue("--ssgi-feedback", s, "on or off");
        return s == "on";
    });
    const auto resolves = parseField<SsrResolveMode>("--ssr-resolve", "ssrResolve", o.resolves);
    const auto traces = parseField<TraceMode>("--ssr-trace", "ssrTrace", o.ssrTraces);
    const auto ssgiTraces = parseField<TraceMode>("--ssgi-trace", "ssgiTrace", o.ssgiTraces);
    std::vector<Point> points;
    bool off = false;
    for (const auto& m : marchers) {
        if (!m) {
            if (!off) points.push_back(Point::off());  // once, whatever the other lists say
            off = true;
            continue;
        }
        for (int st : steps)
            for (SsrMethod me : methods)
                for (int sp : ssrSpp)
                    for (int gp : ssgiSpp)
                        for (float th : thickness)
                            for (bool bf : backFaces)
                                for (bool fb : feedback)
                                    for (SsrResolveMode re : resolves)
                                        for (TraceMode tr : traces)
                                            for (TraceMode gt : ssgiTraces)
                                                points.push_back({.traced = true,
                                                                  .preset = std::nullopt,
                                                                  .embreeSpp = 0,
                                                                  .marcher = *m,
                                                                  .maxSteps = st,
                                                                  .ssrSpp = sp,
                                                                  .ssgiSpp = gp,
                                                                  .ssrMethod = me,
                                                                  .thickness = th,
                                                                  .backFaces = bf,
                                                                  .feedback = fb,
                                                                  .resolve = re,
                                                                  .ssrTrace = tr,
                                                                  .ssgiTrace = gt});
    }
    for (const Quality q : parseOptional<Quality>("--presets", o.presets, [](const std::string& s) {
             const std::optional<Quality> q = parseQuality(s);
             if (!q) badValue("--presets", s, "one of " + std::string(qualityList()));
             return *q;
         }))
        points.push_back(Point::ofPreset(q));
    for (const int spp : parseOptional<int>("--embree-spp", o.embreeSpp, [](const std::string& s) {
             return int(parseInteger("--embree-spp", s, 1, kMaxReferenceSpp));
         }))
        points.push_back(Point::ofEmbree(spp));
    return points;
}

// The point's columns as its settings have them (a preset's are the preset's; the Embree
// method draws its SSR rays with the frame's sampler).
Point describedBy(Point p, const RenderSettings& s) {
    const TraceSettings& t = s.trace;
    p.ssrMethod = t.ssrMethod;
    if (!p.preset) return p;
    p.traced = t.any();
    p.marcher = t.marcher;
    p.maxSteps = t.march.maxSteps;
    p.ssrSpp = t.ssrSpp;
    p.ssgiSpp = t.ssgiSpp;
    p.ssrMethod = t.ssrMethod;
    p.thickness = t.march.thickness;
    p.backFaces = t.march.backFaces;
    p.feedback = t.ssgiFeedback;
    p.resolve = t.resolve.mode;
    p.ssrTrace = t.ssrTrace;
    p.ssgiTrace = t.ssgiTrace;
    return p;
}

RenderSettings settingsFor(const RenderSettings& base, const Point& p) {
    RenderSettings s = base;
    if (p.embreeSpp > 0) return s;  // the frame as the scene options give it, traced by Embree
    if (p.preset) {
        applyQuality(*p.preset, s);
        s.validate();
        return s;
    }
    TraceSettings& t = s.trace;
    t.ssr = t.ssgi = p.traced;
    if (p.traced) {
        t.marcher = p.marcher;
        t.march.maxSteps = p.maxSteps;
        t.ssrMethod = p.ssrMethod;
        t.ssrSpp = p.ssrSpp;
        t.ssgiSpp = p.ssgiSpp;
        t.march.thickness = p.thickness;
        t.march.backFaces = p.backFaces;
        t.ssgiFeedback = p.feedback;
        t.resolve.mode = p.resolve;
        t.ssrTrace = p.ssrTrace;
        t.ssgiTrace = p.ssgiTrace;
    }
    s.validate();
    return s;
}

// RFC 4180: a field with a comma, quote or line break is quoted, its quotes doubled (a glTF
// path may hold any of them).
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string q = "\"";
    for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

double passMs(const Evaluation& ev, const char* name) {
    for (const PassTime& p : ev.passes)
        if (p.name == name) return p.ms;
    return -1.0;  // not run: an empty cell
}

// One CSV row (the values of sweepColumns(), in order).
std::string csvRow(int setting, const std::string& scene, const RenderSettings& s, const Point& p,
                   const ReferenceSettings& reference, const SequencePlan& plan,
                   const SequenceEvaluation& result) {
    const Evaluation& ev = result.last;
    std::ostringstream r;
    r << std::setprecision(6);
    const auto cell = [&](auto v) { r << ',' << v; };
    const auto optional = [&](bool on, double v) {
        r << ',';
        if (on) r << v;
    };
    r << setting << ',' << csvField(scene);
    cell(s.width), cell(s.height), cell(s.threads);
    const bool embree = p.embreeSpp > 0;
    cell(embree     ? std::string_view("embree")
         : p.traced ? marcherName(p.marcher)
                    : std::string_view("off"));
    r << ',' << (p.preset ? qualityName(*p.preset) : std::string_view());
    r << ',' << (p.traced || embree ? std::string(ssrMethodName(p.ssrMethod)) : "");
    optional(p.traced || embree, embree ? p.embreeSpp : p.ssrSpp);
    optional(p.traced || embree, embree ? p.embreeSpp : p.ssgiSpp);
    optional(p.traced, p.maxSteps);
    optional(p.traced, p.thickness);
    optional(p.traced, p.backFaces ? 1 : 0);
    optional(p.traced, p.feedback ? 1 : 0);
    r << ',' << (p.traced ? (p.resolve == SsrResolveMode::Mip ? "mip" : "reuse") : "");
    r << ',' << (p.traced ? traceModeName(p.ssrTrace) : std::string_view());
    r << ',' << (p.traced ? traceModeName(p.ssgiTrace) : std::string_view());
    optional(p.traced, s.trace.traceHidden ? 1 : 0);
    cell(reference.spp);
    cell(bouncesName(reference.bounces));
    cell(ev.frameMs);
    for (const char* pass : kPasses) {
        const double ms = passMs(ev, pass);
        optional(ms >= 0.0, ms);
    }
    const auto checks = [&](bool on, const RayCheckTable& t) {
        optional(on, double(t.rays));
        for (int c = 1; c < kRayClassCount; ++c) optional(on, t.share(RayClass(c)));
        optional(on, RayCheckTable::quantile(t.pixelError, 0.5));
        optional(on, RayCheckTable::quantile(t.pixelError, 0.95));
        optional(on, RayCheckTable::quantile(t.depthError, 0.5));
        // How the rays were answered (mixed and world tracing): world rays, and the screen's
        // own false hits (its false accepts), as shares of all rays.
        optional(on, t.rays ? double(t.worldRays()) / double(t.rays) : 0.0);
        optional(on, t.screenShare(RayClass::FalseHit));
    };
    checks(ev.ssr, ev.ssrCheck);
    checks(ev.ssgi, ev.ssgiCheck);
    const ErrorTable& e = ev.error;
    cell(e.color.relMse), cell(e.color.rmse);
    for (const ImageError* x : {&e.direct, &e.specular, &e.diffuse}) optional(e.parts, x->relMse);
    for (const ImageError* x : {&e.direct, &e.specular, &e.diffuse}) optional(e.parts, x->rmse);
    const bool traced = ev.ssr || ev.ssgi;
    optional(traced, ev.marchMraysPerSecond);
    optional(traced, ev.embreeMraysPerSecond);
    optional(traced, ev.marchVsEmbree());
    cell(plan.frames), cell(plan.warmup);
    const std::optional<double>& flicker = result.frames.back().flicker;
    optional(flicker.has_value(), flicker.value_or(0.0));
    return r.str();
}

// The Embree method's rays take the evaluated frame's index plus this, so that they are not
// the reference's first samples (truth/evaluation.h, evaluateEmbreeMethod).
constexpr uint32_t kEmbreeMethodFrameOffset = 0x80000000u;

// The Embree method on the sequence's last frame (no history: nothing is accumulated), against
// that frame's reference.
SequenceEvaluation evaluateEmbreePoint(const TruthContext& t, const FrameSequence& sequence,
                                       const RenderSettings& settings, int spp) {
    const FrameInput last = sequence.input(sequence.steps() - 1);
    bool fromCache = false;
    const ReferenceImage reference =
        referenceFor(t.embree, t.scene, last, settings, t.reference, t.source, fromCache);
    FrameInput own = last;
    own.frameIndex = last.frameIndex + kEmbreeMethodFrameOffset;
    ReferenceSettings world = t.reference;
    world.spp = spp;
    SequenceEvaluation out;
    out.last =
        evaluateEmbreeMethod(t.embree, t.scene, own, settings, world, reference, t.evaluation);
    FrameError row;
    row.frame = sequence.plan().frames - 1;
    row.frameIndex = last.frameIndex;
    row.relMse = out.last.error.color.relMse;
    out.frames.push_back(row);
    return out;
}

// A shard's settings: i % N == K (cli/shard.h).
bool ownsSetting(const Shard& shard, std::size_t i) {
    return int(i % std::size_t(shard.count)) == shard.index;
}
int ownedCount(const Shard& shard, std::size_t settings) {
    int n = 0;
    for (std::size_t i = 0; i < settings; ++i) n += ownsSetting(shard, i);
    return n;
}

std::string describe(const Point& p) {
    if (p.embreeSpp > 0)
        return "embree, ssr x" + std::to_string(p.embreeSpp) + ", ssgi x" +
               std::to_string(p.embreeSpp) + " (world space, no denoiser)";
    if (p.preset) return "preset " + std::string(qualityName(*p.preset));
    if (!p.traced) return "off (environment light only)";
    std::ostringstream s;
    s << marcherName(p.marcher) << ", " << p.maxSteps << " steps, " << ssrMethodName(p.ssrMethod)
      << ", ssr x" << p.ssrSpp << ", ssgi x" << p.ssgiSpp << ", thickness " << p.thickness
      << (p.backFaces ? ", back faces, " : ", ") << (p.feedback ? "ssgi feedback, " : "")
      << (p.resolve == SsrResolveMode::Mip ? "mip" : "reuse");
    if (p.ssrTrace != TraceMode::Screen) s << ", ssr " << traceModeName(p.ssrTrace);
    if (p.ssgiTrace != TraceMode::Screen) s << ", ssgi " << traceModeName(p.ssgiTrace);
    return s.str();
}

}  // namespace

SweepOptions::SweepOptions() {
    const TraceSettings d;
    maxSteps = std::to_string(d.march.maxSteps);
    ssrMethods = std::string(ssrMethodName(d.ssrMethod));
    ssrSpp = std::to_string(d.ssrSpp);
    ssgiSpp = std::to_string(d.ssgiSpp);
    std::ostringstream t;
    t << d.march.thickness;
    thickness = t.str();
    backFaces = d.march.backFaces ? "on" : "off";
    feedback = d.ssgiFeedback ? "on" : "off";
    resolves = std::string(resolveModeName(d.resolve.mode));
    ssrTraces = std::string(traceModeName(d.ssrTrace));
    ssgiTraces = std::string(traceModeName(d.ssgiTrace));
}

const std::vector<std::string>& sweepColumns() {
    static const std::vector<std::string> columns = [] {
        std::vector<std::string> c = {
            "setting",   "scene",      "width",        "height",        "threads",
            "marcher",   "quality",    "ssr_method",   "ssr_spp",       "ssgi_spp",
            "max_steps", "thickness",  "back_faces",   "ssgi_feedback", "resolve",
            "ssr_trace", "ssgi_trace", "trace_hidden", "reference_spp", "reference_bounces",
            "frame_ms"};
        for (const char* pass : kPasses) c.push_back("ms_" + columnName(pass));
        for (const char* pass : {"ssr", "ssgi"}) {
            const std::string p = pass;
            c.push_back(p + "_rays");
            for (int k = 1; k < kRayClassCount; ++k)
                c.push_back(p + "_" + std::string(rayClassName(RayClass(k))));
            c.insert(c.end(), {p + "_err_px_p50", p + "_err_px_p95", p + "_err_depth_p50",
                               p + "_world_rays", p + "_screen_false_hit"});
        }
        c.insert(c.end(),
                 {"relmse", "rmse", "relmse_direct", "relmse_specular", "relmse_diffuse",
                  "rmse_direct", "rmse_specular", "rmse_diffuse", "march_mrays_s", "embree_mrays_s",
                  "march_vs_embree", "frames", "warmup_frames", "flicker"});
        return c;
    }();
    return columns;
}

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "sweep",
        "Measure a grid of screen-space settings on one scene for time and error against the "
        "Embree truth, one CSV row per setting (chart it with perf/plot.py)");
    addSceneOptions(*cmd, o.render, truthDefaults());
    const auto list = [&](const std::string& flags, std::string& value, const std::string& help) {
        cmd->add_option(flags, value, help)
            ->type_name("LIST")
            ->capture_default_str()
            ->group("Grid");
    };
    list("--marchers", o.marchers,
         "Marchers, comma-separated: linear, dda, hiz, and off (both passes off: the "
         "environment's light, the baseline)");
    list("--max-steps", o.maxSteps, "March steps per ray (Hi-Z: iterations)");
    list("--ssr-methods", o.ssrMethods, "SSR samplers: " + renderField("ssrMethod").choiceList());
    list("--ssr-spp", o.ssrSpp, "SSR rays per pixel");
    list("--ssgi-spp", o.ssgiSpp, "SSGI rays per pixel");
    list("--thickness", o.thickness,
         "Depth-buffer thickness (fractions of view depth, as --thickness)");
    list("--back-faces", o.backFaces,
         "Depth intervals from the back faces (as --back-faces): on, off (column back_faces)");
    list("--ssgi-feedback", o.feedback,
         "Multi-bounce diffuse from the frame before (as --ssgi-feedback): on, off (column "
         "ssgi_feedback; it needs a sequence: --warmup-frames or --frames)");
    list("--ssr-resolve", o.resolves, "SSR resolve modes: reuse, mip");
    list("--ssr-trace", o.ssrTraces,
         "SSR's tracing modes (as --ssr-trace): screen, mixed, world (column ssr_trace; mixed "
         "and world trace their world rays on the truth's Embree scene; columns "
         "ssr_world_rays, ssr_screen_false_hit)");
    list("--ssgi-trace", o.ssgiTraces,
         "SSGI's tracing modes (as --ssgi-trace): screen, mixed, world (column ssgi_trace; "
         "columns ssgi_world_rays, ssgi_screen_false_hit)");
    list("--presets", o.presets,
         "Quality presets as points of their own beside the grid (column quality): " +
             std::string(qualityList()) + "; none by default");
    list("--embree-spp", o.embreeSpp,
         "The world-space alternative as points of its own (marcher embree): SSR and SSGI "
         "traced by Embree with this many rays per pixel each instead of marched, no denoiser, "
         "e.g. 1,4,16; its time is the frame without traces plus Embree's (column "
         "ms_embree_trace); none by default");
    cmd->add_flag("--trace-hidden", o.traceHidden,
                  "Every setting also traces the rays the composite hides (SSR past the "
                  "roughness fade, SSGI on metals); by default they get no ray, so the ray "
                  "checks leave those pixels out (column trace_hidden)")
        ->group("Grid");
    addTruthOptions(*cmd, o.truth);
    addSequenceOptions(*cmd, o.render,
                       "each setting renders a sequence along the shot's camera path (or of the "
                       "still camera), history carried, and its row is the last frame's "
                       "(columns frames, warmup_frames, flicker; --per-frame for every frame)");
    cmd->add_option("-o,--output", o.output, "CSV file to write (whole, when the sweep ends)")
        ->type_name("FILE")
        ->capture_default_str();
    addShardOption(*cmd, o.shard,
                   "settings K - 1, K - 1 + N, K - 1 + 2N, ... of the CSV's setting column, which "
                   "counts from 0; --per-frame's file too");
    return cmd;
}

int runSweep(const SweepOptions& o, std::ostream& out, std::ostream& err) {
    const InterruptScope interruptible;  // stops between settings and reference tiles
    SceneRequest request = loadSceneRequest(o.render, truthDefaults());
    request.settings.trace.traceHidden = o.traceHidden;
    std::vector<Point> points = grid(o);
    std::vector<RenderSettings> settings;
    for (Point& p : points) {
        settings.push_back(settingsFor(request.settings, p));
        p = describedBy(p, settings.back());
    }
    const SequencePlan plan = sequencePlanFrom(o.render, request);
    const EvaluationSettings evalSettings = evaluationSettingsFrom(o.truth);
    ReferenceSettings refBase = referenceSettingsFrom(o.truth);
    refBase.cancel = interruptFlag();
    std::string shardSource;
    const Shard shard = shardFrom(o.shard, &shardSource);
    const std::string output = shardFileName(o.output, shard);
    const std::optional<std::string> perFrameOutput =
        o.truth.perFrame ? std::optional(shardFileName(*o.truth.perFrame, shard)) : std::nullopt;
    checkCsvPath("-o", output);
    if (perFrameOutput) checkCsvPath("--per-frame", *perFrameOutput);
    loadScene(request, err);
    const Scene& scene = request.scene;
    FrameSequence sequence(request, plan);
    std::ostream* progress = o.truth.quiet ? nullptr : &err;
    if (progress)
        *progress << "sweeping " << request.name << " " << request.settings.width << "x"
                  << request.settings.height << ": " << plural(int(points.size()), "setting")
                  << (plan.frames > 1 || plan.warmup > 0 ? " of " + sequenceText(plan)
                                                         : std::string())
                  << " on " << isaName(request.isa) << ", "
                  << plural(threadsFor(request.settings), "thread")
                  << (shard.sharded() ? ", " + describeShard(shard, shardSource) + ": " +
                                            plural(ownedCount(shard, points.size()), "setting")
                                      : std::string())
                  << "\n";

    const EmbreeScene embree(scene);
    // A setting that traces SSR or SSGI in mixed or world mode traces its world rays on this
    // scene.
    const EmbreeWorldRays worldRays(embree);
    sequence.useWorld(&worldRays);
    const ReferenceSource source = referenceSourceFrom(o.truth, err);
    std::ostringstream csv, perFrame;
    const auto& columns = sweepColumns();
    for (std::size_t i = 0; i < columns.size(); ++i) csv << (i ? "," : "") << columns[i];
    csv << "\n";
    perFrame << frameErrorsCsvHeader(true);
    out << std::left << std::setw(56) << "setting" << std::right << std::setw(12) << "frame ms"
        << std::setw(12) << "relMSE"
        << "\n";
    Frame frame;
    int done = 0;
    // The CSV is written whole at the end, so a stopped sweep (or shard) leaves none: merge
    // then names the shard as missing rather than taking a part with rows missing.
    const auto stopped = [&] {
        return std::to_string(done) + " of " + plural(ownedCount(shard, points.size()), "setting") +
               " (" + output + " not written: it is written when the sweep ends)";
    };
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!ownsSetting(shard, i)) continue;
        stopIfInterrupted(stopped);
        if (progress)
            *progress << "setting " << (i + 1) << "/" << points.size() << ": "
                      << describe(points[i]) << "\n";
        // The reference follows the setting's SSR sampler (cached per sampler).
        ReferenceSettings refSettings = refBase;
        refSettings.maxDistance =
            marchLengths(settings[i].trace.march, scene.diagonal()).maxDistance;
        RenderSettings refRender = settings[i];
        if (!points[i].traced) refRender.trace = request.settings.trace;
        const TruthContext truth{embree, scene, refSettings, source, evalSettings, progress};
        const SequenceEvaluation result = [&] {
            try {
                return points[i].embreeSpp > 0
                           ? evaluateEmbreePoint(truth, sequence, settings[i], points[i].embreeSpp)
                           : evaluateSequence(truth, sequence, settings[i], refRender, frame);
            } catch (const ReferenceCancelled&) {
                throw Interrupted(stopped());
            }
        }();
        if (points[i].embreeSpp == 0) requireSurface(frame);  // (before any file is written)
        const Evaluation& ev = result.last;
        csv << csvRow(int(i), request.name, settings[i], points[i], refSettings, plan, result)
            << "\n";
        perFrame << frameErrorsCsvRows(result.frames, int(i));
        out << std::left << std::setw(56) << describe(points[i]) << std::right << std::fixed
            << std::setprecision(2) << std::setw(12) << ev.frameMs << std::scientific
            << std::setprecision(3) << std::setw(12) << ev.error.color.relMse << std::defaultfloat
            << "\n";
        ++done;
    }
    writeTextFile(output, csv.str());
    if (progress) *progress << "wrote " << output << "\n";
    if (perFrameOutput) {
        writeTextFile(*perFrameOutput, perFrame.str());
        if (progress) *progress << "wrote " << *perFrameOutput << "\n";
    }
    return kExitOk;
}

}  // namespace ssrt::cli
