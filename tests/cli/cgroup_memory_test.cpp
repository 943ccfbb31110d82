// What a process's cgroups leave it (cli/memory_check.h cgroupMemoryLeft), read from fake
// trees: cgroup v2 (memory.max less memory.current beyond the inactive file cache) and v1
// (memory.limit_in_bytes, usage_in_bytes, total_inactive_file), the tightest of the process's
// group and every group above it, a container's view of its own sub-tree, and no limit at all.
// (tests/cli/check_cgroup_limit.sh runs `ssrt render` in a real cgroup where one can be made.)
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "cli/memory_check.h"
#include "cli_run.h"
#include "temp_dir.h"

using namespace ssrt;
using test::contains;
using test::TempDir;

namespace {

// A fake system: /proc/self/mountinfo and /proc/self/cgroup as files, the cgroup file systems
// as folders, all under one temporary folder.
struct FakeCgroups {
    TempDir dir;
    cli::CgroupFiles files;

    FakeCgroups(const std::string& mountinfo, const std::string& cgroup) {
        files.mountinfo = dir.file("mountinfo");
        files.cgroup = dir.file("cgroup");
        files.rootPrefix = dir.path.string();
        test::writeFile(files.mountinfo, mountinfo);
        test::writeFile(files.cgroup, cgroup);
    }
    // Writes `text` to the fake file at `path` (an absolute path on the fake system).
    void write(const std::string& path, const std::string& text) const {
        const std::filesystem::path file = dir.path.string() + path;
        std::filesystem::create_directories(file.parent_path());
        test::writeFile(file.string(), text);
    }
    std::string real(const std::string& path) const { return dir.path.string() + path; }
};

// A unified (cgroup v2 only) system, as systemd and recent container runtimes mount it.
const std::string kV2Mounts =
    "22 1 0:20 / /proc rw,nosuid - proc proc rw\n"
    "30 22 0:26 / /sys/fs/cgroup rw,nosuid,nodev,noexec,relatime shared:4 - cgroup2 cgroup2 "
    "rw,nsdelegate,memory_recursiveprot\n";
// A hybrid v1 system (this project's CI machines among them): the memory controller on v1, an
// empty cgroup2 beside it.
const std::string kV1Mounts =
    "30 22 0:27 / /sys/fs/cgroup rw,relatime - tmpfs tmpfs rw,mode=755\n"
    "31 30 0:28 / /sys/fs/cgroup/cpu rw,relatime - cgroup cgroup rw,cpu\n"
    "34 30 0:31 / /sys/fs/cgroup/memory rw,relatime - cgroup cgroup rw,memory\n"
    "40 30 0:37 / /sys/fs/cgroup/unified rw,relatime - cgroup2 cgroup2 rw\n";

constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();

}  // namespace

TEST_CASE("cgroup memory: v2, the limit less what the group uses beyond its file cache") {
    const FakeCgroups fake(kV2Mounts, "0::/user.slice/job.scope\n");
    const std::string job = "/sys/fs/cgroup/user.slice/job.scope/";
    fake.write(job + "memory.max", "1000000000\n");
    fake.write(job + "memory.current", "300000000\n");
    fake.write(job + "memory.stat", "anon 150000000\nfile 150000000\ninactive_file 100000000\n");
    fake.write("/sys/fs/cgroup/user.slice/memory.max", "max\n");
    fake.write("/sys/fs/cgroup/user.slice/memory.current", "900000000\n");
    const cli::AvailableMemory left = cli::cgroupMemoryLeft(fake.files);
    CHECK(left.bytes == 1000000000 - (300000000 - 100000000));
    CHECK(left.source == "cgroup " + fake.real(job + "memory.max"));

    SUBCASE("a group above with less room is the limit") {
        fake.write("/sys/fs/cgroup/user.slice/memory.max", "950000000\n");
        const cli::AvailableMemory above = cli::cgroupMemoryLeft(fake.files);
        CHECK(above.bytes == 50000000);
        CHECK(above.source == "cgroup " + fake.real("/sys/fs/cgroup/user.slice/memory.max"));
    }
    SUBCASE("a group using more than its limit leaves nothing") {
        fake.write(job + "memory.current", "1300000000\n");
        CHECK(cli::cgroupMemoryLeft(fake.files).bytes == 0);
    }
    SUBCASE("the message names the cgroup's file") {
        RenderSettings settings;
        settings.width = 3840, settings.height = 2160;
        try {
            cli::checkFrameMemory(settings, cli::cgroupMemoryLeft(fake.files));
            FAIL("a 3840 x 2160 frame passed in 0.8 GB");
        } catch (const std::runtime_error& e) {
            CHECK(contains(e.what(), "more than the 0.8 GB this process may use (cgroup " +
                                         fake.real(job + "memory.max") + ")"));
        }
    }
}

