// What the commands that render share: numbers and names from text with one-line errors
// naming the option, the screen-space tracing options, and the scene a request names
// (built-in, glTF or shot file) loaded the same way for `render`, `compare` and `sweep`.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/render_command.h"
#include "core/isa.h"
#include "renderer/renderer.h"
#include "scenes/camera_path.h"
#include "scenes/scene.h"
#include "scenes/shot.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

inline constexpr long long kMaxThreads = 256;
inline constexpr long long kMinShadowMap = 16;
inline constexpr long long kMaxShadowMap = 8192;
inline constexpr long long kMaxFrame = 4294967295ll;  // RenderSettings::frame is 32 bits
inline constexpr long long kMaxMarchSteps = 65536;
inline const std::string kSsrMethods =
    "mirror, ggx_ndf, vndf_ellipsoid, vndf_spherical_caps, vndf_bounded";
inline const std::string kMarchers = "linear, dda, hiz";

[[noreturn]] void badValue(const std::string& option, const std::string& text,
                           const std::string& expected);
// The whole text must be a decimal integer in [lo, hi]; no sign tricks, spaces or suffixes.
long long parseInteger(const std::string& option, const std::string& text, long long lo,
                       long long hi);
// A finite number greater than zero.
float parsePositive(const std::string& option, const std::string& text);
// One of a fixed set of names, through the enum's own parser.
template <class Parse>
auto parseChoice(const std::string& option, const std::string& text, Parse parse,
                 const std::string& choices) {
    const auto value = parse(text);
    if (!value) badValue(option, text, "one of " + choices);
    return *value;
}
std::optional<SsrResolveMode> parseResolveMode(std::string_view s);
std::optional<HitRadiance> parseHitRadiance(std::string_view s);
// "a,b,c" -> {a, b, c}; an empty item is an error naming the option.
std::vector<std::string> splitList(const std::string& option, const std::string& text);

std::string defaultSceneName();
std::string knownScenes();
bool isSceneFile(const std::string& name);  // .gltf or .glb
void checkSceneName(const std::string& name);
// The ISA the renderer will run, resolved now so a CPU without it fails before any work.
Isa resolveIsaFor(std::optional<Isa> requested);
int threadsFor(const RenderSettings& settings);  // 0 -> every core
std::string plural(int n, const std::string& noun);

// --shot, --scene, --width, --height, --threads, --isa, --shadow-map-size, --exposure, --frame;
// help shows `defaults` (the command's own) where neither a shot nor a flag decides.
void addSceneOptions(CLI::App& cmd, RenderOptions& options, const RenderSettings& defaults);

// The "Screen-space tracing" group: --no-ssr, --no-ssgi, --ssr-method, --marcher, --ssr-spp,
// --ssgi-spp, --max-steps, --thickness, --ssr-resolve, --hit-radiance.
void addTraceOptions(CLI::App& cmd, RenderOptions& options);
void traceSettingsFrom(const RenderOptions& options, TraceSettings& trace);

// A request checked (flags, shot file, scene name, ISA) but not yet loaded.
struct SceneRequest {
    std::optional<Shot> shot;
    RenderSettings settings;
    std::string name;         // built-in scene or glTF file
    uint32_t firstFrame = 0;  // FrameInput::frameIndex of the first frame (--frame, the shot)
    Isa isa = Isa::Scalar;
    Scene scene;      // after loadScene
    CameraPath path;  // the shot's camera path (empty: the scene's still camera)
};
// Parses and checks everything; throws std::invalid_argument for bad flags, runtime errors
// for a bad shot file. `defaults` are the command's own defaults under the shot and flags.
SceneRequest loadSceneRequest(const RenderOptions& options, const RenderSettings& defaults = {});
// Loads the scene (glTF, shot's light, sky image, camera path); throws on a bad file.
void loadScene(SceneRequest& request);
// The input of a single-frame command (compare, sweep): the first frame index, the path's
// first key or the scene's camera; previous = the scene's previous camera without a path,
// else the camera itself.
FrameInput requestInput(const SceneRequest& request);

}  // namespace ssrt::cli
