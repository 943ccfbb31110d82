// The hit statistics kernel, one copy per ISA (trace/hit_stats_kernel.cpp); what it computes
// is in trace/hit_stats.h.
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "core/plane_view.h"

namespace ssrt {

// One trace pass's hit statistics: the caller names the outputs, HitStatsAccumulator checks
// them and sets the rest. Plain data only: this crosses into code compiled with other ISA
// flags.
struct HitStatsArgs {
    // The caller's: the outputs, of the camera's size (steps, distance absent: not kept).
    OutF hit{}, steps{}, distance{};
    // Set by the accumulator: the camera, the outputs' one stride, the samples.
    int width = 0, height = 0, tilesX = 0;
    std::size_t stride = 0;
    float tanHalfX = 0.0f, tanHalfY = 0.0f;
    bool first = false, last = false;  // sample 0 (overwrite), the last sample (divide)
    float invCount = 0.0f;             // 1 / sampleCount
    // Set per tile: a batch's planes, with their own stride, whose element (0, 0) is the
    // frame's pixel (inX0, inY0) (trace/trace_types.h, BatchCorner).
    const float* marchHit = nullptr;
    const float* marchSteps = nullptr;  // (with steps only)
    const float* hitPos[3] = {};        // hitX, hitY, hitZ (distance only)
    const float* origin[3] = {};        // ox, oy, oz (distance only)
    std::size_t inStride = 0;
    int inX0 = 0, inY0 = 0;
};

SSRT_DECLARE_KERNEL(void, hitStatsTile, (const HitStatsArgs& args, int tile))

}  // namespace ssrt
