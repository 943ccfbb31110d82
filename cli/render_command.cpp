#include "cli/render_command.h"

#include <oneapi/tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "cli/cli.h"
#include "io/image_io.h"
#include "scenes/builtin_scenes.h"
#include "scenes/gltf_loader.h"
#include "scenes/shot.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------
// Numbers from text

inline constexpr long long kMaxThreads = 256;
inline constexpr long long kMinShadowMap = 16;
inline constexpr long long kMaxShadowMap = 8192;
inline constexpr long long kMaxFrame = 4294967295ll;  // RenderSettings::frame is 32 bits

[[noreturn]] void badValue(const std::string& option, const std::string& text,
                           const std::string& expected) {
    throw std::invalid_argument(option + ": invalid value '" + text + "' (expected " + expected +
                                ")");
}

// The whole text must be a decimal integer in [lo, hi]; no sign tricks, spaces or suffixes.
long long parseInteger(const std::string& option, const std::string& text, long long lo,
                       long long hi) {
    const std::string expected =
        "an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
    long long value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    // ec is set for non-numbers and for values beyond long long alike.
    if (text.empty() || ptr != end || ec != std::errc{} || value < lo || value > hi)
        badValue(option, text, expected);
    return value;
}

// A finite number greater than zero (from_chars reads "nan" and "inf", so check both).
float parsePositive(const std::string& option, const std::string& text) {
    float value = 0.0f;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ptr != end || ec != std::errc{} || !std::isfinite(value) || value <= 0)
        badValue(option, text, "a finite number greater than 0");
    return value;
}

// One of a fixed set of names, through the enum's own parser.
template <class Parse>
auto parseChoice(const std::string& option, const std::string& text, Parse parse,
                 const std::string& choices) {
    const auto value = parse(text);
    if (!value) badValue(option, text, "one of " + choices);
    return *value;
}

std::string defaultSceneName() {
    const auto& scenes = builtinScenes();
    return scenes.empty() ? "cornell" : scenes.front().name;
}

std::string knownScenes() {
    std::string out;
    for (const auto& s : builtinScenes()) out += (out.empty() ? "" : ", ") + s.name;
    return out;
}

// A --scene value naming a glTF file rather than a built-in scene.
bool isSceneFile(const std::string& name) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    auto endsWith = [&](const std::string& ext) {
        return lower.size() > ext.size() && lower.compare(lower.size() - ext.size(), ext.size(), ext) == 0;
    };
    return endsWith(".gltf") || endsWith(".glb");
}

void checkSceneName(const std::string& name) {
    if (isSceneFile(name)) return;  // the loader names what is wrong with a file
    for (const auto& s : builtinScenes())
        if (s.name == name) return;
    throw std::invalid_argument("--scene: unknown scene '" + name + "' (known: " + knownScenes() +
                                ")");
}

std::string supportedIsaList() {
    std::string out;
    for (Isa isa : supportedIsas()) out += (out.empty() ? "" : ", ") + std::string(isaName(isa));
    return out;
}

// The ISA the renderer will run, resolved now so a CPU without it fails before any work.
// Errors name where the request came from: --isa, or SSRT_ISA under --isa auto.
Isa resolveIsaFor(std::optional<Isa> requested) {
    const std::string source = requested ? "--isa" : "SSRT_ISA";
    try {
        return resolveIsa(requested);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(source + ": " + e.what());
    } catch (const std::exception& e) {
        throw std::runtime_error(source + ": " + e.what() + " (this CPU runs " +
                                 supportedIsaList() + ")");
    }
}

int threadsFor(const RenderSettings& settings) {
    // 0 means what oneTBB would use: every core this process may run on.
    return settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
}

std::string plural(int n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

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
    {"bin entries", &RasterStats::binEntries},
    {"blocks rejected", &RasterStats::blocksRejected},
    {"blocks accepted", &RasterStats::blocksAccepted},
    {"blocks partial", &RasterStats::blocksPartial},
    {"pixels tested", &RasterStats::pixelsTested},
    {"pixels covered", &RasterStats::pixelsCovered},
    {"pixels written", &RasterStats::pixelsWritten},
};

