// The SSR trace as one chain per tile (issue 27): a tile's rays are generated into a batch of
// one tile's size, marched, and turned into hit radiance and hit statistics while the batch is
// still in the core's cache; only the resolve's second pass, which reads each pixel's
// neighbours, runs after every tile's first. The frame's rays and march results are never
// made: 13 planes a pixel less and neither written to memory nor read back. The truth's ray
// check, which reads the frame's batches, takes the stage-by-stage path instead
// (renderer/trace_pass.cpp). A pixel's result is the same bits either way: every stage reads
// its own pixel's ray and march result, and the tile loop's order changes nothing.
#pragma once

#include "trace/hit_stats.h"
#include "trace/march.h"
#include "trace/ray_gen.h"
#include "trace/ssr_resolve.h"

namespace ssrt {

// One sample's stages, set up over one camera's tile grid (the resolver with tileBatches).
struct SsrTileChain {
    const RayGenerator& rays;
    const RayMarcher& march;
    const SsrResolver& resolve;
    const HitStatsAccumulator& hitStats;
};

struct SsrChainStats {
    RayGenStats rays;
    MarchStats march;
    // Wall time of the chain's tile loop and of the resolve's second pass, and the chain's
    // time split between its stages by the threads' time in each (ms; the three sum to
    // the loop's).
    double raysMs = 0.0, marchMs = 0.0, hitMs = 0.0, resolveMs = 0.0;
};

// Runs the chain on every tile on `threads` threads (0 = every core), then the resolve's
// second pass; counters in tile order.
SsrChainStats runSsrTileChain(const SsrTileChain& chain, int threads);

}  // namespace ssrt
