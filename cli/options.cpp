#include "cli/options.h"

#include <oneapi/tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cli/memory_check.h"
#include "core/suggest.h"
#include "io/image_io.h"
#include "renderer/quality.h"
#include "renderer/settings_fields.h"
#include "renderer/sky_lighting.h"
#include "scenes/builtin_scenes.h"
#include "scenes/gltf_loader.h"
#include "scenes/shot.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

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

void checkSceneName(const std::string& name) {
    if (isSceneFile(name) || isBuiltinScene(name)) return;  // the loader names a bad file
    throw std::invalid_argument("--scene: unknown scene '" + name + "'" +
                                didYouMean(name, knownSceneNames()) + " (known: " + knownScenes() +
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
        throw std::runtime_error(source + ": " + e.what() +
                                 " (available here: " + supportedIsaList() + ")");
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
// The settings' fields

namespace {

std::string kebab(std::string_view key) {
    std::string out;
    for (char c : key) {
        if (std::isupper(static_cast<unsigned char>(c))) out.append("-").push_back(char(c + 32));
        else out.push_back(c);
    }
    return out;
}

bool defaultIsOn(const FieldInfo& f) {
    for (const auto& g : kRenderFields)
        if (g.key == f.key) return g.get(RenderSettings{}) != 0.0;
    return false;
}

// The flags CLI11 registers: the table's, or the derived long option.
std::string fieldFlags(const FieldInfo& f) {
    return f.flag.empty() ? fieldOption(f) : std::string(f.flag);
}

std::string fieldHelp(const FieldInfo& f) {
    if (f.type == FieldType::Bool)
        return std::string(f.help) + (defaultIsOn(f) ? " (on by default)" : " (off by default)");
    return std::string(f.help) + " (" + f.expected() + ")";
}

std::string fieldTypeName(const FieldInfo& f) {
    if (!f.typeName.empty()) return std::string(f.typeName);
    return f.type == FieldType::Int ? "INT" : f.type == FieldType::Float ? "FLOAT" : "NAME";
}

// Whether some quality preset sets the field `key` (renderer/quality.cpp's table).
bool aPresetSets(std::string_view key) {
    for (int q = 0; q < kQualityCount; ++q)
        for (const PresetValue& v : qualityValues(Quality(q)))
            if (v.key == key) return true;
    return false;
}

// One option per CLI field of kRenderFields[begin, end), remembered only when typed (so the
// shot, or else the command's default, decides otherwise); help shows `defaults`.
void addFieldOptions(CLI::App& cmd, RenderOptions& o, const RenderSettings& defaults,
                     std::size_t begin, std::size_t end, const std::string& group) {
    for (std::size_t i = begin; i < end; ++i) {
        const Field<RenderSettings>& f = kRenderFields[i];
        if (!f.has(kFieldCli)) continue;
        const std::string key(f.key);
        CLI::Option* option;
        if (f.type == FieldType::Bool) {
            const std::string value = defaultIsOn(f) ? "false" : "true";
            option = cmd.add_flag_callback(
                fieldFlags(f), [&o, key, value] { o.settings[key] = value; }, fieldHelp(f));
            // A switch that is off by default but that a preset turns on needs its way off.
            if (!defaultIsOn(f) && f.flag.empty() && aPresetSets(key)) {
                CLI::Option* off = cmd.add_flag_callback(
                    "--no-" + kebab(key), [&o, key] { o.settings[key] = "false"; },
                    "Turn " + fieldOption(f) + " off where the --quality preset turns it on");
                off->excludes(option);
                if (!group.empty()) off->group(group);
            }
        } else {
            option = cmd.add_option_function<std::string>(
                            fieldFlags(f), [&o, key](const std::string& v) { o.settings[key] = v; },
                            fieldHelp(f))
                         ->type_name(fieldTypeName(f))
                         ->default_str(f.text(f.get(defaults)));
        }
        if (!group.empty()) option->group(group);
    }
}

}  // namespace

std::string fieldOption(const FieldInfo& f) {
    if (!f.flag.empty()) {
        const std::string_view flags = f.flag;
        const std::size_t comma = flags.rfind(',');
        return std::string(comma == std::string_view::npos ? flags : flags.substr(comma + 1));
    }
    if (f.type == FieldType::Bool && defaultIsOn(f)) return "--no-" + kebab(f.key);
    return "--" + kebab(f.key);
}

const Field<RenderSettings>& renderField(std::string_view key) {
    for (const auto& f : kRenderFields)
        if (f.key == key) return f;
    throw std::logic_error("no settings field '" + std::string(key) + "'");
}

double parseFieldText(const FieldInfo& f, const std::string& option, const std::string& text) {
    switch (f.type) {
        case FieldType::Int:
            return double(parseInteger(option, text, (long long)f.range.lo, (long long)f.range.hi));
        case FieldType::Float: {
            // from_chars reads "nan" and "inf"; accepts() refuses both.
            float value = 0.0f;
            const char* end = text.data() + text.size();
            const auto [ptr, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ptr != end || ec != std::errc{} || !f.accepts(value))
                badValue(option, text, f.expected());
            return value;
        }
        case FieldType::Choice: {
            const int i = f.choiceIndex(text);
            if (i < 0) badValue(option, text, "one of " + f.choiceList());
            return i;
        }
        case FieldType::Bool:
            if (text == "true") return 1.0;
            if (text == "false") return 0.0;
            badValue(option, text, "true or false");
    }
    return 0.0;
}

void addTraceOptions(CLI::App& cmd, RenderOptions& o) {
    addFieldOptions(cmd, o, RenderSettings{}, kRenderOwnFields.size(), kRenderFields.size(),
                    "Screen-space tracing");
}

void addSceneOptions(CLI::App& cmd, RenderOptions& o, const RenderSettings& d) {
    // Options that a shot file can also give: remembered only when typed, so that the shot
    // decides otherwise; help shows the command's default.
    const auto addShotOption = [&](const std::string& flags, std::optional<std::string>& value,
                                   const std::string& type, const std::string& help,
                                   const std::string& defaultText) {
        cmd.add_option_function<std::string>(
               flags, [&value](const std::string& v) { value = v; }, help)
            ->type_name(type)
            ->default_str(defaultText);
    };
    addShotOption("--shot", o.shot, "FILE",
                  "Shot file (JSON): scene, camera and camera path, light, environment, render "
                  "and tracing settings; every field optional, and the flags below override it",
                  "");
    addShotOption("-s,--scene", o.scene, "NAME",
                  "Built-in scene to render (list them: ssrt scenes), or a .gltf/.glb file",
                  defaultSceneName());
    addShotOption("--quality", o.quality, "PRESET",
                  "Quality preset: " + std::string(qualityList()) +
                      " (each a set of the tracing and denoising settings below, which flags "
                      "given beside it override; the default is " +
                      std::string(qualityName(kDefaultQuality)) +
                      "'s values; ultra traces every pixel, as before presets)",
                  std::string(qualityName(kDefaultQuality)));
    addFieldOptions(cmd, o, d, 0, kRenderOwnFields.size(), "");
    cmd.add_option("--isa", o.isa,
                   "Kernels to run: auto, " + isaChoices() +
                       "; auto = $SSRT_ISA if set, else the best this CPU runs of those built")
        ->type_name("ISA")
        ->capture_default_str();
    addShotOption("--frame", o.frame, "INT",
                  "Frame index (seeds the per-pixel random numbers); of a sequence's first frame, "
                  "frame i getting this + i",
                  "0");
    cmd.add_flag("--strict", o.strict,
                 "Every warning about a glTF file (points and lines skipped, lights, cameras, "
                 "extensions or textures ignored) is an error: exit 3, nothing written");
}

void addImageOutputOptions(CLI::App& cmd, RenderOptions& o) {
    cmd.add_option_function<std::string>(
           "--layers", [&o](const std::string& v) { o.layers = v; },
           "EXR layer groups to write, comma-separated: all, or " + layerGroupList() +
               " (color: color, display, shadow; gbuffer: the G-buffer, material planes and "
               "ids; trace: SSR, SSGI and the denoiser's; truth: compare's reference and checks)")
        ->type_name("LIST")
        ->default_str("all");
    cmd.add_option_function<std::string>(
           "--exr-compression", [&o](const std::string& v) { o.exrCompression = v; },
           "EXR compression, all lossless: " + exrCompressionList() +
               " (none is fastest and largest; zip and piz the smallest and slowest)")
        ->type_name("NAME")
        ->default_str(std::string(exrCompressionName(kDefaultExrCompression)));
}

FrameWriteOptions writeOptionsFrom(const RenderOptions& o, const RenderSettings& settings,
                                   const std::string& output, std::ostream& err) {
    FrameWriteOptions w;
    w.file.threads = threadsFor(settings);
    if (o.layers) {
        w.layers.reset();
        for (const std::string& item : splitList("--layers", *o.layers))
            w.layers |=
                item == "all"
                    ? allLayerGroups()
                    : LayerGroups().set(int(parseChoice("--layers", item, parseLayerGroup,
                                                        "all or one of " + layerGroupList())));
    }
    if (o.exrCompression)
        w.file.compression = parseChoice("--exr-compression", *o.exrCompression,
                                         parseExrCompression, exrCompressionList());
    if ((o.layers || o.exrCompression) && !isExrPath(output))
        err << "ssrt: warning: --layers and --exr-compression apply to EXR files only; '" << output
            << "' is not one, so they are ignored\n";
    return w;
}

void writeFrame(const std::string& path, const Frame& frame, const FrameWriteOptions& options) {
    writeImage(path, frameLayers(frame, isExrPath(path) ? options.layers : allLayerGroups()),
               options.file);
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

void writeTextFile(const std::string& path, const std::string& text) { writeTextWhole(path, text); }

void checkCsvPath(const std::string& option, const std::string& path) {
    checkTextPath(option, path, ".csv");
}

void checkTextPath(const std::string& option, const std::string& path,
                   const std::string& extension) {
    const fs::path p(path);
    if (p.extension() != extension)
        throw std::invalid_argument(option + ": '" + path + "' must end in " + extension);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw std::runtime_error(path + ": directory '" + dir.string() + "' does not exist");
    if (fs::is_directory(p, ec)) throw std::runtime_error(path + ": is a directory");
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
    r.strict = o.strict;
    checkFrameMemory(r.settings, availableMemory());
    return r;
}

void loadScene(SceneRequest& r, std::ostream& err) {
    // A glTF file or an environment image that cannot be loaded is a runtime error (exit 1).
    if (isSceneFile(r.name)) {
        GltfLoadReport report;
        r.scene = loadGltf(r.name, GltfLoadOptions{r.strict}, &report);
        for (const std::string& w : report.warnings) err << "ssrt: warning: " << w << "\n";
    } else {
        r.scene = makeBuiltinScene(r.name);
    }
    if (r.shot) {
        applyShot(*r.shot, r.scene);
        if (r.shot->environment.file)
            r.scene.sky.image = std::make_shared<const SkyImage>(
                makeSkyImage(*r.shot->environment.file, readSkyImage(*r.shot->environment.file)));
        r.path = shotCameraPath(*r.shot, r.scene.camera);
    }
}

}  // namespace ssrt::cli
