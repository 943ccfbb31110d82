// `ssrt man`: the manual page, in roff (man(7)), made from the command line's own CLI11 app,
// so that it lists exactly the commands and flags `ssrt --help` lists.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace ssrt::cli {

// Registers the `man` subcommand on `app` and returns it.
CLI::App* addManCommand(CLI::App& app);

// Writes ssrt(1) for `app`: NAME, SYNOPSIS, DESCRIPTION, COMMANDS (each command's usage,
// description and options by help section, with their defaults), EXIT STATUS
// (`exitStatus`, the text the help's footer gives), ENVIRONMENT, FILES and SEE ALSO.
// `version` names the program in the page's footer ("ssrt 0.1.0").
void writeManPage(const CLI::App& app, const std::string& exitStatus, const std::string& version,
                  std::ostream& out);

}  // namespace ssrt::cli
