#include "cli/options.h"

#include <oneapi/tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "io/image_io.h"
#include "scenes/builtin_scenes.h"
#include "scenes/gltf_loader.h"
#include "scenes/shot.h"

namespace ssrt::cli {

// ---------------------------------------------------------------------------------------
// Numbers from text

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
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    auto endsWith = [&](const std::string& ext) {
        return lower.size() > ext.size() &&
               lower.compare(lower.size() - ext.size(), ext.size(), ext) == 0;
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
    cmd.add_flag("--no-ssr", o.noSsr,
                 "Skip screen-space reflections (the environment's split-sum "
                 "light stands in)")
        ->group("Screen-space tracing");
    cmd.add_flag("--no-ssgi", o.noSsgi,
                 "Skip screen-space one-bounce diffuse (the environment's irradiance stands in)")
        ->group("Screen-space tracing");
    cmd.add_flag("--trace-hidden", o.traceHidden,
                 "Trace rays also where the composite hides what they find: SSR where the "
                 "roughness fade does (perceptual roughness >= 0.7), SSGI on metals (no diffuse "
                 "colour). The image is the same at those pixels; the counters and hit planes "
                 "then cover them too. By default they get no ray")
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
    if (o.traceHidden) t.traceHidden = true;
    if (o.ssrMethod)
        t.ssrMethod = parseChoice("--ssr-method", *o.ssrMethod, parseSsrMethod, kSsrMethods);
    if (o.marcher) t.marcher = parseChoice("--marcher", *o.marcher, parseMarcher, kMarchers);
    if (o.ssrSpp) t.ssrSpp = int(parseInteger("--ssr-spp", *o.ssrSpp, 1, TraceSettings::kMaxSpp));
    if (o.ssgiSpp)
        t.ssgiSpp = int(parseInteger("--ssgi-spp", *o.ssgiSpp, 1, TraceSettings::kMaxSpp));
    if (o.maxSteps)
        t.march.maxSteps = int(parseInteger("--max-steps", *o.maxSteps, 1, kMaxMarchSteps));
    if (o.thickness) t.march.thickness = parsePositive("--thickness", *o.thickness);
    if (o.ssrResolve)
        t.resolve.mode =
            parseChoice("--ssr-resolve", *o.ssrResolve, parseResolveMode, "mip, reuse");
    if (o.hitRadiance)
        t.resolve.radiance =
            parseChoice("--hit-radiance", *o.hitRadiance, parseHitRadiance, "current, reprojected");
}

void addSceneOptions(CLI::App& command, RenderOptions& o, const RenderSettings& d) {
    CLI::App* cmd = &command;
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
                  "0");
}

std::vector<std::string> splitList(const std::string& option, const std::string& text) {
    std::vector<std::string> items;
    std::string item;
    std::istringstream in(text);
    while (std::getline(in, item, ','))
        if (item.empty()) badValue(option, text, "a comma-separated list without empty items");
        else items.push_back(item);
    if (items.empty() || text.back() == ',')
        badValue(option, text, "a comma-separated list without empty items");
    return items;
}

SceneRequest loadSceneRequest(const RenderOptions& o, const RenderSettings& defaults) {
    // Everything that can be wrong with the request fails here, before any rendering and
    // before any file exists: flags (exit 2), then the shot file (exit 1).
    SceneRequest r;
    RenderSettings base = defaults;
    if (o.shot) {
        r.shot = loadShot(*o.shot);
        applyShot(*r.shot, base);
    }
    r.settings = settingsFrom(o, base);
    if (r.shot && r.shot->render.frame) r.firstFrame = *r.shot->render.frame;
    if (o.frame) r.firstFrame = uint32_t(parseInteger("--frame", *o.frame, 0, kMaxFrame));
    r.name = defaultSceneName();
    if (o.scene) {
        checkSceneName(*o.scene);
        r.name = *o.scene;
    } else if (r.shot && r.shot->scene) {
        r.name = *r.shot->scene;  // checked by the shot's parser
    }
    r.isa = resolveIsaFor(r.settings.isa);
    return r;
}

void loadScene(SceneRequest& r) {
    // A glTF file or an environment image that cannot be loaded is a runtime error (exit 1).
    r.scene = isSceneFile(r.name) ? loadGltf(r.name) : makeBuiltinScene(r.name);
    if (r.shot) {
        applyShot(*r.shot, r.scene);
        if (r.shot->environment.file)
            r.scene.sky.image =
                std::make_shared<const SkyImage>(readSkyImage(*r.shot->environment.file));
        r.path = shotCameraPath(*r.shot, r.scene.camera);
    }
}

FrameInput requestInput(const SceneRequest& r) {
    FrameInput in;
    in.frameIndex = r.firstFrame;
    if (r.path.empty()) {
        in.camera = r.scene.camera;
        in.previousCamera = r.scene.previousCamera;
    } else {
        in.camera = in.previousCamera = r.path.at(r.path.frameTime(0, 1), r.scene.camera);
    }
    return in;
}

}  // namespace ssrt::cli
