// `ssrt sweep`: a grid of screen-space settings (marchers, step counts, SSR samplers, rays
// per pixel, thickness, resolve modes, SSR's tracing mode) on one scene, each measured on both axes
// as `ssrt compare` does, one CSV row per setting: time per pass, every ray-check share, the
// hit-error quantiles, the image errors, and the march's rate against Embree's on the same
// rays. perf/plot.py turns the CSV into the error-against-time chart. With --frames or
// --warmup-frames each setting renders a sequence (cli/sequence.h) and its row is the last
// frame's, with the sequence's length and that frame's flicker (cli/sequence_evaluation.h).
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "cli/compare_command.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

struct SweepOptions {
    RenderOptions render;  // scene options only (the grid replaces the tracing options)
    TruthOptions truth;
    std::string marchers = "off,linear,dda,hiz";
    std::string maxSteps, ssrMethods, ssrSpp, ssgiSpp, thickness, backFaces, feedback, resolves,
        ssrTraces, ssgiTraces;  // defaults: TraceSettings{}
    std::string presets;        // quality presets as points: "low,medium,..." (none by default)
    std::string embreeSpp;      // the Embree method's rays per pixel: "1,4,16" (none by default)
    std::string output = "sweep.csv";
    bool traceHidden = false;          // every setting: TraceSettings::traceHidden
    std::optional<std::string> shard;  // --shard K/N (cli/shard.h)
    SweepOptions();
};

// The CSV's columns, in order (the header line).
const std::vector<std::string>& sweepColumns();

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options);
int runSweep(const SweepOptions& options, std::ostream& out, std::ostream& err);

}  // namespace ssrt::cli
