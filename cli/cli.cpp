#include "cli/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <exception>
#include <iterator>
#include <memory>
#include <new>
#include <ostream>
#include <stdexcept>

#include "cli/bash_completion.h"
#include "cli/build_info.h"
#include "cli/command_line.h"
#include "cli/interrupt.h"
#include "cli/man_page.h"
#include "cli/memory_check.h"
#include "cli/scenes_command.h"
#include "core/suggest.h"

namespace ssrt::cli {

namespace {

// The commands, as the errors for a missing or mistyped one list them.
constexpr const char* kCommandList =
    "render, graph, compare, sweep, diff, check, reference, merge, scenes, completion or man";

// The exit statuses, as the help's footer and the man page's EXIT STATUS give them.
constexpr const char* kExitStatusText =
    "Exit status: 0 success (diff, render --compare, check: within every threshold and "
    "rule), 1 the images differ beyond a threshold (diff, render --compare, and check: a "
    "case failed, is stale or has no reference), 2 bad command line, 3 the work failed (a "
    "bad shot, scene, suite or image file, file I/O, an ISA this CPU lacks, rendering, "
    "images of different sizes).";

// The first argument the parse left that looks like an option ("--widht"; its "=value" cut
// off), or empty.
std::string unknownOption(const CLI::App& app) {
    for (const std::string& arg : app.remaining(true))
        if (arg.size() > 1 && arg[0] == '-' && !std::isdigit(static_cast<unsigned char>(arg[1])))
            return arg.substr(0, arg.find('='));
    return {};
}

// Every spelling of `app`'s options ("--width", "-W", ...).
std::vector<std::string> optionNames(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::Option* o : app.get_options()) {
        for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
        for (const std::string& n : o->get_snames()) names.push_back("-" + n);
    }
    return names;
}

}  // namespace

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

int reportErrors(std::ostream& err, const std::function<int()>& command) {
    try {
        return command();
    } catch (const Interrupted& e) {
        err << "ssrt: " << e.what() << "\n";
        return e.status();
    } catch (const std::invalid_argument& e) {
        err << "ssrt: error: " << oneLine(e.what()) << "\n";
        return kExitUsage;
    } catch (const std::bad_alloc&) {  // past the checks made before the work: still one line
        err << "ssrt: error: " << outOfMemoryMessage() << "\n";
        return kExitFailure;
    } catch (const std::exception& e) {
        err << "ssrt: error: " << oneLine(e.what()) << "\n";
        return kExitFailure;
    }
}

CommandLine::CommandLine(std::string_view only)
    : app_(std::make_unique<CLI::App>(
          "ssrt: a deterministic CPU renderer (tiled SIMD rasterizer, G-buffer, shadow map, "
          "direct light, screen-space reflections and diffuse, checked against Embree)",
          "ssrt")) {
    CLI::App& app = *app_;
    app.footer(std::string(kExitStatusText) +
               "\nRun 'ssrt COMMAND --help' for a command's options.");
    app.set_version_flag("--version", versionLine(), "Print the version, commit and compiler");
    app.require_subcommand(1);
    // The completion script and the man page walk every command, so they never come alone.
    int alone = -1;
    for (int c = 0; c < kCommandCount; ++c)
        if (only == kCommandNames[c] && Command(c) != Command::Completion &&
            Command(c) != Command::Man)
            alone = c;
    for (int c = 0; c < kCommandCount; ++c) {
        if (alone >= 0 && c != alone) continue;
        commands_[c] = addCommand(Command(c));
        if (commands_[c]->get_name() != kCommandNames[c])
            throw std::logic_error("cli: command " + std::to_string(c) + " is named '" +
                                   commands_[c]->get_name() + "', not '" +
                                   std::string(kCommandNames[c]) + "'");
    }
}

CLI::App* CommandLine::addCommand(Command c) {
    CLI::App& app = *app_;
    switch (c) {
        case Command::Render: return addRenderCommand(app, render);
        case Command::Compare: return addCompareCommand(app, compare);
        case Command::Sweep: return addSweepCommand(app, sweep);
        case Command::Diff: return addDiffCommand(app, diff);
        case Command::Check: return addCheckCommand(app, check);
        case Command::Reference: return addReferenceCommand(app, reference);
        case Command::Merge: return addMergeCommand(app, merge);
        case Command::Graph: return addGraphCommand(app, graph);
        case Command::Scenes: return addScenesCommand(app, scenes);
        case Command::Completion: return addCompletionCommand(app, completionShell);
        case Command::Man: return addManCommand(app);
    }
    throw std::logic_error("cli: no such command");
}

