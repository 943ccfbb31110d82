// The ssrt command line, callable without a process so tests can drive it.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace ssrt::cli {

// Exit statuses, project-wide. 1 means only "the images differ": a script can tell a golden
// image that no longer matches (1) from a command line it got wrong (2) and from work that
// could not be done at all (3).
inline constexpr int kExitOk = 0;       // success; for `diff` and `render --compare`: within
                                        // every threshold
inline constexpr int kExitDiffer = 1;   // `diff` / `render --compare`: beyond a threshold
inline constexpr int kExitUsage = 2;    // unknown option, bad value, unknown scene or format
inline constexpr int kExitFailure = 3;  // bad shot/scene/image file, I/O, missing ISA, render

// Parses argv (argv[0] is the program) and runs the chosen command. Help and results go to
// `out`; progress and one-line "ssrt: error: ..." messages go to `err`. Returns the exit status.
int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

class CommandLine;  // cli/command_line.h

// runCli with `line` (new, or reset()) for the parsing: what runs many command lines in one
// process (the fuzzers) without building the app's hundreds of options for each.
int runCli(CommandLine& line, int argc, const char* const* argv, std::ostream& out,
           std::ostream& err);

// Runs `command`, turning an escaping exception into one error line on `err` and a status:
// std::invalid_argument means bad input (kExitUsage), any other exception kExitFailure.
int reportErrors(std::ostream& err, const std::function<int()>& command);

// `text` with line breaks turned into spaces, so every error stays on one line.
std::string oneLine(std::string text);

}  // namespace ssrt::cli
