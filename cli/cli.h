// The ssrt command line, callable without a process so tests can drive it.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace ssrt::cli {

// Exit statuses: the command line was wrong, or the work it asked for could not be done.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  // bad shot/scene/image file, I/O, missing ISA, render
inline constexpr int kExitUsage = 2;    // unknown option, bad value, unknown scene or format

// Parses argv (argv[0] is the program) and runs the chosen command. Help and results go to
// `out`; progress and one-line "ssrt: error: ..." messages go to `err`. Returns the exit status.
int runCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

// Runs `command`, turning an escaping exception into one error line on `err` and a status:
// std::invalid_argument means bad input (kExitUsage), any other exception kExitFailure.
int reportErrors(std::ostream& err, const std::function<int()>& command);

// `text` with line breaks turned into spaces, so every error stays on one line.
std::string oneLine(std::string text);

}  // namespace ssrt::cli
