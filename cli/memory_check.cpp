#include "cli/memory_check.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "renderer/memory_use.h"

namespace ssrt::cli {

namespace {

constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();

// MemAvailable from /proc/meminfo, in bytes; kUnlimited if it cannot be read.
std::size_t memAvailable() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::size_t kib = 0;
    while (in >> key >> kib) {
        if (key == "MemAvailable:") return kib * 1024;
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return kUnlimited;
}

// What ulimit -v leaves this process beyond what it maps already; kUnlimited without a limit.
std::size_t addressSpaceLeft() {
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return kUnlimited;
    std::ifstream statm("/proc/self/statm");
    std::size_t pages = 0;
    statm >> pages;
    const std::size_t mapped = pages * std::size_t(4096);
    return limit.rlim_cur > mapped ? std::size_t(limit.rlim_cur) - mapped : 0;
}

std::string gigabytes(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", double(bytes) / 1e9);
    return text;
}

}  // namespace

AvailableMemory availableMemory() {
    const std::size_t system = memAvailable(), process = addressSpaceLeft();
    return process < system ? AvailableMemory{process, "ulimit -v"}
                            : AvailableMemory{system, "MemAvailable"};
}

void checkFrameMemory(const RenderSettings& s, const AvailableMemory& available) {
    const FrameMemoryNeed need = frameMemoryNeed(s.width, s.height, s.shadowMapSize);
    if (need.bytes <= available.bytes) return;
    const std::string side = std::to_string(s.shadowMapSize);
    throw std::runtime_error(
        "--width, --height: a " + std::to_string(s.width) + " x " + std::to_string(s.height) +
        " frame needs about " + gigabytes(need.bytes) + " (" + std::to_string(need.planes) +
        " planes of 4 bytes a pixel and a " + side + " x " + side + " shadow map), more than the " +
        gigabytes(available.bytes) + " this process may use (" + available.source + ")");
}

}  // namespace ssrt::cli
