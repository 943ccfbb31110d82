// The thread counts a bit-identity case compares: those it names, unless the environment
// variable SSRT_TEST_THREADS narrows them for a run where the others prove nothing:
//   single    the first count only, for runs under an emulator (scripts/test-arm.sh, qemu-user):
//             its threads run on the host's cores, in the host's memory order, so more of them
//             prove nothing the native runs of the same cases do not, and each costs minutes;
//   parallel  the counts over 1 (the largest, if none is), for runs under ThreadSanitizer
//             (scripts/test-tsan.sh): one thread cannot race. A case's 1-thread reference,
//             made outside its loop, still runs.
// Any other value fails the case, so a typo cannot quietly drop runs.
#pragma once

#include <cstdlib>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

inline std::vector<int> testThreadCounts(std::initializer_list<int> named) {
    const std::vector<int> counts(named);
    const char* env = std::getenv("SSRT_TEST_THREADS");
    const std::string mode = env ? env : "";
    if (mode.empty()) return counts;
    if (mode == "single") return {counts.front()};
    if (mode == "parallel") {
        std::vector<int> over1;
        for (int t : counts)
            if (t > 1) over1.push_back(t);
        return over1.empty() ? std::vector<int>{counts.back()} : over1;
    }
    throw std::invalid_argument("SSRT_TEST_THREADS is '" + mode +
                                "': it may be empty, single or parallel");
}
