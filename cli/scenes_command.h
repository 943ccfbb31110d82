// `ssrt scenes`: the built-in scenes, one line each.
#pragma once

#include <iosfwd>

namespace CLI {
class App;
}

namespace ssrt::cli {

struct ScenesOptions {
    bool json = false;  // --json: {name: description}, as ssrt.builtin_scenes() returns them
};

// Registers the `scenes` subcommand on `app`, bound to `options`, and returns it.
CLI::App* addScenesCommand(CLI::App& app, ScenesOptions& options);

// Prints "name  description" for every built-in scene, the default first (with --json one
// JSON object of them instead); returns 0.
int runScenes(const ScenesOptions& options, std::ostream& out);

}  // namespace ssrt::cli
