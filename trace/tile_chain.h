// A trace pass as one chain per tile (issue 27): a tile's rays are generated into a batch of
// one tile's size, marched, and handed to what reads each pixel's own ray and march result
// (the resolve's per-pixel pass, the hit statistics) while the batch is still in the core's
// cache. The frame's rays and march results are never made: 13 planes a pixel less, neither
// written to memory nor read back. A pass that reads its neighbours' results (the SSR
// resolve's ray reuse, the layouts' reconstruction) runs after the chain on what the chain's
// consumer copied out. The truth's ray check, which reads the frame's batches, takes the
// stage-by-stage path instead (renderer/trace_pass.cpp). A pixel's result is the same bits
// either way: every stage reads its own pixel's ray and march result, and the order of the
// tiles changes nothing.
#pragma once

#include <functional>

#include "trace/march.h"
#include "trace/ray_gen.h"

namespace ssrt {

// The tile rows a chain's `finish` stage reads through: what `consume` writes for it may lie in
// a ring of this many tile rows (frame row y at row y % (kChainRingTileRows * kTileSize)).
inline constexpr int kChainRingTileRows = 4;

// One sample's stages over one camera's tile grid.
struct TileChain {
    const RayGenerator& rays;
    const RayMarcher& march;
    // Reads the tile's batches (their corner the tile's): called once per tile, on the tile
    // loop's threads, so it writes only the tile's pixels.
    std::function<void(int tile, const RayBatch& rays, const MarchResult& march)> consume;
    // Optional: a stage that reads what `consume` wrote up to one pixel around the tile (the
    // SSR resolve's ray reuse), so the halo lies in the tile rows above and below. It runs on a
    // tile once `consume` has run on its tile row and the rows next to it, and before `consume`
    // runs kChainRingTileRows - 1 rows below it: tile row r's finish runs with row r + 2's
    // chains, so what `consume` writes for it needs no more than kChainRingTileRows tile rows
    // of memory, not a frame's.
    std::function<void(int tile)> finish = {};
    // Optional, between the march and `consume`: what the march could not answer, answered
    // another way (world rays: trace/world_rays.h), written into the tile's march result.
    std::function<void(int tile, const RayBatch& rays, MarchResult& march)> answer = {};
};

struct TileChainStats {
    RayGenStats rays;
    MarchStats march;
    // The tile loop's wall time split between the stages by the threads' time in each (ms;
    // the five sum to the loop's).
    double raysMs = 0.0, marchMs = 0.0, consumeMs = 0.0, finishMs = 0.0, answerMs = 0.0;
};

// Runs the chain on every tile on `threads` threads (0 = every core); counters in tile order.
// With a `finish` stage, the tiles run a tile row at a time: step k runs row k's chains and
// row k - 2's finish together (tilesY + 2 steps).
TileChainStats runTileChain(const TileChain& chain, int threads);

}  // namespace ssrt
