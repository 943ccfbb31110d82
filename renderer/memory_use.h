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

}  // namespace ssrt
