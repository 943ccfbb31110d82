// What the commands that render share: numbers and names from text with one-line errors
// naming the option, the screen-space tracing options, and the scene a request names
// (built-in, glTF or shot file) loaded the same way for `render`, `compare` and `sweep`.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "cli/render_command.h"
#include "cli/shot_settings.h"
#include "core/fields.h"
#include "core/isa.h"
#include "io/write_options.h"
#include "renderer/layer_groups.h"
#include "renderer/renderer.h"
#include "scenes/camera_path.h"
#include "scenes/scene.h"
#include "scenes/scene_names.h"
#include "scenes/shot.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

inline constexpr long long kMaxFrame = 4294967295ll;  // RenderSettings::frame is 32 bits

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

// The settings' field table (renderer/settings_fields.h) on the command line. A field's
// option is its key in kebab case (shadowMapSize: --shadow-map-size) unless the table gives
// one; a bool's flag turns it away from its default (ssr: --no-ssr, traceHidden:
// --trace-hidden). fieldOption is the long option, as messages name it.
std::string fieldOption(const FieldInfo& field);
// The table's field with this key (std::logic_error if none: a programming error).
const Field<RenderSettings>& renderField(std::string_view key);
// The value `text` gives `field`, checked against its range; errors name `option`.
double parseFieldText(const FieldInfo& field, const std::string& option, const std::string& text);
// "a,b,c" -> {a, b, c}; an empty item is an error naming the option.
std::vector<std::string> splitList(const std::string& option, const std::string& text);

std::string defaultSceneName();
void checkSceneName(const std::string& name);
// The ISA the renderer will run, resolved now so a CPU without it fails before any work.
Isa resolveIsaFor(std::optional<Isa> requested);
int threadsFor(const RenderSettings& settings);  // 0 -> every core
std::string plural(int n, const std::string& noun);

// --shot, --scene, one option per RenderSettings field of the table (--width, --height,
// --threads, --shadow-map-size, --shadow-bias, ...), --isa, --frame, --strict; help shows
// `defaults` (the command's own) where neither a shot nor a flag decides.
void addSceneOptions(CLI::App& cmd, RenderOptions& options, const RenderSettings& defaults);

// The "Screen-space tracing" group: one option per TraceSettings field of the table
// (--no-ssr, --no-ssgi, --ssr-method, --marcher, --ssr-spp, --ssgi-spp, --trace-hidden,
// --max-steps, --thickness, ..., --ssr-resolve, --hit-radiance, ...).
void addTraceOptions(CLI::App& cmd, RenderOptions& options);

// --layers and --exr-compression (EXR output only).
void addImageOutputOptions(CLI::App& cmd, RenderOptions& options);
// How a frame goes into an image file: the layer groups an EXR keeps (--layers) and how the
// file is written (--exr-compression, threads).
struct FrameWriteOptions {
    LayerGroups layers = allLayerGroups();  // EXR only: a PNG is always the display planes
    WriteOptions file;
};
// How `output` is written: the layer groups and compression given (checked: an unknown name
// throws std::invalid_argument naming the option), compressed on the render's threads. A PNG
// output with either option given warns on `err` that it is ignored.
FrameWriteOptions writeOptionsFrom(const RenderOptions& options, const RenderSettings& settings,
                                   const std::string& output, std::ostream& err);
// Writes `frame` to `path` (io/image_io.h writeImage): an EXR holds the layers of the groups
// options.layers names, in the frame's order; a PNG the display planes. Throws as writeImage
// does (an EXR whose chosen groups hold no plane is refused: std::invalid_argument).
void writeFrame(const std::string& path, const Frame& frame, const FrameWriteOptions& options);

// A CSV file to write later: the name must end in .csv (std::invalid_argument naming
// `option`), its folder must exist and it must not be a folder (std::runtime_error).
void checkCsvPath(const std::string& option, const std::string& path);
// The same for another kind of text file, named by its extension (".json").
void checkTextPath(const std::string& option, const std::string& path,
                   const std::string& extension);
// Writes `text` whole or not at all: a temporary beside the target, renamed over it.
void writeTextFile(const std::string& path, const std::string& text);

// A request checked (flags, shot file, scene name, ISA) but not yet loaded.
struct SceneRequest {
    std::optional<Shot> shot;
    RenderSettings settings;
    std::string name;         // built-in scene or glTF file
    uint32_t firstFrame = 0;  // FrameInput::frameIndex of the first frame (--frame, the shot)
    Isa isa = Isa::Scalar;
    bool strict = false;  // --strict
    Scene scene;          // after loadScene
    CameraPath path;      // the shot's camera path (empty: the scene's still camera)
};
// Parses and checks everything; throws std::invalid_argument for bad flags, runtime errors
// for a bad shot file. `defaults` are the command's own defaults under the shot and flags.
SceneRequest loadSceneRequest(const RenderOptions& options, const RenderSettings& defaults = {});
// Loads the scene (glTF, shot's light, sky image, camera path); throws on a bad file. A glTF
// file's warnings go to `err`, one "ssrt: warning: " line each, even under --quiet (they are
// not progress); with --strict the first is an error instead.
void loadScene(SceneRequest& request, std::ostream& err);

}  // namespace ssrt::cli
