#include "cli/scenes_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <ostream>

#include "cli/cli.h"
#include "scenes/builtin_scenes.h"

namespace ssrt::cli {

CLI::App* addScenesCommand(CLI::App& app) {
    return app.add_subcommand("scenes", "List the built-in scenes with a line about each");
}

int runScenes(std::ostream& out) {
    const auto& scenes = builtinScenes();
    std::size_t nameWidth = 0;
    for (const auto& s : scenes) nameWidth = std::max(nameWidth, s.name.size());
    for (const auto& s : scenes) {
        out << s.name << std::string(nameWidth - s.name.size() + 2, ' ') << s.description << "\n";
    }
    return kExitOk;
}

}  // namespace ssrt::cli
