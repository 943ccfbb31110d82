// What a process pays around its frames, for `render --stats`' process table: main marks the
// moment it starts (and the CPU time the process had used by then: the dynamic loader's and
// the static initialisers'), the commands measure from there.
#pragma once

#include <chrono>
#include <optional>

namespace ssrt::cli {

struct ProcessStart {
    std::chrono::steady_clock::time_point wall;  // main's first line
    double cpuMsBeforeMain = 0.0;                // CPU time used before it, every thread's
};

// Called by main before anything else; a program that runs runCli inside itself (the tests,
// the fuzzers) does not, and its commands then have no process start to report.
void markProcessStart();
std::optional<ProcessStart> processStart();

// Minor page faults of the process so far (getrusage): the pages it touched for the first
// time, each a fault and a page the kernel zeroed.
long minorPageFaults();

}  // namespace ssrt::cli
