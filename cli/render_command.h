// `ssrt render`: a frame, or a sequence along a shot's camera path, of a built-in scene or a
// glTF file, to PNG previews or multi-layer EXRs.
#pragma once

#include <iosfwd>
#include <map>
#include <optional>
#include <string>

#include "cli/diff_command.h"
#include "renderer/layer_groups.h"
#include "renderer/renderer.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

// The options as typed. Numbers stay text until settingsFrom() so that every bad value
// (NaN, "12px", 1e99, -3) gets the same one-line message naming the option. Options a shot
// file can also give are optional: unset means "not on the command line", so the shot (or
// else the default) decides; a flag that is given overrides the shot.
struct RenderOptions {
    std::optional<std::string> shot;   // a shot file (scenes/shot.h)
    std::optional<std::string> scene;  // a built-in scene or a .gltf/.glb file
    std::optional<std::string> frame, frames, warmupFrames;
    std::optional<std::string> quality;  // a preset (renderer/quality.h), applied before the fields
    // The settings' fields given (renderer/settings_fields.h): key -> the value as typed; a
    // bool's flag stores "true" or "false". A key not here is not on the command line.
    std::map<std::string, std::string, std::less<>> settings;
    std::string isa;
    std::string output;        // -o as given; renderOutput() says what a render writes
    bool outputGiven = false;  // -o on the command line (else --compare picks the format)
    // --compare FILE: the written frame against this reference, with these thresholds.
    std::optional<std::string> compare;
    DiffFlags diff;
    // --layers and --exr-compression as typed (unset: every layer, the default compression).
    std::optional<std::string> layers, exrCompression;
    bool stats = false;
    std::optional<std::string> profile;  // --profile FILE: a trace-event file (cli/profile_file.h)
    bool json = false;  // --json: the command's report (render: --stats, --compare) as JSON
    bool quiet = false;
    bool strict = false;               // --strict: a glTF file's warnings are errors
    std::optional<std::string> shard;  // render's --shard K/N (cli/shard.h): a block of frames

    RenderOptions();  // isa defaults to RenderSettings{}'s
};

// Registers the `render` subcommand on `app`, bound to `options`, and returns it.
CLI::App* addRenderCommand(CLI::App& app, RenderOptions& options);

// Parses and range-checks the numbers given, over `base` (the defaults, or a shot's
// settings), then RenderSettings::validate(). Throws std::invalid_argument naming the option
// and the value.
RenderSettings settingsFrom(const RenderOptions& options, const RenderSettings& base = {});

// The file frame `index` of a `count`-frame sequence goes to: `output` itself for a single
// frame, else the stem, an underscore, the index zero-padded to 4 digits (more if count - 1
// needs them), and the extension: out.png -> out_0000.png, out_0001.png, ...
std::string sequenceFileName(const std::string& output, int index, int count);

// The file a render writes: --output as given; without -o, named after the shot file or the
// scene ("cornell.png"; a glTF file's name without its folder), with the --compare
// reference's extension where that is .exr, so that the two files hold the same kind of layers.
std::string renderOutput(const RenderOptions& options);

// The id planes and the debug planes exist to be looked at: a file that shows none of them (a
// PNG, or an EXR whose layer groups leave out theirs) does not make them.
void planesForFile(const std::string& output, const LayerGroups& layers, RenderSettings& settings);

// Validates everything (flags, the shot file, the output path) before any work, then renders
// the warm-up frames and each frame of the sequence (cli/sequence.h) into one reused Frame
// and one history, and writes each frame of the sequence (whole, through a temporary and a
// rename) before the next; progress to `err` unless quiet (one line per frame, warm-up frames
// included, when there is more than one), the --stats table of each written frame to `out`.
// With --compare (a single frame only: more is a usage error; the reference must be readable
// before rendering starts) the written file is then compared as `ssrt diff` does, its table
// to `out`. Returns the exit status (kExitDiffer beyond a threshold); throws on errors (see
// reportErrors).
int runRender(const RenderOptions& options, std::ostream& out, std::ostream& err);

// The --stats table: ISA, threads, per-pass milliseconds, raster counters per pass, and for
// the screen-space passes rays, misses by cause, steps per ray, SIMD lane utilisation and the
// march's speed (rays per second and nanoseconds per step, over its stage's time); last the
// memory the frame holds by resource group, per pixel of the frame's `pixels`. `wallMs` is the
// whole render call as the CLI timed it, `writeMs` the image file's write (encoding,
// compression and the rename), after it.
void printStats(std::ostream& out, const FrameStats& stats, double pixels, double wallMs,
                double writeMs);

}  // namespace ssrt::cli
