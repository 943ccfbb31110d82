#include "cli/render_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/interrupt.h"
#include "cli/json_output.h"
#include "cli/options.h"
#include "cli/process_clock.h"
#include "cli/profile_file.h"
#include "cli/progress_line.h"
#include "cli/scene_world.h"
#include "cli/sequence.h"
#include "cli/shard.h"
#include "io/image_io.h"
#include "renderer/quality.h"
#include "renderer/settings_fields.h"
#include "scenes/shot.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------
// The --stats table

struct Counter {
    const char* label;
    uint64_t RasterStats::*field;
};

constexpr Counter kCounters[] = {
    {"triangles in", &RasterStats::trianglesIn},
    {"triangles invalid", &RasterStats::trianglesInvalid},
    {"triangles culled", &RasterStats::trianglesCulled},
    {"triangles outside", &RasterStats::trianglesOutside},
    {"triangles clipped", &RasterStats::trianglesClipped},
    {"triangles set up", &RasterStats::trianglesSetUp},
    {"triangles masked", &RasterStats::trianglesMasked},
    {"triangles cut out", &RasterStats::trianglesCutOut},
    {"bin entries", &RasterStats::binEntries},
    {"blocks rejected", &RasterStats::blocksRejected},
    {"blocks accepted", &RasterStats::blocksAccepted},
    {"blocks partial", &RasterStats::blocksPartial},
    {"pixels tested", &RasterStats::pixelsTested},
    {"pixels covered", &RasterStats::pixelsCovered},
    {"pixels written", &RasterStats::pixelsWritten},
    {"pixels cut out", &RasterStats::pixelsCutOut},
};

constexpr int kLabelWidth = 20;
constexpr int kValueWidth = 14;

Json statsJson(const FrameStats& stats, double wallMs, double writeMs);  // (below printStats)

// What the process paid before and in its first render call, beyond the passes: the table
// `--stats` prints with the first frame written (what a one-frame render costs as a process).
struct ProcessCosts {
    std::optional<double> cpuBeforeMainMs;  // none where runCli runs inside another program
    std::optional<double> commandLineMs;    // main's start to the command's
    double sceneSetupMs = 0.0;              // the command's start to its first render call
    long firstCallPageFaults = 0;           // pages the first render call touched first
};
void printProcessCosts(std::ostream& out, const ProcessCosts& costs);
Json processCostsJson(const ProcessCosts& costs);

}  // namespace

RenderOptions::RenderOptions() {
    const RenderSettings d;
    isa = d.isa ? std::string(isaName(*d.isa)) : "auto";
}

CLI::App* addRenderCommand(CLI::App& app, RenderOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "render",
        "Render a frame, or a sequence along a shot's camera path, of a built-in scene or a glTF "
        "file to PNG or EXR files");
    addSceneOptions(*cmd, o, RenderSettings{});
    addSequenceOptions(*cmd, o,
                       "evenly along the shot's camera path from its first key to its last "
                       "(Catmull-Rom or linear, as the shot says; history restarts at a key "
                       "marked cut), or N frames of the still camera without a path");
    cmd->add_option_function<std::string>(
           "-o,--output",
           [&o](const std::string& v) {
               o.output = v;
               o.outputGiven = true;
           },
           "Output image: .png (tone-mapped preview) or .exr (every plane as a float layer); "
           "with more than one frame, frame i goes to NAME_iiii.EXT (out.png: out_0000.png, "
           "out_0001.png, ...). Default: named after the shot file or the scene (cornell.png, "
           "spheres_orbit_0000.png, ...), .exr with an .exr --compare reference")
        ->type_name("FILE");
    addImageOutputOptions(*cmd, o);
    addShardOption(*cmd, o.shard,
                   "frames: block K of N of --frames, each frame's file named as unsharded; the "
                   "frames before the block since the history last restarted are rendered, "
                   "not written");
    addTraceOptions(*cmd, o);
    cmd->add_flag("--stats", o.stats,
                  "Print per-pass times, rasterizer counters and the screen-space march's "
                  "counters and speed (Mrays per second, ns per step; per frame)");
    cmd->add_option_function<std::string>(
           "--profile", [&o](const std::string& v) { o.profile = v; },
           "Write where the time goes as a Chrome trace-event file (.json; Perfetto and "
           "chrome://tracing open it): every pass, tile chain and stage of every frame as "
           "slices on the thread that ran it, the march's counters per frame as counter tracks")
        ->type_name("FILE");
    cmd->add_flag("--json", o.json,
                  "Print the --stats figures (every frame's) and the --compare report as one "
                  "JSON document on stdout instead of their tables (docs/cli.md gives its keys); "
                  "needs --stats or --compare");
    cmd->add_flag("-q,--quiet", o.quiet, "No progress lines on stderr (warnings still print)");
    CLI::Option* compare =
        cmd->add_option_function<std::string>(
               "--compare", [&o](const std::string& v) { o.compare = v; },
               "After writing the frame, compare it with this reference (a golden image) as "
               "'ssrt diff OUTPUT FILE' does: its table, exit 1 beyond a threshold; a single "
               "frame only")
            ->type_name("FILE")
            ->group("Golden image");
    for (CLI::Option* flag : addDiffFlags(*cmd, o.diff, "Golden image")) flag->needs(compare);
    return cmd;
}

