#include "cli/process_clock.h"

#include <sys/resource.h>

#include <ctime>

namespace ssrt::cli {

namespace {

std::optional<ProcessStart> gStart;

}  // namespace

void markProcessStart() {
    timespec cpu{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
    gStart = ProcessStart{std::chrono::steady_clock::now(),
                          double(cpu.tv_sec) * 1e3 + double(cpu.tv_nsec) * 1e-6};
}

std::optional<ProcessStart> processStart() { return gStart; }

long minorPageFaults() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}

}  // namespace ssrt::cli
