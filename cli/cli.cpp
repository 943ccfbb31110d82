#include "cli/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <ostream>
#include <stdexcept>

#include "cli/build_info.h"
#include "cli/check_command.h"
#include "cli/compare_command.h"
#include "cli/diff_command.h"
#include "cli/merge_command.h"
#include "cli/reference_command.h"
#include "cli/render_command.h"
#include "cli/scenes_command.h"
#include "cli/sweep_command.h"

namespace ssrt::cli {

namespace {

// The commands, as the errors for a missing or mistyped one list them.
constexpr const char* kCommandList =
    "render, compare, sweep, diff, check, reference, merge or scenes";

}  // namespace

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

int reportErrors(std::ostream& err, const std::function<int()>& command) {
    try {
        return command();
    } catch (const std::invalid_argument& e) {
        err << "ssrt: error: " << oneLine(e.what()) << "\n";
        return kExitUsage;
    } catch (const std::exception& e) {
        err << "ssrt: error: " << oneLine(e.what()) << "\n";
        return kExitFailure;
    }
}

int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    CLI::App app{
        "ssrt: a deterministic CPU renderer (tiled SIMD rasterizer, G-buffer, shadow map, "
        "direct light, screen-space reflections and diffuse, checked against Embree)",
        "ssrt"};
    app.footer(
        "Exit status: 0 success (diff, render --compare, check: within every threshold and "
        "rule), 1 the images differ beyond a threshold (diff, render --compare, and check: a "
        "case failed, is stale or has no reference), 2 bad command line, 3 the work failed (a "
        "bad shot, scene, suite or image file, file I/O, an ISA this CPU lacks, rendering, "
        "images of different sizes).\nRun 'ssrt COMMAND --help' for "
        "a command's options.");
    app.set_version_flag("--version", versionLine(), "Print the version, commit and compiler");
    app.require_subcommand(1);
    RenderOptions renderOptions;
    CLI::App* render = addRenderCommand(app, renderOptions);
    CompareOptions compareOptions;
    CLI::App* compare = addCompareCommand(app, compareOptions);
    SweepOptions sweepOptions;
    CLI::App* sweep = addSweepCommand(app, sweepOptions);
    DiffOptions diffOptions;
    CLI::App* diff = addDiffCommand(app, diffOptions);
    CheckOptions checkOptions;
    CLI::App* check = addCheckCommand(app, checkOptions);
    ReferenceOptions referenceOptions;
    CLI::App* reference = addReferenceCommand(app, referenceOptions);
    MergeOptions mergeOptions;
    CLI::App* merge = addMergeCommand(app, mergeOptions);
    CLI::App* scenes = addScenesCommand(app);
    if (argc <= 1) {
        err << "ssrt: error: no command given (" << kCommandList << "; see 'ssrt --help')\n";
        return kExitUsage;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help arrives as a "parse error" whose exit code is success.
        if (e.get_exit_code() == 0) return app.exit(e, out, err);
        // CLI11 reports a mistyped command as "a subcommand is required"; name it instead.
        const std::string first = argv[1];
        const bool anyParsed = render->parsed() || compare->parsed() || sweep->parsed() ||
                               diff->parsed() || check->parsed() || reference->parsed() ||
                               merge->parsed() || scenes->parsed();
        if (!anyParsed && first.rfind('-', 0) != 0) {
            err << "ssrt: error: unknown command '" << first << "' (expected " << kCommandList
                << "; see 'ssrt --help')\n";
            return kExitUsage;
        }
        err << "ssrt: error: " << oneLine(e.what()) << " (see 'ssrt --help')\n";
        return kExitUsage;
    }
    if (render->parsed())
        return reportErrors(err, [&] { return runRender(renderOptions, out, err); });
    if (compare->parsed())
        return reportErrors(err, [&] { return runCompare(compareOptions, out, err); });
    if (sweep->parsed()) return reportErrors(err, [&] { return runSweep(sweepOptions, out, err); });
    if (diff->parsed()) return reportErrors(err, [&] { return runDiff(diffOptions, out); });
    if (check->parsed()) return reportErrors(err, [&] { return runCheck(checkOptions, out); });
    if (reference->parsed())
        return reportErrors(err, [&] { return runReference(referenceOptions, out, err); });
    if (merge->parsed()) return reportErrors(err, [&] { return runMerge(mergeOptions, out, err); });
    if (scenes->parsed()) return reportErrors(err, [&] { return runScenes(out); });
    return kExitUsage;  // unreachable: require_subcommand(1) holds
}

}  // namespace ssrt::cli
