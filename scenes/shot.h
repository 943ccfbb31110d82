// A shot file: a small JSON document naming a scene and, optionally, the camera (and a
// camera path for sequences), the light, the environment and render settings. Every field is
// optional: what a shot leaves out stays as the scene (or RenderSettings{}) has it, and the
// command line's flags override the shot.
//
// Lives beside the scene model in its own library (ssrt_shot, with nlohmann-json), so the core
// library does not depend on a JSON parser. The environment image is named here but loaded by
// the caller (io/image_io.h readSkyImage): the shot library reads no images.
//
// Schema (README.md, "Shot files", shows an example):
//   scene        string: a built-in scene name, or a .gltf/.glb path (relative to the shot
//                file's folder)
//   camera       object: position, target, up [3 numbers]; fovY (0, 180) degrees; near > 0;
//                far > near; path: { interpolation: "catmull-rom" (default) or "linear",
//                keys: [ { time, position, target, fovY, cut }, ... ] }
//                (scenes/camera_path.h; a key's time defaults to its index, its position,
//                target and fovY to the camera's; cut: true/false, default false, the camera
//                jumps to this key and history restarts there; not on the first key)
//   light        object: direction [3 numbers, not all 0] (the way the light travels),
//                color [3 numbers >= 0], intensity >= 0
//   environment  object: type "constant" (color), "gradient" (zenith, horizon, ground) or
//                "image" (file: .exr, .hdr or any image OpenImageIO reads, relative to the
//                shot file's folder; required), intensity >= 0. Without a type only the
//                intensity may be given (it scales the scene's own sky).
//   render       object: frames (1 to 100000), frame (the first frame's index, 0 to
//                4294967295), warmupFrames (0 to 100000: frames rendered before the first
//                written one and not written), and every render and tracing setting by its
//                field-table key
//                (renderer/settings_fields.h; README.md, "Shot files", lists them): width,
//                height, shadowMapSize, shadowBias, shadowSlopeBias, pcfRadius, exposure,
//                idPlanes, gbufferPlanes, tracePlanes, debugPlanes, ssr, ssgi, ssrMethod,
//                marcher, ssrSpp, ssgiSpp, traceHidden, maxSteps, maxDistance, linearStep,
//                thickness, ddaStride, ddaJitter, refineSteps, hizMostDetailedLevel, hizStartLevel,
//                ssrResolve, hitRadiance, hitBilinear, edgeFadeLength, roughnessFadeStart,
//                roughnessFadeEnd. Booleans are true/false, choices are names ("marcher":
//                "dda"). The parser keeps these settings as written; applying them
//                (cli/shot_settings.h) checks each against its table entry, unknown keys
//                included.
// Numbers must be finite (1e999 is not), integers must be written as integers, and any key
// not listed is an error (typos do not pass silently), as are duplicate keys.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scenes/camera_path.h"
#include "scenes/scene.h"

namespace ssrt {

// A shot file that cannot be used. what() is one line: "<file>: <json path>: <problem>",
// e.g. "shot.json: camera.fovY: expected a number in (0, 180)".
class ShotError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline constexpr int kMaxShotFrames = 100000;

struct ShotKey {
    std::optional<double> time;  // default: the key's index
    std::optional<glm::vec3> position, target;
    std::optional<float> fovY;
    bool cut = false;  // CameraKey::cut
};

// A value of the render object as the JSON wrote it.
struct ShotValue {
    enum class Kind { Bool, Integer, Number, String, Other } kind = Kind::Other;
    double number = 0.0;  // Bool (0 or 1), Integer (as written), Number (finite)
    std::string text;     // String
};

struct Shot {
    std::string file;                  // the shot file, as named
    std::optional<std::string> scene;  // a built-in name, or a file path already resolved

    struct CameraFields {
        std::optional<glm::vec3> position, target, up;
        std::optional<float> fovY, nearZ, farZ;
    } camera;
    PathInterpolation interpolation = PathInterpolation::CatmullRom;
    std::vector<ShotKey> path;  // empty: no path

    struct LightFields {
        std::optional<glm::vec3> direction, color;
        std::optional<float> intensity;
    } light;

    struct EnvironmentFields {
        std::optional<Sky::Kind> kind;
        std::optional<glm::vec3> color;                    // constant
        std::optional<glm::vec3> zenith, horizon, ground;  // gradient
        std::optional<std::string> file;                   // image, resolved against the shot
        std::optional<float> intensity;
    } environment;

    struct RenderFields {
        std::optional<int> frames;
        std::optional<uint32_t> frame;
        std::optional<int> warmupFrames;  // frames rendered and not written before frame 0
        // Every other key of the render object, in key order: a setting for the caller to
        // look up in its field table (cli/shot_settings.h), as pbrt-v4's ParameterDictionary
        // holds parameters for the plugin that reads them.
        std::vector<std::pair<std::string, ShotValue>> settings;
    } render;
};

// Reads and validates a shot file; throws ShotError (one line) for anything wrong, files it
// names that do not exist included (the render settings are checked when applied).
Shot loadShot(const std::string& path);

// The same from text; `file` names it in messages and its folder resolves relative paths.
Shot parseShot(const std::string& text, const std::string& file);

// Applies the shot's camera, light and environment to a scene (the environment's image is
// the caller's to load and set on scene.sky.image), and makes previousCamera the camera (a
// still frame). Throws ShotError if the camera that results cannot look anywhere (position
// equal to target, up along the view direction).
void applyShot(const Shot& shot, Scene& scene);

// The shot's camera path, its keys' missing fields taken from `camera` (the scene's camera
// after applyShot). Empty if the shot has none. Throws ShotError naming the key if a key ends
// up with its position on its target.
CameraPath shotCameraPath(const Shot& shot, const Camera& camera);

}  // namespace ssrt