constexpr int kLabelWidth = 20;
constexpr int kValueWidth = 14;

}  // namespace

// ---------------------------------------------------------------------------------------
// Options

namespace {

const std::string kSsrMethods = "mirror, ggx_ndf, vndf_ellipsoid, vndf_spherical_caps, vndf_bounded";
const std::string kMarchers = "linear, dda, hiz";
inline constexpr long long kMaxMarchSteps = 65536;

std::optional<SsrResolveMode> parseResolveMode(std::string_view s) {
    if (s == "mip") return SsrResolveMode::Mip;
    if (s == "reuse") return SsrResolveMode::Reuse;
    return std::nullopt;
}
std::optional<HitRadiance> parseHitRadiance(std::string_view s) {
    if (s == "current") return HitRadiance::Current;
    if (s == "reprojected") return HitRadiance::Reprojected;
    return std::nullopt;
}

void addTraceOptions(CLI::App& cmd, RenderOptions& o) {
    const TraceSettings d;
    const auto add = [&](const std::string& flags, std::optional<std::string>& value,
                         const std::string& type, const std::string& help,
                         const std::string& defaultText) {
        cmd.add_option_function<std::string>(
               flags, [&value](const std::string& v) { value = v; }, help)
            ->type_name(type)
            ->default_str(defaultText)
            ->group("Screen-space tracing");
    };
    cmd.add_flag("--no-ssr", o.noSsr, "Skip screen-space reflections (the environment's split-sum "
                                      "light stands in)")
        ->group("Screen-space tracing");
    cmd.add_flag("--no-ssgi", o.noSsgi,
                 "Skip screen-space one-bounce diffuse (the environment's irradiance stands in)")
        ->group("Screen-space tracing");
    add("--ssr-method", o.ssrMethod, "NAME", "How SSR rays sample the GGX lobe: " + kSsrMethods,
        std::string(ssrMethodName(d.ssrMethod)));
    add("--marcher", o.marcher, "NAME", "Depth-buffer marcher for SSR and SSGI rays: " + kMarchers,
        std::string(marcherName(d.marcher)));
    add("--ssr-spp", o.ssrSpp, "INT",
        "SSR rays per pixel, 1 to " + std::to_string(TraceSettings::kMaxSpp),
        std::to_string(d.ssrSpp));
    add("--ssgi-spp", o.ssgiSpp, "INT",
        "SSGI rays per pixel, 1 to " + std::to_string(TraceSettings::kMaxSpp),
        std::to_string(d.ssgiSpp));
    add("--max-steps", o.maxSteps, "INT",
        "March steps per ray (Hi-Z: iterations), 1 to " + std::to_string(kMaxMarchSteps),
        std::to_string(d.march.maxSteps));
    std::ostringstream thickness;
    thickness << d.march.thickness;
    add("--thickness", o.thickness, "FLOAT",
        "Depth a surface is assumed to have behind the depth buffer (view-space units), > 0",
        thickness.str());
    add("--ssr-resolve", o.ssrResolve, "MODE",
        "SSR resolve: reuse (3x3 neighbours' hits, ratio estimator) or mip (colour pyramid at "
        "mip = roughness x max mip)",
        d.resolve.mode == SsrResolveMode::Mip ? "mip" : "reuse");
    add("--hit-radiance", o.hitRadiance, "SOURCE",
        "Radiance at a hit: current (this frame's direct light) or reprojected (the previous "
        "frame's final colour through the motion vectors; a sequence's first frame uses current)",
        d.resolve.radiance == HitRadiance::Current ? "current" : "reprojected");
}

void traceSettingsFrom(const RenderOptions& o, TraceSettings& t) {
    if (o.noSsr) t.ssr = false;
    if (o.noSsgi) t.ssgi = false;
    if (o.ssrMethod)
        t.ssrMethod = parseChoice("--ssr-method", *o.ssrMethod, parseSsrMethod, kSsrMethods);
    if (o.marcher) t.marcher = parseChoice("--marcher", *o.marcher, parseMarcher, kMarchers);
    if (o.ssrSpp) t.ssrSpp = int(parseInteger("--ssr-spp", *o.ssrSpp, 1, TraceSettings::kMaxSpp));
    if (o.ssgiSpp)
        t.ssgiSpp = int(parseInteger("--ssgi-spp", *o.ssgiSpp, 1, TraceSettings::kMaxSpp));
    if (o.maxSteps) t.march.maxSteps = int(parseInteger("--max-steps", *o.maxSteps, 1, kMaxMarchSteps));
    if (o.thickness) t.march.thickness = parsePositive("--thickness", *o.thickness);
    if (o.ssrResolve)
        t.resolve.mode = parseChoice("--ssr-resolve", *o.ssrResolve, parseResolveMode, "mip, reuse");
    if (o.hitRadiance)
        t.resolve.radiance =
            parseChoice("--hit-radiance", *o.hitRadiance, parseHitRadiance, "current, reprojected");
}

}  // namespace