TEST_CASE("cgroup memory: v1's memory controller, hierarchical, beside an empty cgroup2") {
    const FakeCgroups fake(kV1Mounts,
                           "9:name=systemd:/\n4:memory:/process_api/34ae\n1:cpu:/\n0::/\n");
    const std::string group = "/sys/fs/cgroup/memory/process_api/34ae/";
    fake.write(group + "memory.limit_in_bytes", "9223372036854771712\n");  // v1's "no limit"
    fake.write(group + "memory.usage_in_bytes", "20000000\n");
    fake.write("/sys/fs/cgroup/memory/process_api/memory.limit_in_bytes", "2000000000\n");
    fake.write("/sys/fs/cgroup/memory/process_api/memory.usage_in_bytes", "600000000\n");
    fake.write("/sys/fs/cgroup/memory/process_api/memory.stat",
               "cache 1\ninactive_file 7\ntotal_inactive_file 100000000\n");
    fake.write("/sys/fs/cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");
    const cli::AvailableMemory left = cli::cgroupMemoryLeft(fake.files);
    CHECK(left.bytes == 2000000000 - (600000000 - 100000000));
    CHECK(left.source ==
          "cgroup " + fake.real("/sys/fs/cgroup/memory/process_api/memory.limit_in_bytes"));
}

TEST_CASE("cgroup memory: a container sees its own group as the mount's top") {
    // The mount's root is the container's group; /proc/self/cgroup names the same path.
    const FakeCgroups fake(
        "34 30 0:31 /docker/abc /sys/fs/cgroup rw,relatime - cgroup2 cgroup2 rw\n",
        "0::/docker/abc\n");
    fake.write("/sys/fs/cgroup/memory.max", "536870912\n");
    fake.write("/sys/fs/cgroup/memory.current", "36870912\n");
    const cli::AvailableMemory left = cli::cgroupMemoryLeft(fake.files);
    CHECK(left.bytes == 500000000);
    CHECK(left.source == "cgroup " + fake.real("/sys/fs/cgroup/memory.max"));
}

TEST_CASE("cgroup memory: no limit, no cgroup or nothing readable is unlimited") {
    const FakeCgroups unlimited(kV2Mounts, "0::/user.slice\n");
    unlimited.write("/sys/fs/cgroup/user.slice/memory.max", "max\n");
    unlimited.write("/sys/fs/cgroup/user.slice/memory.current", "5000\n");
    CHECK(cli::cgroupMemoryLeft(unlimited.files).bytes == kUnlimited);
    CHECK(cli::cgroupMemoryLeft(unlimited.files).source.empty());
    const FakeCgroups unmounted("22 1 0:20 / /proc rw,nosuid - proc proc rw\n", "0::/x\n");
    unmounted.write("/sys/fs/cgroup/x/memory.max", "1000\n");  // not a mount: never read
    CHECK(cli::cgroupMemoryLeft(unmounted.files).bytes == kUnlimited);
    cli::CgroupFiles missing;
    missing.mountinfo = missing.cgroup = "/nonexistent/ssrt-test";
    CHECK(cli::cgroupMemoryLeft(missing).bytes == kUnlimited);
}
