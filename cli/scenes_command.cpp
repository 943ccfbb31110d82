#include "cli/scenes_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <ostream>

#include "cli/cli.h"
#include "cli/json_output.h"
#include "scenes/builtin_scenes.h"

namespace ssrt::cli {

CLI::App* addScenesCommand(CLI::App& app, ScenesOptions& o) {
    CLI::App* cmd = app.add_subcommand("scenes", "List the built-in scenes with a line about each");
    cmd->add_flag("--json", o.json,
                  "Print them as one JSON object on stdout instead, {name: description} in the "
                  "same order");
    return cmd;
}

int runScenes(const ScenesOptions& o, std::ostream& out) {
    if (o.json) {
        printJson(out, builtinScenesJson());
        return kExitOk;
    }
    const auto& scenes = builtinScenes();
    std::size_t nameWidth = 0;
    for (const auto& s : scenes) nameWidth = std::max(nameWidth, s.name.size());
    for (const auto& s : scenes) {
        out << s.name << std::string(nameWidth - s.name.size() + 2, ' ') << s.description << "\n";
    }
    return kExitOk;
}

}  // namespace ssrt::cli