RenderOptions::RenderOptions() {
    const RenderSettings d;
    threads = std::to_string(d.threads);
    isa = d.isa ? std::string(isaName(*d.isa)) : "auto";
}

CLI::App* addRenderCommand(CLI::App& app, RenderOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "render",
        "Render a frame, or a sequence along a shot's camera path, of a built-in scene or a glTF "
        "file to PNG or EXR files");
    const RenderSettings d;
    // Options that a shot file can also give: remembered only when typed, so that the shot
    // decides otherwise; help shows the built-in default.
    const auto addShotOption = [&](const std::string& flags, std::optional<std::string>& value,
                                   const std::string& type, const std::string& help,
                                   const std::string& defaultText) {
        cmd->add_option_function<std::string>(
               flags, [&value](const std::string& v) { value = v; }, help)
            ->type_name(type)
            ->default_str(defaultText);
    };
    const auto add = [&](const std::string& flags, std::string& value, const std::string& type,
                         const std::string& help) {
        cmd->add_option(flags, value, help)->type_name(type)->capture_default_str();
    };
    std::ostringstream exposure;
    exposure << d.exposure;
    addShotOption("--shot", o.shot, "FILE",
                  "Shot file (JSON): scene, camera and camera path, light, environment, render "
                  "settings; every field optional, and the flags below override it",
                  "");
    addShotOption("-s,--scene", o.scene, "NAME",
                  "Built-in scene to render (list them: ssrt scenes), or a .gltf/.glb file",
                  defaultSceneName());
    addShotOption("--width", o.width, "INT",
                  "Image width in pixels, 1 to " + std::to_string(kMaxImageSize),
                  std::to_string(d.width));
    addShotOption("--height", o.height, "INT",
                  "Image height in pixels, 1 to " + std::to_string(kMaxImageSize),
                  std::to_string(d.height));
    add("-j,--threads", o.threads, "INT",
        "Worker threads, 0 to " + std::to_string(kMaxThreads) + "; 0 = every core");
    add("--isa", o.isa, "ISA",
        "Kernels to run: auto, scalar, sse2, sse42, avx2 or avx512; auto = $SSRT_ISA if set, "
        "else the best this CPU runs");
    addShotOption("--shadow-map-size", o.shadowMapSize, "INT",
                  "Shadow map texels per side, " + std::to_string(kMinShadowMap) + " to " +
                      std::to_string(kMaxShadowMap),
                  std::to_string(d.shadowMapSize));
    addShotOption("--exposure", o.exposure, "FLOAT",
                  "Scale on linear radiance before the tone map, > 0", exposure.str());
    addShotOption("--frame", o.frame, "INT",
                  "Frame index (seeds the per-pixel random numbers); of a sequence's first frame, "
                  "frame i getting this + i",
                  std::to_string(d.frame));
    addShotOption("--frames", o.frames, "INT",
                  "Frames to render, 1 to " + std::to_string(kMaxShotFrames) +
                      ": evenly along the shot's camera path from its first key to its last "
                      "(Catmull-Rom or linear, as the shot says), or N frames of the still "
                      "camera without a path",
                  "1");
    add("-o,--output", o.output, "FILE",
        "Output image: .png (tone-mapped preview) or .exr (every plane as a float layer); with "
        "more than one frame, frame i goes to NAME_iiii.EXT (out.png: out_0000.png, "
        "out_0001.png, ...)");
    addTraceOptions(*cmd, o);
    cmd->add_flag("--stats", o.stats,
                  "Print per-pass times, rasterizer counters and the screen-space march's "
                  "counters (per frame)");
    cmd->add_flag("-q,--quiet", o.quiet, "No progress lines on stderr");
    return cmd;
}

