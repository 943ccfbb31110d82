// libFuzzer target for `ssrt merge`: the input is a shard's parts (split by fuzz_files.h's
// marker), written as NAME.shard-K-of-N.csv or .exr (the first byte picks which) and merged.
// Every input must end in a status of ssrt's with one error line or a merged file; and a
// refused merge must write nothing.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const std::string ext = data[0] & 1 ? ".exr" : ".csv";
    const std::vector<std::string_view> pieces = ssrt::fuzz::splitInput(data + 1, size - 1);
    const int n = int(pieces.size());
    std::vector<std::string> args = {"merge", "--quiet", "-o",
                                     ssrt::fuzz::workDir() + "/merged" + ext};
    for (int k = 0; k < n; ++k)
        args.push_back(ssrt::fuzz::writeFile(
            "part.shard-" + std::to_string(k + 1) + "-of-" + std::to_string(n) + ext, pieces[k]));
    std::filesystem::remove(args[3]);
    const int status = ssrt::fuzz::runSsrt(args);
    if (status != 0 && std::filesystem::exists(args[3])) std::abort();  // nothing half-written
    for (int k = 0; k < n; ++k) std::filesystem::remove(args[4 + k]);
    return 0;
}
