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
    // What limits it: "MemAvailable", "ulimit -v", or a cgroup's limit file with its path
    // ("cgroup /sys/fs/cgroup/job/memory.max").
    std::string source;
};

// Where the cgroup file systems are mounted and which cgroup this process is in: the running
// system's by default; a test points them at a fake tree.
struct CgroupFiles {
    std::string mountinfo = "/proc/self/mountinfo";  // the cgroup2 and v1 memory mounts
    std::string cgroup = "/proc/self/cgroup";        // this process's cgroup in each
    std::string rootPrefix;  // put before every mount point found (a fake tree's folder)
};

// What the cgroups this process is in leave it: for its own cgroup and every one above it up
// to the mount, the limit (cgroup v2 memory.max, v1 memory.limit_in_bytes) less what the
// group uses (memory.current, memory.usage_in_bytes) beyond its inactive file cache (which
// the kernel drops before it refuses memory: memory.stat inactive_file, total_inactive_file);
// the smallest. Unlimited (SIZE_MAX, source empty) where no cgroup sets a limit or none can
// be read.
AvailableMemory cgroupMemoryLeft(const CgroupFiles& files = {});

// The smallest of the system's available memory (MemAvailable in /proc/meminfo), what the
// address-space limit (ulimit -v) leaves this process, and what its cgroups leave it
// (cgroupMemoryLeft); unlimited where none can be read.
AvailableMemory availableMemory();

// Throws std::runtime_error (exit 3), one line naming --width and --height, the frame's size,
// the bytes it needs (renderer/memory_use.h frameMemoryNeed) and the bytes available, when the
// frame needs more than `available`.
void checkFrameMemory(const RenderSettings& settings, const AvailableMemory& available);

// For a std::bad_alloc that got past checkFrameMemory (a scene, texture or environment image
// larger than the memory left, or an estimate short of the truth): one line saying so, with
// what this process may use now that the failed work's memory is freed ("out of memory: an
// allocation failed; this process may use about 0.9 GB (ulimit -v)").
std::string outOfMemoryMessage();

}  // namespace ssrt::cli
