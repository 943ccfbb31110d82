#include "cli/graph_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <ostream>
#include <string>

#include "cli/cli.h"
#include "cli/options.h"
#include "cli/render_command.h"
#include "cli/sequence.h"
#include "renderer/frame_graph.h"
#include "renderer/quality.h"

namespace ssrt::cli {

CLI::App* addGraphCommand(CLI::App& app, GraphOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "graph",
        "Print the frame's passes and resources for the given settings, before rendering: "
        "each resource's format, resolution, lifetime, bytes per pixel and first and last "
        "pass, what the settings cull, and the memory a frame holds (or Graphviz DOT)");
    addSceneOptions(*cmd, o.render, RenderSettings{});
    addTraceOptions(*cmd, o.render);
    addSequenceOptions(*cmd, o.render,
                       "the frames a render would make: above 1, the graph of a sequence's frame, "
                       "which reads and keeps a history (default 1: a single image, without)");
    cmd->add_option_function<std::string>(
           "-o,--output",
           [&o](const std::string& v) {
               o.render.output = v;
               o.render.outputGiven = true;
           },
           "The file the render would write (default a PNG): a PNG, or an EXR whose --layers "
           "leave out a group, makes no plane only that group shows")
        ->type_name("FILE");
    addImageOutputOptions(*cmd, o.render);
    cmd->add_flag("--dot", o.dot,
                  "Graphviz DOT instead of the table: passes as boxes, resources as ellipses "
                  "(outputs green, history orange), reads dashed around the pixel, dotted from "
                  "anywhere (e.g. ssrt graph --dot | dot -Tsvg -o graph.svg)");
    return cmd;
}

namespace {

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

std::string padded(std::string s, std::size_t width) {
    if (s.size() < width) s.append(width - s.size(), ' ');
    return s;
}

std::string mib(std::size_t bytes) { return fixed(double(bytes) / (1024.0 * 1024.0), 1); }

void printTable(const CompiledGraph& g, const SceneRequest& r, bool sequence, std::ostream& out) {
    const double pixels = double(g.width) * double(g.height);
    out << "frame graph: " << r.name << ", " << g.width << "x" << g.height << ", "
        << (sequence ? "a frame of a sequence (history read and kept)"
                     : "a single image (no history)")
        << "\n\npasses, in order (a chain: passes that run in one loop over the tiles)\n";
    out << "  " << padded("pass", 28) << padded("chain", 7) << padded("reads MiB", 11)
        << "writes MiB\n";
    for (const GraphPass& p : g.passes)
        out << "  " << padded(std::string(p.decl->name), 28) << padded(std::to_string(p.chain), 7)
            << padded(mib(p.bytesRead), 11) << mib(p.bytesWritten) << "\n";
    if (!g.culled.empty()) {
        out << "culled (enabled, but nothing reads what they write):";
        for (std::string_view c : g.culled) out << " " << c << ";";
        out << "\n";
    }
    out << "\nresources\n  " << padded("resource", 26) << padded("format", 8)
        << padded("channels", 10) << padded("resolution", 14) << padded("lifetime", 11)
        << padded("B/pixel", 9) << padded("MiB", 8) << padded("first pass", 28) << "last pass\n";
    for (const GraphResource& res : g.resources) {
        const ResourceDecl& d = resourceDecl(res.id);
        out << "  " << padded(std::string(d.name), 26)
            << padded(std::string(pixelFormatName(d.format)), 8)
            << padded(std::to_string(d.channelCount()), 10)
            << padded(std::string(resolutionName(d.resolution)), 14)
            << padded(std::string(lifetimeName(res.lifetime)), 11)
            << padded(fixed(double(res.bytes) / pixels, 1), 9) << padded(mib(res.bytes), 8)
            << padded(std::string(g.passes[std::size_t(res.first)].decl->name), 28)
            << g.passes[std::size_t(res.last)].decl->name << "\n";
    }
    std::size_t transientSum = 0;
    for (const GraphResource& res : g.resources)
        if (res.lifetime == Lifetime::Transient) transientSum += res.bytes;
    const auto perPixel = [&](std::size_t b) { return fixed(double(b) / pixels, 1) + " B/pixel"; };
    out << "\nmemory (declared formats, no row padding)\n"
        << "  transient  " << mib(g.transientBytes) << " MiB, " << perPixel(g.transientBytes)
        << " (" << mib(transientSum) << " MiB without reuse)\n"
        << "  output     " << mib(g.outputBytes) << " MiB, " << perPixel(g.outputBytes) << "\n"
        << "  history    " << mib(g.historyBytes) << " MiB, " << perPixel(g.historyBytes) << "\n"
        << "  total      " << mib(g.totalBytes()) << " MiB, " << perPixel(g.totalBytes()) << "\n";
}

}  // namespace

int runGraph(const GraphOptions& o, std::ostream& out, std::ostream& err) {
    SceneRequest request = loadSceneRequest(o.render);
    const SequencePlan plan = sequencePlanFrom(o.render, request);
    const FrameWriteOptions writeOptions =
        writeOptionsFrom(o.render, request.settings, renderOutput(o.render), err);
    planesForFile(renderOutput(o.render), writeOptions.layers, request.settings);
    loadScene(request, err);
    // (The graph of a sequence's middle frame: the last one's history read and its own kept.)
    const bool sequence = plan.frames + plan.warmup > 1;
    const CompiledGraph g =
        compileFrameGraph({request.settings, SceneFacts::of(request.scene), sequence, sequence});
    if (o.dot) out << frameGraphDot(g);
    else printTable(g, request, sequence, out);
    return kExitOk;
}

}  // namespace ssrt::cli
