// The ssrt command line parsed but not run: every command's options bound to one CLI11 app.
// runCli (cli/cli.h) parses with it and then runs the chosen command; the command-line fuzzer
// (tests/fuzz/cli_fuzz.cpp) parses with it and then only checks what the command would check
// before its work, so that parsing and checking are fuzzed without rendering anything.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "cli/check_command.h"
#include "cli/compare_command.h"
#include "cli/diff_command.h"
#include "cli/graph_command.h"
#include "cli/merge_command.h"
#include "cli/reference_command.h"
#include "cli/render_command.h"
#include "cli/scenes_command.h"
#include "cli/sweep_command.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

enum class Command {
    Render,
    Compare,
    Sweep,
    Diff,
    Check,
    Reference,
    Merge,
    Graph,
    Scenes,
    Completion,
    Man
};
inline constexpr int kCommandCount = int(Command::Man) + 1;
// Their names on the command line, by Command.
inline constexpr std::string_view kCommandNames[kCommandCount] = {
    "render", "compare", "sweep",  "diff",       "check", "reference",
    "merge",  "graph",   "scenes", "completion", "man"};

class CommandLine {
public:
    // Every command's options; or, where `only` names a command (the first argument: runCli
    // passes it), that command's alone, which is all its parse needs: a one-frame render no
    // longer builds the hundreds of options of the commands it is not. The completion script
    // and the man page walk every command, so for them, as for any other text, all are built.
    explicit CommandLine(std::string_view only = {});
    ~CommandLine();

    // Parses argv (argv[0] is the program). Returns the exit status when parsing alone ends
    // the run (--help: 0, its text on `out`; a usage error: kExitUsage, one line on `err`),
    // else nothing: command() and the options below hold what was asked.
    std::optional<int> parse(int argc, const char* const* argv, std::ostream& out,
                             std::ostream& err);
    Command command() const { return command_; }
    // Back to the state before parse(), without building the app again (its hundreds of
    // options cost milliseconds): what parses many command lines in one process, the fuzzer.
    void reset();

    RenderOptions render;
    CompareOptions compare;
    SweepOptions sweep;
    DiffOptions diff;
    CheckOptions check;
    ReferenceOptions reference;
    MergeOptions merge;
    GraphOptions graph;
    ScenesOptions scenes;
    std::string completionShell;  // `ssrt completion SHELL`

    // The app itself: what the completion script and the man page are made from.
    const CLI::App& app() const { return *app_; }

private:
    CLI::App* addCommand(Command c);

    std::unique_ptr<CLI::App> app_;
    CLI::App* commands_[kCommandCount] = {};  // by Command
    Command command_ = Command::Scenes;
};

}  // namespace ssrt::cli
