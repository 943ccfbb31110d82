// `ssrt diff A B`: an image against a reference (a golden image), layer by layer, with
// thresholds; its table and exit status are also `ssrt render --compare FILE`'s. With --flip
// it also prints FLIP, a perceptual difference of the two images' colour (io/flip.h).
#pragma once

#include <iosfwd>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/flip.h"
#include "io/image_compare.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace ssrt::cli {

// The thresholds and heat map as typed (checked by diffSettingsFrom).
struct DiffFlags {
    std::string threshold = "0";  // per-channel difference above which a pixel differs
    std::optional<std::string> maxError, maxRelMse;  // unset: not checked
    std::string maxShare = "0";                      // share of pixels over --threshold allowed
    std::optional<std::string> heatmap;              // a .png to write
    std::optional<std::string> heatmapLayer;         // the layer it shows (default: colour)
    std::optional<std::string> heatmapScale;         // the difference drawn white
};

struct DiffOptions {
    std::string a, b;  // b is the reference
    DiffFlags flags;
    std::optional<std::string> layers;       // comma-separated layer names
    bool flip = false;                       // print FLIP (--flip, or implied by --flip-heatmap)
    std::optional<std::string> flipHeatmap;  // a .png of FLIP's error on the magma map
    std::optional<std::string> maxFlipMean;  // FLIP's mean above it differs (implies --flip)
    bool json = false;                       // --json: the report as JSON (cli/json_output.h)
};

// What the flags mean, checked.
struct DiffSettings {
    ImageCompareOptions compare;
    DiffThresholds limits;
};

// Adds --threshold, --max-error, --max-relmse, --max-share, --heatmap, --heatmap-layer and
// --heatmap-scale to `cmd` in the group `group`, and returns them (render makes them need
// --compare).
std::vector<CLI::Option*> addDiffFlags(CLI::App& cmd, DiffFlags& flags, const std::string& group);

// Parses the flags: numbers finite and >= 0, --max-share in [0, 1], the heat map a .png
// (std::invalid_argument naming the option) in a writable folder (std::runtime_error).
DiffSettings diffSettingsFrom(const DiffFlags& flags);

// Whether two paths name the same file (or would, once written): their absolute, normal
// forms with symbolic links resolved as far as they exist.
bool samePath(const std::string& a, const std::string& b);

// Throws std::invalid_argument (naming --heatmap) when the heat map `heatmap` (empty: none)
// is one of `images`: writing it would replace an image being compared.
void checkHeatmapApart(const std::string& heatmap, const std::vector<std::string>& images);

// A difference as the tables print it: 4 significant digits, "inf" for +inf.
std::string number(double v);
// Channel names as the tables print them: "R,G,B" for color.R, color.G, color.B.
std::string channelList(const std::vector<std::string>& channels);

// Registers the `diff` subcommand on `app`, bound to `options`, and returns it.
CLI::App* addDiffCommand(CLI::App& app, DiffOptions& options);

// Compares `a` against the reference `b`, prints the table, FLIP's line (when `flip` is given:
// its mean, weighted median and maximum) and a summary line to `out` and returns kExitOk (every
// layer within the thresholds, and FLIP's mean at most `maxFlipMean` when that is given) or
// kExitDiffer; throws on errors. FLIP without `maxFlipMean` sets no exit status: it is a
// report until someone states the limit. With `json`, the same report goes there as a JSON
// object (docs/golden.md gives its keys) and nothing to `out`.
int diffImages(const std::string& a, const std::string& b, const DiffSettings& settings,
               std::ostream& out, const FlipFileOptions* flip = nullptr,
               std::optional<double> maxFlipMean = {}, nlohmann::ordered_json* json = nullptr);

// `ssrt diff`: diffSettingsFrom, then diffImages.
int runDiff(const DiffOptions& options, std::ostream& out);

}  // namespace ssrt::cli
