// `ssrt scenes`: the built-in scenes, one line each.
#pragma once

#include <iosfwd>

namespace CLI {
class App;
}

namespace ssrt::cli {

// Registers the `scenes` subcommand on `app` and returns it.
CLI::App* addScenesCommand(CLI::App& app);

// Prints "name  description" for every built-in scene, the default first; returns 0.
int runScenes(std::ostream& out);

}  // namespace ssrt::cli