RenderSettings settingsFrom(const RenderOptions& o, const RenderSettings& base) {
    RenderSettings s = base;
    if (o.width) s.width = int(parseInteger("--width", *o.width, 1, kMaxImageSize));
    if (o.height) s.height = int(parseInteger("--height", *o.height, 1, kMaxImageSize));
    s.threads = int(parseInteger("--threads", o.threads, 0, kMaxThreads));
    try {
        s.isa = parseIsa(o.isa);
    } catch (const std::exception& e) {
        throw std::invalid_argument(std::string("--isa: ") + e.what());
    }
    if (o.shadowMapSize)
        s.shadowMapSize =
            int(parseInteger("--shadow-map-size", *o.shadowMapSize, kMinShadowMap, kMaxShadowMap));
    if (o.exposure) s.exposure = parsePositive("--exposure", *o.exposure);
    if (o.frame) s.frame = uint32_t(parseInteger("--frame", *o.frame, 0, kMaxFrame));
    traceSettingsFrom(o, s.trace);
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

// ---------------------------------------------------------------------------------------
// The command

int runRender(const RenderOptions& o, std::ostream& out, std::ostream& err) {
    // Everything that can be wrong with the request fails here, before any rendering and
    // before any file exists: flags (exit 2), then the shot file (exit 1).
    RenderSettings base;
    std::optional<Shot> shot;
    if (o.shot) {
        shot = loadShot(*o.shot);
        applyShot(*shot, base);
    }
    const RenderSettings settings = settingsFrom(o, base);
    int frames = shot && shot->render.frames ? *shot->render.frames : 1;
    if (o.frames) frames = int(parseInteger("--frames", *o.frames, 1, kMaxShotFrames));
    if (settings.frame + uint64_t(frames - 1) > uint64_t(kMaxFrame))
        throw std::invalid_argument("--frame: " + std::to_string(settings.frame) + " + " +
                                    std::to_string(frames) + " frames passes " +
                                    std::to_string(kMaxFrame));
    std::string sceneName = defaultSceneName();
    if (o.scene) {
        checkSceneName(*o.scene);
        sceneName = *o.scene;
    } else if (shot && shot->scene) {
        sceneName = *shot->scene;  // checked by the shot's parser
    }
    const Isa isa = resolveIsaFor(settings.isa);
    checkWritable(sequenceFileName(o.output, 0, frames));

    // A glTF file or an environment image that cannot be loaded is a runtime error (exit 1),
    // thrown before anything is written.
    Scene scene = isSceneFile(sceneName) ? loadGltf(sceneName) : makeBuiltinScene(sceneName);
    CameraPath path;
    if (shot) {
        applyShot(*shot, scene);
        if (shot->environment.file)
            scene.sky.image =
                std::make_shared<const SkyImage>(readSkyImage(*shot->environment.file));
        path = shotCameraPath(*shot, scene.camera);
    }
    if (!o.quiet) {
        err << "rendering " << sceneName << " " << settings.width << "x" << settings.height
            << (frames > 1 ? ", " + plural(frames, "frame") : std::string()) << " on "
            << isaName(isa) << ", " << plural(threadsFor(settings), "thread") << "...\n";
    }

    // One Frame for the whole sequence: its planes and scratch buffers are reused. Frame i
    // looks from the path at frameTime(i, frames) and its previous camera is frame i - 1's
    // (frame 0's is itself), so motion vectors follow the path.
    Frame frame;
    Camera previous;
    for (int i = 0; i < frames; ++i) {
        const Camera camera =
            path.empty() ? scene.camera : path.at(path.frameTime(i, frames), scene.camera);
        const Camera& previousCamera =
            i > 0 ? previous : (path.empty() ? scene.previousCamera : camera);
        RenderSettings frameSettings = settings;
        frameSettings.frame = settings.frame + uint32_t(i);
        const auto start = std::chrono::steady_clock::now();
        Renderer(frameSettings).render(scene, camera, previousCamera, frame);
        const std::chrono::duration<double, std::milli> wall =
            std::chrono::steady_clock::now() - start;
        previous = camera;

        const std::string file = sequenceFileName(o.output, i, frames);
        writeImage(file, frame);
        if (!o.quiet) {
            if (frames > 1)
                err << "frame " << (i + 1) << "/" << frames << ": wrote " << file << "\n";
            else
                err << "wrote " << file << "\n";
        }
        if (o.stats) {
            if (frames > 1) out << (i > 0 ? "\n" : "") << "frame " << i << " (" << file << ")\n";
            // The renderer may report the thread setting (0 = every core) rather than the count.
            FrameStats stats = frame.stats;
            if (stats.threads <= 0) stats.threads = threadsFor(settings);
            printStats(out, stats, wall.count());
        }
    }
    return kExitOk;
}

namespace {

// The screen-space passes side by side: rays, how they ended, steps per ray, lane use.
void printTraceStats(std::ostream& out, const FrameStats& stats) {
    const TraceStats* passes[2] = {&stats.ssr, &stats.ssgi};
    const auto row = [&](const std::string& label, auto value) {
        out << "  " << std::left << std::setw(kLabelWidth) << label << std::right;
        for (const TraceStats* t : passes) {
            out << std::setw(kValueWidth);
            if (t->ran) out << value(*t);
            else out << "-";
        }
        out << "\n";
    };
    const auto share = [](uint64_t part, uint64_t whole) {
        return whole ? 100.0 * double(part) / double(whole) : 0.0;
    };
    out << "\n" << std::left << std::setw(kLabelWidth + 2) << "trace counter" << std::right
        << std::setw(kValueWidth) << "ssr" << std::setw(kValueWidth) << "ssgi" << "\n";
    row("rays per pixel", [](const TraceStats& t) { return t.spp; });
    row("surface pixels", [](const TraceStats& t) { return t.rays.pixels; });
    row("rays traced", [](const TraceStats& t) { return t.march.rays; });
    row("below surface", [](const TraceStats& t) { return t.rays.belowSurface; });
    for (int e = 0; e < kMarchEndCount; ++e) {
        if (MarchEnd(e) == MarchEnd::NoRay) continue;
        const std::string label = MarchEnd(e) == MarchEnd::Hit
                                      ? std::string("hits")
                                      : "miss: " + std::string(marchEndName(MarchEnd(e)));
        row(label, [e](const TraceStats& t) { return t.march.ends[e]; });
    }
    out << std::fixed << std::setprecision(2);
    row("steps per ray, mean", [](const TraceStats& t) { return t.march.meanSteps(); });
    row("steps per ray, p50", [](const TraceStats& t) { return t.march.stepsPercentile(0.5); });
    row("steps per ray, p95", [](const TraceStats& t) { return t.march.stepsPercentile(0.95); });
    row("steps per ray, max", [](const TraceStats& t) { return t.march.maxStepsTaken(); });
    row("steps in all", [](const TraceStats& t) { return t.march.steps; });
    row("lanes active %", [&](const TraceStats& t) {
        return share(t.march.laneActive, t.march.laneSlots);
    });
}

}  // namespace

void printStats(std::ostream& out, const FrameStats& stats, double wallMs) {
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
        row(p.name) << std::setw(kValueWidth) << p.ms << "\n";
        sum += p.ms;
    }
    row("sum of passes") << std::setw(kValueWidth) << sum << "\n";
    row("render call") << std::setw(kValueWidth) << wallMs << "\n\n";

    out << std::left << std::setw(kLabelWidth + 2) << "raster counter" << std::right
        << std::setw(kValueWidth) << "visibility" << std::setw(kValueWidth) << "shadow"
        << "\n";
    for (const Counter& c : kCounters) {
        row(c.label) << std::setw(kValueWidth) << stats.visibility.*c.field
                     << std::setw(kValueWidth) << stats.shadow.*c.field << "\n";
    }
    if (stats.ssr.ran || stats.ssgi.ran) printTraceStats(out, stats);
    out.copyfmt(saved);
}

}  // namespace ssrt::cli
