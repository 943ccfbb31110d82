// Per-pixel statistics of one trace pass over its samples (the renderer's "ssrHit",
// "ssrSteps", "ssrHitDistance", "ssgiHit", "ssgiHitDistance", "ssgiSteps" planes): the fraction of
// rays that hit, the mean march steps and, optionally, the mean view-space distance from the ray's
// origin to its hit (over the hits; 0 without any). A kernel over the lane type, one copy per ISA:
// every pixel gets the same bits on every ISA and thread count, and the same as the scalar
// loops it replaces (renderer/trace_pass.cpp before it).
#pragma once

#include "core/image.h"
#include "core/isa.h"
#include "core/tiles.h"
#include "trace/hit_stats_kernel.h"
#include "trace/trace_types.h"

namespace ssrt {

// Adds one sample's march to the outputs `out` names (views of the camera's size): sample 0
// overwrites, later samples add, and the call with sample == sampleCount - 1 turns the sums
// into means. Per pixel, the distance to a hit is |P - O| with P the hit's view-space point,
//   P = ((2 hitX / W - 1) tanHalfX z, (1 - 2 hitY / H) tanHalfY z, -z), z = hitZ,
// and O the ray's origin. Throws std::invalid_argument on a missing or mis-sized plane or a
// sample outside [0, sampleCount).
void accumulateHitStats(Isa isa, const TraceCamera& camera, const RayBatch& rays,
                        const MarchResult& march, const HitStatsArgs& out, int sample,
                        int sampleCount, int threads);

// The same, checked and set up once, then run tile by tile: over the frame by
// accumulateHitStats, or one tile at a time by a trace pass's tile chain (trace/tile_chain.h).
class HitStatsAccumulator {
public:
    // accumulateHitStats' arguments less the batches and threads.
    HitStatsAccumulator(Isa isa, const TraceCamera& camera, const HitStatsArgs& out, int sample,
                        int sampleCount);
    const TileGrid& grid() const { return grid_; }
    // Tile `tile` of the batches: each the frame's (corner (0, 0)) or a tile's; one corner.
    void tile(int tile, const RayBatch& rays, const MarchResult& march) const;

private:
    HitStatsArgs args_{};
    TileGrid grid_;
    decltype(&isa_scalar::hitStatsTile) kernel_ = nullptr;
};

}  // namespace ssrt
