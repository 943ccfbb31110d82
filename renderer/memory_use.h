// What a frame holds in memory, by resource group: the planes it hands out, the scratch its
// passes keep between frames, and the caller's history. `ssrt render --stats` prints it as
// bytes per pixel, the budget issue 27 sets (DESIGN.md: 150 B per pixel in all).
#pragma once

#include <vector>

#include "renderer/frame.h"

namespace ssrt {

// Every group that holds memory, in frame order (hand-outs, scratch, history; empty groups
// left out). `history` may be null.
std::vector<MemoryUse> memoryUse(const Frame& frame, const FrameHistory* history);

// What a frame of these settings needs before it is rendered, for a caller that must refuse a
// size the machine cannot hold before allocating any of it: every plane of the frame's and the
// history's plane tables (renderer/frame.h, the same lists memoryUse counts) at full
// resolution, each its element's bytes a pixel (4 for f32, 2 for the denoiser's f16 signals),
// and the shadow map. Groups a frame leaves empty and
// half-resolution ones count as full, the scratch outside the tables does not: an estimate
// within a factor of about two of what --stats then reports.
struct FrameMemoryNeed {
    int planes = 0;              // full-resolution planes counted
    std::size_t pixelBytes = 0;  // their bytes a pixel
    std::size_t bytes = 0;
};
FrameMemoryNeed frameMemoryNeed(int width, int height, int shadowMapSize);

}  // namespace ssrt
