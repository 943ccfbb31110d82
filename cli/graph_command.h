// `ssrt graph`: the frame's passes and resources for given settings, before any rendering: a
// table (each resource's format, resolution, lifetime, bytes per pixel, first and last pass)
// or Graphviz DOT (--dot), compiled from the declarations in renderer/frame_graph.h.
#pragma once

#include <iosfwd>

#include "cli/render_command.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

struct GraphOptions {
    RenderOptions render;  // the scene, the settings and the file a render would write
    bool dot = false;
};

// Registers the `graph` subcommand on `app`, bound to `options`, and returns it.
CLI::App* addGraphCommand(CLI::App& app, GraphOptions& options);

// Prints the graph of the frame `ssrt render` would render with these options (its last frame:
// with --frames above 1, a frame of a sequence, which reads and keeps a history). Returns 0;
// throws on bad options (see reportErrors).
int runGraph(const GraphOptions& options, std::ostream& out, std::ostream& err);

}  // namespace ssrt::cli