RenderSettings settingsFrom(const RenderOptions& o, const RenderSettings& base) {
    RenderSettings s = base;
    for (const auto& [key, text] : o.settings) renderField(key);  // a key the table lacks throws
    if (o.quality) {
        const std::optional<Quality> q = parseQuality(*o.quality);
        if (!q)
            throw std::invalid_argument("--quality: '" + *o.quality + "' is not one of " +
                                        std::string(qualityList()));
        applyQuality(*q, s);  // then the flags given beside it
    }
    for (const auto& f : kRenderFields) {
        const auto it = o.settings.find(f.key);
        if (it != o.settings.end() && f.has(kFieldCli))
            f.set(s, parseFieldText(f, fieldOption(f), it->second));
    }
    try {
        s.isa = parseIsa(o.isa);
    } catch (const std::exception& e) {
        throw std::invalid_argument(std::string("--isa: ") + e.what());
    }
    s.validate();
    return s;
}

std::string sequenceFileName(const std::string& output, int index, int count) {
    if (count <= 1) return output;
    const fs::path path(output);
    std::string number = std::to_string(index);
    const std::size_t digits = std::max<std::size_t>(4, std::to_string(count - 1).size());
    if (number.size() < digits) number.insert(0, digits - number.size(), '0');
    std::string name = path.stem().string();
    name.append("_").append(number).append(path.extension().string());
    return (path.parent_path() / name).string();
}

void planesForFile(const std::string& output, const LayerGroups& layers, RenderSettings& s) {
    const bool exr = isExrPath(output);
    if (!exr || !hasGroup(layers, LayerGroup::GBuffer)) s.idPlanes = s.gbufferPlanes = false;
    if (!exr || !hasGroup(layers, LayerGroup::Trace)) s.debugPlanes = s.tracePlanes = false;
}

std::string renderOutput(const RenderOptions& o) {
    if (o.outputGiven) return o.output;
    // Named after what is rendered, as pbrt and Mitsuba name theirs, so a second render of
    // another scene does not overwrite the first: the shot file's name, else the scene's (a
    // glTF file's without its folder and extension), in the working folder.
    const std::string name = o.shot    ? fs::path(*o.shot).stem().string()
                             : o.scene ? fs::path(*o.scene).stem().string()
                                       : defaultSceneName();
    return name + (o.compare && isExrPath(*o.compare) ? ".exr" : ".png");
}

// ---------------------------------------------------------------------------------------
// The command

namespace {

// How far an interrupted render got: "3 of 200 frames (out_0000.png to out_0002.png written
// whole)".
std::string framesWrittenText(int written, int total, const std::string& first,
                              const std::string& last) {
    const std::string files = written == 0   ? "none written"
                              : written == 1 ? last + " written whole"
                                             : first + " to " + last + " written whole";
    return std::to_string(written) + " of " + plural(total, "frame") + " (" + files + ")";
}

}  // namespace

