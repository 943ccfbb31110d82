// The frame graph: every resource a frame may hold, every pass with what it reads (and how far
// around its pixel) and writes, and what follows from them for given settings and scene.
//
// The declarations are one table of resources (renderer/resources.h) and one list of passes
// in the order data flows (renderer/frame_graph_decl.cpp). compileFrameGraph() applies the
// settings: a pass the settings turn off is gone with its reads and writes, and a pass none of
// whose writes is read later, kept as an output or kept as history is culled (Filament's FrameGraph
// culls so). What is left gives which resources a frame holds, each one's first and last pass, how
// transient resources with disjoint lifetimes share memory, each pass's bytes per pixel,
// which passes could run tile by tile as one chain (every read of an earlier pass's resource
// at the reader's own pixel, and no write of what an earlier pass reads around its own), the
// frame's file layers, and `ssrt graph`'s table and DOT.
//
// (After Filament's FrameGraph and Unreal's RDG: passes declare their resources, which are
// virtual until the graph is compiled; and NRD's named resources with formats. A CPU adds the
// footprint: what a pass reads around its pixel decides whether it can follow the pass that
// wrote it in the same tile.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/frame.h"
#include "renderer/resources.h"

namespace ssrt {

// How far around its own pixel a pass reads a resource.
enum class Footprint : uint8_t { Pixel, Around, Anywhere };

struct Access {
    Res res;
    Footprint footprint = Footprint::Pixel;
    GraphCondition when = nullptr;  // null: always (while the pass runs)
};

// The names of the passes the renderer asks the graph about (CompiledGraph::runs), spelt
// once for the declarations and the renderer.
namespace pass {
inline constexpr std::string_view kShadow = "shadow";
inline constexpr std::string_view kVisibility = "visibility";
inline constexpr std::string_view kBackFaces = "back faces";
inline constexpr std::string_view kResolve = "resolve";
inline constexpr std::string_view kShading = "shading";
inline constexpr std::string_view kTextures = "textures";
inline constexpr std::string_view kIds = "ids";
inline constexpr std::string_view kHiZ = "hi-z";
inline constexpr std::string_view kThinFeatures = "thin features";
inline constexpr std::string_view kSsr = "ssr";
inline constexpr std::string_view kSsrReconstruct = "ssr reconstruct";
inline constexpr std::string_view kSsgi = "ssgi";
inline constexpr std::string_view kSsgiHalfFrame = "ssgi half frame";
inline constexpr std::string_view kSsgiHalf = "ssgi (half)";
inline constexpr std::string_view kSsgiReconstruct = "ssgi reconstruct";
inline constexpr std::string_view kSsgiUpsample = "ssgi upsample";
inline constexpr std::string_view kDenoiseFrontEnd = "denoise front end";
inline constexpr std::string_view kDenoiseFrontEndHalf = "denoise front end (half)";
inline constexpr std::string_view kDenoiseTemporal = "denoise temporal";
inline constexpr std::string_view kDenoiseTemporalHalf = "denoise temporal (half)";
inline constexpr std::string_view kDenoiseHistory = "denoise history";  // its commit
inline constexpr std::string_view kDenoiseUpsample = "denoise upsample";
inline constexpr std::string_view kComposite = "composite";
inline constexpr std::string_view kHistoryCommit = "history commit";
}  // namespace pass

struct PassDecl {
    std::string_view name;      // as `--stats` names its time
    GraphCondition enabled;     // null: always
    std::vector<Access> reads;  // a resource a pass reads and writes is in both lists
    std::vector<Access> writes;
    // It runs tile by tile (a kernel on one tile at a time, writing only that tile), so it may
    // share a loop over the tiles with other passes (a chain); else it runs over the whole
    // frame by itself. The frame scheduler runs each pass as declared here.
    bool tiled = false;
};

// The passes in the order they run.
const std::vector<PassDecl>& passDecls();

// One resource of a compiled graph.
struct GraphResource {
    Res id;
    Lifetime lifetime;          // the declared one, or transient for an output not handed out
    int first = -1, last = -1;  // indices into CompiledGraph::passes: the writer, the last reader
    std::size_t bytes = 0;      // at the graph's size, without row padding
    // Transient: where each of its planes lies in the transients' memory (byte offsets, as
    // the planes' range would place them: core/plane_memory.h), shared only with transients
    // whose lifetimes do not overlap its own.
    std::vector<std::size_t> offsets;
};

struct GraphPass {
    const PassDecl* decl;
    std::vector<Access> reads, writes;  // those the settings keep
    // Writes nothing reads (culled from `writes`) that the pass's kernel makes all the same:
    // they take memory while the pass runs (the shading's colour where the composite
    // overwrites it unread).
    std::vector<Access> unread;
    std::size_t bytesRead = 0, bytesWritten = 0;  // per frame, each resource once
    int chain = 0;  // passes of one chain run in one loop over the tiles
};

struct CompiledGraph {
    int width = 0, height = 0;
    std::vector<GraphPass> passes;         // in order, culled ones gone
    std::vector<GraphResource> resources;  // those that exist, in table order
    std::vector<std::string_view> culled;  // passes the settings enable but nothing reads
    std::size_t transientBytes = 0;        // after reuse: the highest the placed planes reach
    std::size_t outputBytes = 0, historyBytes = 0;
    const GraphResource* find(Res id) const;
    // Whether the pass called `name` runs.
    bool runs(std::string_view name) const;
    bool has(Res id) const { return find(id) != nullptr; }
    // The channel names of the outputs, in table order: a rendered Frame's layers.
    std::vector<std::string> layerNames() const;
    std::size_t totalBytes() const { return transientBytes + outputBytes + historyBytes; }
};

// Throws std::invalid_argument for settings that fail validate().
CompiledGraph compileFrameGraph(const GraphKey& key);

// Graphviz DOT of the compiled graph: passes as boxes, resources as ellipses (history and
// outputs marked), an edge per read and write.
std::string frameGraphDot(const CompiledGraph& graph);

}  // namespace ssrt
