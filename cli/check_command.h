// `ssrt check SUITE.json`: a golden-image suite (cli/suite_file.h) run as render tests run
// one. Each case renders in its own `ssrt render` process (the cases side by side, --jobs at a
// time), is compared with its reference and judged by its rules (cli/check_case.h); one line
// per case in the suite's order, whatever finished first, then a summary, an HTML report and a
// JUnit file. --update rewrites the references of the failing and new cases, and only those.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace ssrt::cli {

struct CheckOptions {
    std::string suite;
    std::string out = "ssrt-check";      // the folder of the reports and each case's files
    std::string jobs = "0";              // cases at a time (0: one per core)
    std::optional<std::string> program;  // --ssrt: the ssrt that renders (default: this one)
    bool update = false;
    bool json = false;  // --json: the run as one JSON document instead of the lines
};

// Registers the `check` subcommand on `app`, bound to `options`, and returns it.
CLI::App* addCheckCommand(CLI::App& app, CheckOptions& options);

// Runs the suite. Returns kExitOk when every case passes (or was updated), kExitDiffer when a
// case fails, is stale or has no reference, kExitFailure when a case could not be rendered (an
// error outranks a failure); throws std::invalid_argument for bad flags and
// std::runtime_error for a bad suite file or an output folder that cannot be made.
int runCheck(const CheckOptions& options, std::ostream& out);

}  // namespace ssrt::cli