int runRender(const RenderOptions& o, std::ostream& out, std::ostream& err) {
    const auto entered = std::chrono::steady_clock::now();
    ProcessCosts process;
    if (const std::optional<ProcessStart> start = processStart()) {
        process.cpuBeforeMainMs = start->cpuMsBeforeMain;
        process.commandLineMs =
            std::chrono::duration<double, std::milli>(entered - start->wall).count();
    }
    bool firstCall = true, processPrinted = false;
    const InterruptScope interruptible;  // stops between frames (cli/interrupt.h)
    SceneRequest request = loadSceneRequest(o);
    const RenderSettings& settings = request.settings;
    const SequencePlan plan = sequencePlanFrom(o, request);
    const int frames = plan.frames;
    const std::string output = renderOutput(o);
    std::string shardSource;
    const Shard shard = shardFrom(o.shard, &shardSource);
    const ItemRange block = shardBlock(shard, frames);
    // --compare: its flags, one frame, and a reference that can be read, before any work.
    std::optional<DiffSettings> diff;
    if (o.compare) {
        diff = diffSettingsFrom(o.diff);
        if (frames > 1)
            throw std::invalid_argument("--compare: compares a single frame, but this render has " +
                                        plural(frames, "frame") + " (--frames or the shot)");
        if (shard.sharded())
            throw std::invalid_argument("--compare: compares a whole render, not a shard of one (" +
                                        describeShard(shard, shardSource) + ")");
        // Writing over the reference would compare the frame with itself.
        if (samePath(output, *o.compare))
            throw std::invalid_argument("--compare: the reference '" + *o.compare +
                                        "' is the output file itself");
        checkHeatmapApart(diff->compare.heatmap, {output, *o.compare});
        readChannelNames(*o.compare);
    }
    // --json replaces the text of --stats and --compare; alone it would print nothing.
    if (o.json && !o.stats && !o.compare)
        throw std::invalid_argument(
            "--json: prints the --stats or --compare report, and neither "
            "was given");
    checkWritable(sequenceFileName(output, int(block.begin), frames));
    if (o.profile) checkTextPath("--profile", *o.profile, ".json");
    const FrameWriteOptions writeOptions = writeOptionsFrom(o, settings, output, err);
    planesForFile(output, writeOptions.layers, request.settings);
    if (o.layers && writeOptions.layers == LayerGroups().set(int(LayerGroup::Truth)))
        throw std::invalid_argument(
            "--layers: a rendered frame has no truth layers (ssrt "
            "compare adds them), so 'truth' alone writes nothing");
    // Loaded before anything is written.
    loadScene(request, err);
    const Scene& scene = request.scene;
    FrameSequence sequence(request, plan);
    // World rays for a signal traced in mixed or world mode: Embree's scene, built once.
    const SceneWorld world(scene, request.settings.trace);
    sequence.useWorld(world.rays());
    // A shard renders from the last step at or before its block where the history restarts
    // (step 0, or a camera cut): the frames between are rendered for their history only.
    const int firstStep = plan.warmup + int(block.begin), endStep = plan.warmup + int(block.end);
    int startStep = firstStep;
    while (block.begin < block.end && startStep > 0 && !sequence.input(startStep).resetHistory)
        --startStep;
    const int historyFrom = std::max(0, sequence.frameOf(startStep));  // the first replayed
    if (!o.quiet) {
        err << "rendering " << request.name << " " << settings.width << "x" << settings.height
            << (frames > 1 ? ", " + plural(frames, "frame") : std::string())
            << (plan.warmup > 0 ? " after " + plural(plan.warmup, "warm-up frame") : std::string())
            << " on " << isaName(request.isa) << ", " << plural(threadsFor(settings), "thread");
        if (shard.sharded())
            err << ", " << describeShard(shard, shardSource) << ": "
                << (block.begin == block.end
                        ? std::string("no frame")
                        : "frames " + std::to_string(block.begin) + " to " +
                              std::to_string(block.end - 1) +
                              (historyFrom < block.begin
                                   ? " (history from frame " + std::to_string(historyFrom) + ")"
                                   : std::string()));
        err << "...\n";
    }

    // One Renderer, one Frame and one history for the whole sequence: planes and scratch
    // buffers are reused, and each frame reads what the one before committed (cli/sequence.h:
    // the cameras, frame indices and cuts).
    const Renderer renderer(settings);
    Frame frame;
    FrameHistory history;
    // --profile: the slices of every frame, written once the last is (cli/profile_file.h).
    std::optional<ProfileFile> profile;
    if (o.profile) profile.emplace();
    const ProfileTarget profiling(profile ? &*profile : nullptr);
    Json document = Json::object();  // --json: printed whole once every frame is written
    if (o.json && o.stats) document["frames"] = Json::array();
    // For the frame lines' time left (the message only).
    const auto sequenceStart = std::chrono::steady_clock::now();
    int framesWritten = 0;
    std::string firstWritten, lastWritten;
    for (int step = startStep; step < endStep; ++step) {
        stopIfInterrupted([&] {
            return framesWrittenText(framesWritten, int(block.end - block.begin), firstWritten,
                                     lastWritten);
        });
        FrameInput input = sequence.input(step);
        // No frame reads the last one's history: it is read, not replaced (the same image,
        // without the denoiser's history planes and their writes).
        input.replaceHistory = step + 1 < endStep;
        input.cancel = interruptFlag();  // a large frame stops between its passes
        const auto start = std::chrono::steady_clock::now();
        const long faultsBefore = minorPageFaults();
        if (firstCall)
            process.sceneSetupMs =
                std::chrono::duration<double, std::milli>(start - entered).count();
        const std::string frameName = "frame " + std::to_string(input.frameIndex);
        std::optional<ProfileScope> frameSlice(std::in_place, frameName);
        try {
            renderer.render(scene, input, history, frame);
        } catch (const RenderCancelled&) {
            stopIfInterrupted([&] {
                return framesWrittenText(framesWritten, int(block.end - block.begin), firstWritten,
                                         lastWritten);
            });
            throw;  // (raised by no one else)
        }
        const std::chrono::duration<double, std::milli> wall =
            std::chrono::steady_clock::now() - start;
        if (firstCall) process.firstCallPageFaults = minorPageFaults() - faultsBefore;
        firstCall = false;
        if (profile) profile->counters(frame.stats, std::chrono::steady_clock::now());
        if (sequence.isWarmup(step)) {
            if (!o.quiet) err << "warm-up " << (step + 1) << "/" << plan.warmup << "\n";
            continue;
        }

        const int i = sequence.frameOf(step);
        if (step < firstStep) {
            if (!o.quiet) err << "history frame " << (i + 1) << "/" << frames << "\n";
            continue;
        }
        const std::string file = sequenceFileName(output, i, frames);
        const auto written = std::chrono::steady_clock::now();
        {
            const ProfileScope slice("image write");
            writeFrame(file, frame, writeOptions);
        }
        frameSlice.reset();
        if (framesWritten++ == 0) firstWritten = file;
        lastWritten = file;
        const std::chrono::duration<double, std::milli> write =
            std::chrono::steady_clock::now() - written;
        if (!o.quiet) {
            if (frames > 1) {
                err << "frame " << (i + 1) << "/" << frames << ": wrote " << file
                    << (input.resetHistory ? " (camera cut: history restarted)" : "");
                if (step + 1 < endStep) {
                    const std::chrono::duration<double> elapsed =
                        std::chrono::steady_clock::now() - sequenceStart;
                    const double done = double(step - startStep + 1) / (endStep - startStep);
                    const std::string left = timeLeftText(secondsLeft(done, elapsed.count()));
                    if (!left.empty()) err << ", " << left;
                }
                err << "\n";
            } else {
                err << "wrote " << file << "\n";
            }
        }
        if (o.stats) {
            // The renderer may report the thread setting (0 = every core) rather than the count.
            FrameStats stats = frame.stats;
            if (stats.threads <= 0) stats.threads = threadsFor(settings);
            if (o.json) {
                Json entry = {{"frame", i}, {"file", file}};
                entry.update(statsJson(stats, wall.count(), write.count()));
                document["frames"].push_back(std::move(entry));
                if (!processPrinted) document["process"] = processCostsJson(process);
            } else {
                if (frames > 1)
                    out << (i > 0 ? "\n" : "") << "frame " << i << " (" << file << ")\n";
                printStats(out, stats, double(frame.width) * double(frame.height), wall.count(),
                           write.count());
                if (!processPrinted) printProcessCosts(out, process);
            }
            processPrinted = true;
        }
    }
    if (profile) {
        writeTextFile(*o.profile, profile->text());
        if (!o.quiet) err << "wrote " << *o.profile << "\n";
    }
    int status = kExitOk;
    if (diff)
        status = diffImages(output, *o.compare, *diff, out, nullptr, std::nullopt,
                            o.json ? &document["compare"] : nullptr);
    if (o.json) printJson(out, document);
    return status;
}