CommandLine::~CommandLine() = default;

void CommandLine::reset() {
    // The options are bound to these members by reference and written only when given, so
    // fresh values and a cleared app are the state parse() starts from.
    app_->clear();
    render = {};
    compare = {};
    sweep = {};
    diff = {};
    check = {};
    reference = {};
    merge = {};
    graph = {};
    scenes = {};
    completionShell.clear();
    command_ = Command::Scenes;
}

std::optional<int> CommandLine::parse(int argc, const char* const* argv, std::ostream& out,
                                      std::ostream& err) {
    if (argc <= 1) {
        err << "ssrt: error: no command given (" << kCommandList << "; see 'ssrt --help')\n";
        return kExitUsage;
    }
    try {
        app_->parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help arrives as a "parse error" whose exit code is success.
        if (e.get_exit_code() == 0) return app_->exit(e, out, err);
        // CLI11 reports a mistyped command as "a subcommand is required"; name it instead.
        const std::string first = argv[1];
        const CLI::App* command = nullptr;
        for (const CLI::App* c : commands_)
            if (c && c->parsed()) command = c;
        const std::vector<std::string> names(std::begin(kCommandNames), std::end(kCommandNames));
        if (!command && first.rfind('-', 0) != 0) {
            err << "ssrt: error: unknown command '" << first << "'" << didYouMean(first, names)
                << " (expected " << kCommandList << "; see 'ssrt --help')\n";
            return kExitUsage;
        }
        const std::string help =
            command ? "'ssrt " + command->get_name() + " --help'" : std::string("'ssrt --help'");
        // An option the command does not have: named, with the nearest one it has.
        if (const std::string unknown = unknownOption(*app_); !unknown.empty()) {
            err << "ssrt: error: unknown option '" << unknown << "'"
                << (command ? " for 'ssrt " + command->get_name() + "'" : std::string())
                << didYouMean(unknown, optionNames(command ? *command : *app_)) << " (see " << help
                << ")\n";
            return kExitUsage;
        }
        err << "ssrt: error: " << oneLine(e.what()) << " (see " << help << ")\n";
        return kExitUsage;
    }
    // require_subcommand(1) holds: exactly one command was parsed.
    for (int c = 0; c < kCommandCount; ++c)
        if (commands_[c] && commands_[c]->parsed()) command_ = Command(c);
    return std::nullopt;
}

int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    CommandLine line(argc > 1 ? argv[1] : "");
    return runCli(line, argc, argv, out, err);
}

int runCli(CommandLine& line, int argc, const char* const* argv, std::ostream& out,
           std::ostream& err) {
    if (const std::optional<int> status = line.parse(argc, argv, out, err)) return *status;
    switch (line.command()) {
        case Command::Render:
            return reportErrors(err, [&] { return runRender(line.render, out, err); });
        case Command::Compare:
            return reportErrors(err, [&] { return runCompare(line.compare, out, err); });
        case Command::Sweep:
            return reportErrors(err, [&] { return runSweep(line.sweep, out, err); });
        case Command::Diff: return reportErrors(err, [&] { return runDiff(line.diff, out); });
        case Command::Check: return reportErrors(err, [&] { return runCheck(line.check, out); });
        case Command::Reference:
            return reportErrors(err, [&] { return runReference(line.reference, out, err); });
        case Command::Merge:
            return reportErrors(err, [&] { return runMerge(line.merge, out, err); });
        case Command::Graph:
            return reportErrors(err, [&] { return runGraph(line.graph, out, err); });
        case Command::Scenes: return reportErrors(err, [&] { return runScenes(line.scenes, out); });
        case Command::Completion:  // its one shell, checked by the parse
            writeBashCompletion(line.app(), out);
            return kExitOk;
        case Command::Man: {
            const std::string version = versionLine();
            writeManPage(line.app(), kExitStatusText, version.substr(0, version.find(" (")), out);
            return kExitOk;
        }
    }
    return kExitUsage;  // unreachable: every command is a case
}

}  // namespace ssrt::cli
