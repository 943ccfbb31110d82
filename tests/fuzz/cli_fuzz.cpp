// libFuzzer target for the command line: the input is the arguments, one per line, parsed as
// `ssrt` parses them (cli/command_line.h) and then checked as the command checks them before
// any work (flags, values, ranges, shards, the shot file a flag names), without rendering.
// Every input must end in a status of ssrt's with one error line, or pass.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/command_line.h"
#include "cli/sequence.h"
#include "cli/shard.h"
#include "fuzz_files.h"

namespace {

using namespace ssrt::cli;

// What each command checks before its work (the head of its run function).
void checkRenderOptions(const RenderOptions& o, const ssrt::RenderSettings& defaults) {
    const SceneRequest request = loadSceneRequest(o, defaults);
    sequencePlanFrom(o, request);
}

int check(const CommandLine& line) {
    switch (line.command()) {
        case Command::Render:
            checkRenderOptions(line.render, {});
            shardFrom(line.render.shard);
            if (line.render.compare) diffSettingsFrom(line.render.diff);
            break;
        case Command::Compare: checkRenderOptions(line.compare.render, truthDefaults()); break;
        case Command::Sweep:
            checkRenderOptions(line.sweep.render, truthDefaults());
            shardFrom(line.sweep.shard);
            break;
        case Command::Reference:
            checkRenderOptions(line.reference.render, truthDefaults());
            shardFrom(line.reference.shard);
            break;
        case Command::Graph: checkRenderOptions(line.graph.render, {}); break;
        case Command::Diff: diffSettingsFrom(line.diff.flags); break;
        case Command::Check:  // (its suite file is read when it runs: suite_fuzz.cpp)
        case Command::Merge:
        case Command::Scenes:
        case Command::Completion:
        case Command::Man: break;
    }
    return kExitOk;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<std::string> args = {"ssrt"};
    std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
    for (std::string arg; std::getline(lines, arg);) args.push_back(arg);
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    static CommandLine line;
    line.reset();
    std::optional<int> status = line.parse(int(argv.size()), argv.data(), out, err);
    if (!status) status = reportErrors(err, [&] { return check(line); });
    if (*status < kExitOk || *status > kExitFailure) std::abort();
    if (*status >= kExitUsage && ssrt::fuzz::errorLines(err.str()) != 1) std::abort();
    return 0;
}
