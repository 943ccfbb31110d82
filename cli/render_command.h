// `ssrt render`: one frame of a built-in scene to a PNG preview or a multi-layer EXR.
#pragma once

#include <iosfwd>
#include <string>

#include "renderer/renderer.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

// The options as typed. Numbers stay text until settingsFrom() so that every bad value
// (NaN, "12px", 1e99, -3) gets the same one-line message naming the option.
struct RenderOptions {
    std::string scene;  // a built-in scene; defaults to the first ("cornell")
    std::string width, height, threads, isa, shadowMapSize, exposure, frame;
    std::string output = "ssrt.png";
    bool stats = false;
    bool quiet = false;

    RenderOptions();  // numbers default to RenderSettings{}'s, so help shows the truth
};

// Registers the `render` subcommand on `app`, bound to `options`, and returns it.
CLI::App* addRenderCommand(CLI::App& app, RenderOptions& options);

// Parses and range-checks the numbers, then RenderSettings::validate(). Throws
// std::invalid_argument naming the option and the value.
RenderSettings settingsFrom(const RenderOptions& options);

// Validates everything, renders, writes the file; progress to `err` unless quiet, the
// --stats table to `out`. Returns the exit status; throws on errors (see reportErrors).
int runRender(const RenderOptions& options, std::ostream& out, std::ostream& err);

// The --stats table: ISA, threads, per-pass milliseconds, raster counters per pass.
// `wallMs` is the whole render call as the CLI timed it.
void printStats(std::ostream& out, const FrameStats& stats, double wallMs);

}  // namespace ssrt::cli