namespace {

// The pass table's mark of a pass run in one loop over the tiles with the pass above it.
constexpr const char* kFusedMark = "in the loop above";

// Milliseconds of the pass named `name` (0 if it did not run).
double passMs(const FrameStats& stats, const std::string& name) {
    for (const PassTime& p : stats.passes)
        if (p.name == name) return p.ms;
    return 0.0;
}

// One row of the trace table: its label (the JSON key is jsonKey(label)), its value for a pass
// that ran, and the decimals the text gives a fraction (an integer prints whole).
struct TraceRow {
    std::string label;
    std::function<Json(const TraceStats&, double marchMs)> value;
    int decimals = 2;
};

// The trace table's rows, in order: rays, how they ended, steps per ray, lane use, and the
// march's speed over its stage's time ("ssr march", "ssgi march"), null where there is none.
std::vector<TraceRow> traceRows() {
    using T = const TraceStats&;
    std::vector<TraceRow> rows = {
        {"rays per pixel", [](T t, double) { return Json(t.spp); }},
        {"surface pixels", [](T t, double) { return Json(t.rays.pixels); }},
        {"rays traced", [](T t, double) { return Json(t.march.rays); }},
        {"below surface", [](T t, double) { return Json(t.rays.belowSurface); }},
        {"hidden, no ray", [](T t, double) { return Json(t.rays.hidden); }},
        {"layout cut, no ray", [](T t, double) { return Json(t.rays.cut); }},
        // (of those, the pixels a long history spared: TraceSettings::ssrSparseFrames)
        {"  long history", [](T t, double) { return Json(t.rays.sparse); }},
    };
    for (int e = 0; e < kMarchEndCount; ++e) {
        if (MarchEnd(e) == MarchEnd::NoRay) continue;
        const std::string label = MarchEnd(e) == MarchEnd::Hit
                                      ? std::string("hits")
                                      : "miss: " + std::string(marchEndName(MarchEnd(e)));
        rows.push_back({label, [e](T t, double) { return Json(t.march.ends[e]); }});
    }
    // After the march (--ssr-trace mixed or world: renderer/world_stage.h): the hits the
    // proof holds, and the rays traced in world space, by what they met.
    std::vector<TraceRow> world = {
        {"proven hits", [](T t, double) { return Json(t.world.proven); }},
        {"world rays", [](T t, double) { return Json(t.world.sent); }},
        {"  hit, shown", [](T t, double) { return Json(t.world.shown); }},
        {"  hit, hidden", [](T t, double) { return Json(t.world.hidden); }},
        {"  missed", [](T t, double) { return Json(t.world.missed); }},
    };
    rows.insert(rows.end(), world.begin(), world.end());
    const auto share = [](uint64_t part, uint64_t whole) {
        return whole ? 100.0 * double(part) / double(whole) : 0.0;
    };
    std::vector<TraceRow> rest = {
        {"steps per ray, mean", [](T t, double) { return Json(t.march.meanSteps()); }},
        {"steps per ray, p50", [](T t, double) { return Json(t.march.stepsPercentile(0.5)); }},
        {"steps per ray, p95", [](T t, double) { return Json(t.march.stepsPercentile(0.95)); }},
        {"steps per ray, max", [](T t, double) { return Json(t.march.maxStepsTaken()); }},
        {"steps in all", [](T t, double) { return Json(t.march.steps); }},
        {"lanes active %",
         [share](T t, double) { return Json(share(t.march.laneActive, t.march.laneSlots)); }},
        // The march's speed: its rays, and its steps, over the march stage's wall time (summed
        // over the samples, every thread at work), as ssrt compare's "rays per second" is.
        {"Mrays per second",
         [](T t, double ms) {
             return ms > 0.0 ? Json(double(t.march.rays) * 1e-3 / ms) : Json(nullptr);
         }},
        {"ns per march step",
         [](T t, double ms) {
             return t.march.steps > 0 ? Json(ms * 1e6 / double(t.march.steps)) : Json(nullptr);
         }},
    };
    rows.insert(rows.end(), rest.begin(), rest.end());
    return rows;
}

// The screen-space passes side by side, from traceRows().
void printTraceStats(std::ostream& out, const FrameStats& stats) {
    const TraceStats* passes[2] = {&stats.ssr, &stats.ssgi};
    const double marchMs[2] = {passMs(stats, "ssr march"), passMs(stats, "ssgi march")};
    out << "\n"
        << std::left << std::setw(kLabelWidth + 2) << "trace counter" << std::right
        << std::setw(kValueWidth) << "ssr" << std::setw(kValueWidth) << "ssgi"
        << "\n";
    for (const TraceRow& r : traceRows()) {
        out << "  " << std::left << std::setw(kLabelWidth) << r.label << std::right;
        for (int p = 0; p < 2; ++p) {
            out << std::setw(kValueWidth);
            const Json v = passes[p]->ran ? r.value(*passes[p], marchMs[p]) : Json(nullptr);
            if (v.is_number_float())
                out << std::fixed << std::setprecision(r.decimals) << v.get<double>();
            else if (v.is_null()) out << "-";
            else out << v.dump();
        }
        out << "\n";
    }
}

// One pass's column of the trace table: {key: value}; null for a pass that did not run.
Json traceJson(const TraceStats& t, double marchMs) {
    if (!t.ran) return nullptr;
    Json out = Json::object();
    for (const TraceRow& r : traceRows()) out[jsonKey(r.label)] = r.value(t, marchMs);
    return out;
}

// What the frame holds, by resource group: bytes per pixel of the frame, and megabytes.
// One table of memory rows and their sum, under `title`.
void printMemory(std::ostream& out, const char* title, const std::vector<MemoryUse>& memory,
                 double pixels) {
    // (resource names are longer than pass names: the column widens to the longest)
    int width = kLabelWidth;
    for (const MemoryUse& m : memory) width = std::max(width, int(m.name.size()) + 1);
    out << "\n"
        << std::left << std::setw(width + 2) << title << std::right << std::setw(kValueWidth)
        << "B/pixel" << std::setw(kValueWidth) << "MB"
        << "\n";
    std::size_t sum = 0;
    const auto row = [&](const std::string& label, std::size_t bytes) {
        out << "  " << std::left << std::setw(width) << label << std::right << std::fixed
            << std::setprecision(1) << std::setw(kValueWidth) << double(bytes) / pixels
            << std::setw(kValueWidth) << double(bytes) / 1.0e6 << "\n";
    };
    for (const MemoryUse& m : memory) {
        row(m.name, m.bytes);
        sum += m.bytes;
    }
    row("in all", sum);
}

// A memory table in bytes, the text's rows before their units: {by_resource: {name: bytes},
// in_all: their sum}.
Json memoryJson(const std::vector<MemoryUse>& memory) {
    Json rows = Json::object();
    std::size_t sum = 0;
    for (const MemoryUse& m : memory) {
        rows[m.name] = m.bytes;
        sum += m.bytes;
    }
    return {{"by_resource", std::move(rows)}, {"in_all", sum}};
}

// The --stats figures of one frame as JSON, unrounded (docs/cli.md, "--json").
Json statsJson(const FrameStats& stats, double wallMs, double writeMs) {
    Json passes = Json::object();
    Json fused = Json::array();
    double sum = 0.0;
    for (const PassTime& p : stats.passes) {
        passes[p.name] = p.ms;
        if (p.fused) fused.push_back(p.name);
        sum += p.ms;
    }
    Json raster = {{"visibility", Json::object()}, {"shadow", Json::object()}};
    for (const Counter& c : kCounters) {
        raster["visibility"][jsonKey(c.label)] = stats.visibility.*c.field;
        raster["shadow"][jsonKey(c.label)] = stats.shadow.*c.field;
    }
    return {{"isa", isaName(stats.isa)},
            {"threads", stats.threads},
            {"pass_times", std::move(passes)},
            {"fused_passes", std::move(fused)},
            {"sum_of_passes_ms", sum},
            {"render_call_ms", wallMs},
            {"image_write_ms", writeMs},
            {"raster", std::move(raster)},
            {"trace",
             {{"ssr", traceJson(stats.ssr, passMs(stats, "ssr march"))},
              {"ssgi", traceJson(stats.ssgi, passMs(stats, "ssgi march"))}}},
            {"memory", memoryJson(stats.memory)},
            {"memory_declared", memoryJson(stats.declared)}};
}

}  // namespace

