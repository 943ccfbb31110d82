// Another program run to its end: `ssrt check` renders each case in its own `ssrt render`
// process, so a case runs exactly as its printed command does, and a crash fails that case only.
#pragma once

#include <string>
#include <vector>

namespace ssrt::cli {

// Runs `program` with `args` (without the program's name) in the folder `folder`, its standard
// output and error both to the file `log` (created or truncated), and waits for it. Returns its
// exit status, or 128 + the signal that ended it. Throws std::runtime_error when it cannot start.
int runProcess(const std::string& program, const std::vector<std::string>& args,
               const std::string& folder, const std::string& log);

// The words as a POSIX shell reads them back: each quoted with '...' unless it holds only
// characters that need none.
std::string shellCommand(const std::vector<std::string>& words);

// The path of the running program (/proc/self/exe).
std::string thisProgram();

}  // namespace ssrt::cli
