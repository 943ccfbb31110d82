#include "cli/memory_check.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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

// The files of one cgroup version's memory controller.
struct CgroupKind {
    const char* limit;     // the limit in bytes ("max": none)
    const char* usage;     // what the group uses now, in bytes
    const char* inactive;  // memory.stat's key for the inactive file cache
};
constexpr CgroupKind kCgroupV2{"memory.max", "memory.current", "inactive_file"};
constexpr CgroupKind kCgroupV1{"memory.limit_in_bytes", "memory.usage_in_bytes",
                               "total_inactive_file"};

// Where a controller's hierarchy is mounted: the folder, and which cgroup its top is.
struct CgroupMount {
    std::string dir, root;
};

// One number of a cgroup file (a missing file, "max" or v1's "no limit", 2^63 rounded down to
// a page, all read as kUnlimited).
std::size_t readBytes(const std::filesystem::path& file) {
    std::ifstream in(file);
    unsigned long long value = 0;
    if (!(in >> value) || value >= (1ull << 62)) return kUnlimited;
    return std::size_t(value);
}

// A key's value in a memory.stat file; 0 where it is missing.
std::size_t statValue(const std::filesystem::path& file, const std::string& wanted) {
    std::ifstream in(file);
    std::string key;
    unsigned long long value = 0;
    while (in >> key >> value)
        if (key == wanted) return std::size_t(value);
    return 0;
}

// The mounts of cgroup2 (`v2`) and of v1's memory controller (`v1`) in a mountinfo file
// ("ID PARENT MAJ:MIN ROOT MOUNT OPTIONS [TAGS] - TYPE SOURCE SUPER-OPTIONS").
void findMounts(const CgroupFiles& files, CgroupMount& v2, CgroupMount& v1) {
    std::ifstream in(files.mountinfo);
    for (std::string line; std::getline(in, line);) {
        std::istringstream fields(line);
        std::vector<std::string> f;
        for (std::string word; fields >> word;) f.push_back(word);
        const auto dash = std::find(f.begin(), f.end(), "-");
        if (f.size() < 5 || f.end() - dash < 4) continue;
        const std::string& type = dash[1];
        const CgroupMount mount{files.rootPrefix + f[4], f[3]};
        if (type == "cgroup2" && v2.dir.empty()) v2 = mount;
        if (type == "cgroup" && v1.dir.empty() &&
            ("," + dash[3] + ",").find(",memory,") != std::string::npos)
            v1 = mount;
    }
}

// This process's cgroup in the v2 hierarchy ("0::/path") and in v1's memory one
// ("N:cpu,memory:/path"); empty where it has none.
void findCgroups(const CgroupFiles& files, std::string& v2, std::string& v1) {
    std::ifstream in(files.cgroup);
    for (std::string line; std::getline(in, line);) {
        const std::size_t a = line.find(':'), b = line.find(':', a + 1);
        if (a == std::string::npos || b == std::string::npos) continue;
        const std::string controllers = "," + line.substr(a + 1, b - a - 1) + ",";
        const std::string path = line.substr(b + 1);
        if (line.compare(0, a, "0") == 0 && controllers == ",,") v2 = path;
        else if (controllers.find(",memory,") != std::string::npos) v1 = path;
    }
}

// The smallest of what the limits of `cgroup` and every cgroup above it leave.
void leftInHierarchy(const CgroupMount& mount, std::string cgroup, const CgroupKind& kind,
                     AvailableMemory& best) {
    namespace fs = std::filesystem;
    if (mount.dir.empty() || cgroup.empty()) return;
    // Seen from a mount of a sub-hierarchy (a container's), the path starts with its root.
    if (mount.root != "/" && cgroup.rfind(mount.root, 0) == 0) cgroup.erase(0, mount.root.size());
    const fs::path top = fs::path(mount.dir).lexically_normal();
    fs::path dir = top;
    for (const fs::path& part : fs::path(cgroup).relative_path())
        if (!part.empty()) dir /= part;
    for (;; dir = dir.parent_path()) {
        const std::size_t limit = readBytes(dir / kind.limit);
        if (limit != kUnlimited) {
            std::size_t used = readBytes(dir / kind.usage);
            if (used == kUnlimited) used = 0;
            used -= std::min(used, statValue(dir / "memory.stat", kind.inactive));
            const std::size_t left = limit > used ? limit - used : 0;
            if (left < best.bytes) best = {left, "cgroup " + (dir / kind.limit).string()};
        }
        if (dir == top || dir == dir.parent_path()) break;
    }
}

std::string gigabytes(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", double(bytes) / 1e9);
    return text;
}

}  // namespace

AvailableMemory cgroupMemoryLeft(const CgroupFiles& files) {
    CgroupMount v2Mount, v1Mount;
    findMounts(files, v2Mount, v1Mount);
    std::string v2Cgroup, v1Cgroup;
    findCgroups(files, v2Cgroup, v1Cgroup);
    AvailableMemory best{kUnlimited, ""};
    leftInHierarchy(v2Mount, v2Cgroup, kCgroupV2, best);
    leftInHierarchy(v1Mount, v1Cgroup, kCgroupV1, best);
    return best;
}

AvailableMemory availableMemory() {
    AvailableMemory best{memAvailable(), "MemAvailable"};
    if (const std::size_t process = addressSpaceLeft(); process < best.bytes)
        best = {process, "ulimit -v"};
    if (AvailableMemory group = cgroupMemoryLeft(); group.bytes < best.bytes)
        best = std::move(group);
    return best;
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

std::string outOfMemoryMessage() {
    const AvailableMemory available = availableMemory();
    return "out of memory: an allocation failed; this process may use about " +
           gigabytes(available.bytes) + " (" + available.source + ")";
}

}  // namespace ssrt::cli
