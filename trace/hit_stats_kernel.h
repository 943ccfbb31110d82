// The hit statistics kernel, one copy per ISA (trace/hit_stats_kernel.cpp); what it computes
// is in trace/hit_stats.h.
#pragma once

#include <cstddef>

#include "core/dispatch.h"

namespace ssrt {

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
// The outputs have the frame's size and one stride (`stride`).
struct HitStatsArgs {
    int width, height, tilesX;
    std::size_t stride;
    float tanHalfX, tanHalfY;
    const float* hit;
    const float* steps;      // (with outSteps only)
    const float* hitPos[3];  // hitX, hitY, hitZ (distance only)
    const float* origin[3];  // ox, oy, oz (distance only)
    // The inputs above (a batch's planes) have their own stride, and their element (0, 0) is
    // the frame's pixel (inX0, inY0) (trace/trace_types.h, BatchCorner).
    std::size_t inStride;
    int inX0, inY0;
    float* outHit;
    float* outSteps;     // null: no steps
    float* outDistance;  // null: no distance
    bool first, last;    // sample 0 (overwrite), the last sample (divide)
    float invCount;      // 1 / sampleCount
};

SSRT_DECLARE_KERNEL(void, hitStatsTile, (const HitStatsArgs& args, int tile))

}  // namespace ssrt
