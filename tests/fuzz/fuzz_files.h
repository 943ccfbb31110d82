// What the fuzz targets share: the parsers read files, so each input is written to a file in
// a folder of the process's own; inputs that hold several files split at a marker; and the
// command line run in-process, whose status must be one of ssrt's.
#pragma once

#include <oneapi/tbb/global_control.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "cli/cli.h"
#include "cli/command_line.h"

namespace ssrt::fuzz {

// A folder for this process's files (libFuzzer's -jobs run several processes): in memory
// (/dev/shm) where there is one, since creating and removing files on a disk's file system took
// a tenth of a merge_fuzz run; else /tmp.
inline const std::string& workDir() {
    static const std::string dir = [] {
        const char* root = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
        std::string d = std::string(root) + "/ssrt-fuzz-" + std::to_string(::getpid());
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

// Writes `bytes` to workDir()/name and returns the path.
inline std::string writeFile(const std::string& name, std::string_view bytes) {
    const std::string path = workDir() + "/" + name;
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(bytes.data(), 1, bytes.size(), f);
        std::fclose(f);
    } else {
        std::abort();  // the harness's own folder must be writable
    }
    return path;
}

// The input cut at every "\nSSRT-FUZZ-SPLIT\n" (the seeds put it between their files).
inline std::vector<std::string_view> splitInput(const uint8_t* data, std::size_t size) {
    constexpr std::string_view kMarker = "\nSSRT-FUZZ-SPLIT\n";
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    std::vector<std::string_view> pieces;
    for (std::size_t at; (at = rest.find(kMarker)) != std::string_view::npos;) {
        pieces.push_back(rest.substr(0, at));
        rest.remove_prefix(at + kMarker.size());
    }
    pieces.push_back(rest);
    return pieces;
}

// The lines of `text` that are ssrt's errors.
inline int errorLines(const std::string& text) {
    std::istringstream lines(text);
    int count = 0;
    for (std::string line; std::getline(lines, line);) count += line.rfind("ssrt: error: ", 0) == 0;
    return count;
}

// Runs `ssrt args...` in-process; any status but ssrt's own (0 to 3) is a bug, and so is an
// error that is not one line (cli/cli.h's contract).
inline int runSsrt(std::vector<std::string> args) {
    args.insert(args.begin(), "ssrt");
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    // One thread: a campaign is one process per core, and the passes' results do not depend
    // on the thread count (DESIGN.md), so TBB's workers would only spin beside it.
    static const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
    static cli::CommandLine line;  // built once: building it cost most of a short run
    line.reset();
    const int status = cli::runCli(line, int(argv.size()), argv.data(), out, err);
    if (status < cli::kExitOk || status > cli::kExitFailure) std::abort();
    if (status >= cli::kExitUsage && errorLines(err.str()) != 1) std::abort();
    return status;
}

}  // namespace ssrt::fuzz
