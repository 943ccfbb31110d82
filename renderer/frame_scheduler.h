// Runs a frame's passes in the frame graph's order (renderer/frame_graph.h), and the passes of
// one chain that run tile by tile as one loop over the tiles: each tile goes through every
// pass of the chain while its pixels are in cache, and no pass waits for the whole frame of
// the one before. The graph's chains say where that is allowed (a pass reads what its chain
// wrote only at its own pixel, and overwrites nothing an earlier pass of the chain reads
// around its own); a tile kernel writes only its own tile, so the bits do not depend on the
// order the threads take the tiles in (core/tiles.h). A chain's set-ups all run before its
// first tile: a set-up may not read what an earlier pass of its chain writes.
//
// Given the frame's memory, each chain and each whole pass is one of its steps: a chain's
// planes are taken before its set-ups and the transients it read last go back after its
// finishes (the graph places transient memory so). The screen-space passes run on one
// scheduler (renderer/trace_pass.cpp): SSR and SSGI whole, the denoiser's passes and the
// composite tiled, each denoiser pass's own scratch taken in its set-up and given back in its
// finish; so the denoiser's front end and temporal pass, and its post-blur, the history's commit
// and the composite, share a loop where the graph chains them.
//
// (No halo: a pass that reads around its pixel what its chain made starts a chain of its own.
// The denoiser's blur and post-blur, the one pair of spatial passes in a row, read 30 and 60
// pixels around: a halo that wide would blur about eight times a tile's pixels per tile.)
#pragma once

#include <atomic>
#include <functional>
#include <string_view>
#include <vector>

#include "core/tiles.h"
#include "renderer/frame.h"
#include "renderer/frame_graph.h"

namespace ssrt {

class FrameMemory;

class FrameScheduler {
public:
    // `cancel` (optional) is read before each whole pass and each chain (render_cancel.h).
    // `memory` (optional): each whole pass and each chain is one of its steps, so the planes a
    // step's passes write first are taken just before it and the transients they read last go
    // back just after it (renderer/frame_memory.h).
    FrameScheduler(const CompiledGraph& graph, const TileGrid& grid, int threads,
                   const std::atomic<bool>* cancel = nullptr, FrameMemory* memory = nullptr)
        : graph_(graph), grid_(grid), threads_(threads), cancel_(cancel), memory_(memory) {}

    // A pass that runs over the whole frame by itself (and times itself); it also runs the
    // declared passes after it through `through` (a declared pass; empty: none), which are not
    // given here (the SSR pass makes its checkerboard's other phase). A name given twice is a
    // std::logic_error.
    void whole(std::string_view pass, std::function<void()> run, std::string_view through = {});
    // A pass that runs tile by tile: `setUp` (optional) before the chain's first tile, after
    // the set-ups of the chain's passes before it; then `tile` for each tile; then `finish`
    // (optional) after the chain's last tile, after the finishes of the passes before it. Its
    // tiles are the frame's, or `grid`'s (the half frame's, read once the chain's set-ups have
    // run: a chain's passes share one grid, else std::logic_error). Its time is its share of
    // the chain's loop, with its set-up and finish.
    // A pass given whole that is declared tiled, or tiled that is declared whole
    // (PassDecl::tiled), is a std::logic_error when run() starts.
    void tiled(std::string_view pass, std::function<void(int tile)> tile,
               std::function<void()> setUp = {}, std::function<void()> finish = {},
               const TileGrid* grid = nullptr);

    // Runs the passes given, those the graph runs, in the graph's order (std::logic_error for
    // a pass the graph does not know); adds the tiled passes' times to `stats`.
    void run(FrameStats& stats);

    struct Pass {
        std::string_view name;
        std::string_view through;  // a whole pass's last declared pass (empty: itself)
        std::function<void()> whole, setUp, finish;
        std::function<void(int)> tile;
        const TileGrid* grid = nullptr;  // null: the frame's
    };

private:
    void runChain(const std::vector<const Pass*>& chain, FrameStats& stats);
    // Runs `fn` as the declared passes through `last` (a memory step, with memory).
    void step(std::string_view last, const std::function<void()>& fn);

    const CompiledGraph& graph_;
    TileGrid grid_;
    int threads_;
    const std::atomic<bool>* cancel_;
    FrameMemory* memory_;
    std::vector<Pass> passes_;
};

}  // namespace ssrt