namespace {

// The process table's rows: label and milliseconds, none where the process start is unknown.
std::vector<std::pair<std::string, std::optional<double>>> processRows(const ProcessCosts& c) {
    return {{"CPU before main", c.cpuBeforeMainMs},
            {"command line", c.commandLineMs},
            {"scene set-up", c.sceneSetupMs}};
}

void printProcessCosts(std::ostream& out, const ProcessCosts& costs) {
    std::ios saved(nullptr);
    saved.copyfmt(out);
    out << "\n"
        << std::left << std::setw(kLabelWidth + 2) << "process" << std::right
        << std::setw(kValueWidth) << "ms"
        << "\n"
        << std::fixed << std::setprecision(3);
    for (const auto& [label, ms] : processRows(costs))
        if (ms)
            out << "  " << std::left << std::setw(kLabelWidth) << label << std::right
                << std::setw(kValueWidth) << *ms << "\n";
    out << "\nthe first render call touched " << costs.firstCallPageFaults
        << " pages for the first time (minor page faults)\n";
    out.copyfmt(saved);
}

Json processCostsJson(const ProcessCosts& costs) {
    Json j = Json::object();
    for (const auto& [label, ms] : processRows(costs))
        j[jsonKey(label) + "_ms"] = ms ? Json(*ms) : Json(nullptr);
    j["first_render_call_page_faults"] = costs.firstCallPageFaults;
    return j;
}

}  // namespace

