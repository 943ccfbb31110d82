// `ssrt completion bash`: a bash completion script made from the command line's own CLI11 app,
// so that it completes exactly the commands and flags `ssrt --help` lists.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace ssrt::cli {

// Registers the `completion` subcommand on `app` (its one argument, the shell, goes to
// `shell`) and returns it.
CLI::App* addCompletionCommand(CLI::App& app, std::string& shell);

// Writes the bash completion script for `app`: its commands, each command's flags, the
// built-in scene names after -s/--scene and file names after options whose value is a file
// and for positional arguments.
void writeBashCompletion(const CLI::App& app, std::ostream& out);

}  // namespace ssrt::cli
