// What a frame holds in memory, by resource: the planes it hands out, the scratch its passes
// keep between frames, and the caller's history. `ssrt render --stats` prints it as bytes per
// pixel beside what the frame graph declares (150 B per pixel in all is the budget).
#pragma once

#include <vector>

#include "renderer/frame.h"

namespace ssrt {

// Every resource that holds memory, named and in order as the resource table
// (renderer/resources.h) has them; then, by the group they lie in (Frame::Scratch::
// forEachBuffer: "rays", "march", ...), buffers that hold no declared resource; then the
// planes' range's free memory. Nothing that holds no memory. `history` may be null. Found by
// walking what the frame holds (Frame::forEachPlane, Frame::Scratch::forEachBuffer, the
// history's tables), not from a list of its own.
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