void printStats(std::ostream& out, const FrameStats& stats, double pixels, double wallMs,
                double writeMs) {
    std::ios saved(nullptr);  // the caller's stream formatting, restored at the end
    saved.copyfmt(out);
    const auto row = [&](const std::string& label) -> std::ostream& {
        return out << "  " << std::left << std::setw(kLabelWidth) << label << std::right;
    };
    out << "isa " << isaName(stats.isa) << ", " << plural(stats.threads, "thread") << "\n\n";

    out << std::left << std::setw(kLabelWidth + 2) << "pass" << std::right << std::setw(kValueWidth)
        << "ms"
        << "\n";
    double sum = 0.0;
    out << std::fixed << std::setprecision(3);
    for (const PassTime& p : stats.passes) {
        row(p.name) << std::setw(kValueWidth) << p.ms;
        // (one loop over the tiles with the pass above: renderer/frame_scheduler.h)
        if (p.fused) out << "  " << kFusedMark;
        out << "\n";
        sum += p.ms;
    }
    row("sum of passes") << std::setw(kValueWidth) << sum << "\n";
    row("render call") << std::setw(kValueWidth) << wallMs << "\n";
    row("image write") << std::setw(kValueWidth) << writeMs << "\n\n";

    out << std::left << std::setw(kLabelWidth + 2) << "raster counter" << std::right
        << std::setw(kValueWidth) << "visibility" << std::setw(kValueWidth) << "shadow"
        << "\n";
    for (const Counter& c : kCounters) {
        row(c.label) << std::setw(kValueWidth) << stats.visibility.*c.field
                     << std::setw(kValueWidth) << stats.shadow.*c.field << "\n";
    }
    if (stats.ssr.ran || stats.ssgi.ran) printTraceStats(out, stats);
    if (!stats.memory.empty() && pixels > 0) printMemory(out, "memory", stats.memory, pixels);
    if (!stats.declared.empty() && pixels > 0)
        printMemory(out, "memory the frame graph declares", stats.declared, pixels);
    out.copyfmt(saved);
}

}  // namespace ssrt::cli
