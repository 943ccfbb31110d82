// A frame size against the memory this process may use, checked before anything is loaded or
// allocated: a render the machine cannot hold fails in one line saying so, rather than with
// std::bad_alloc (or the kernel's OOM killer) part way through.
#pragma once

#include <cstddef>
#include <string>

#include "renderer/settings.h"

namespace ssrt::cli {

struct AvailableMemory {
    std::size_t bytes = 0;
    std::string source;  // what limits it: "MemAvailable" or "ulimit -v"
};

// The smaller of the system's available memory (MemAvailable in /proc/meminfo) and what the
// address-space limit (ulimit -v) leaves this process; unlimited where neither can be read.
AvailableMemory availableMemory();

// Throws std::runtime_error (exit 3), one line naming --width and --height, the frame's size,
// the bytes it needs (renderer/memory_use.h frameMemoryNeed) and the bytes available, when the
// frame needs more than `available`.
void checkFrameMemory(const RenderSettings& settings, const AvailableMemory& available);

}  // namespace ssrt::cli
