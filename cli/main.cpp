// The ssrt command: everything lives in runCli so tests can drive it without a process.
#include <cstdio>
#include <iostream>
#include <new>

#include "cli/cli.h"
#include "cli/interrupt.h"
#include "cli/process_clock.h"

int main(int argc, char** argv) {
    ssrt::cli::markProcessStart();  // (render --stats: what the process paid before its frames)
    // The process's own handlers: tests that call runCli in-process keep theirs.
    ssrt::cli::installInterruptHandlers();
    try {
        return ssrt::cli::runCli(argc, argv, std::cout, std::cerr);
    } catch (const std::bad_alloc&) {
        // Out of memory outside a command's own handler (reading the command line): one line
        // that allocates nothing, the status of the other resource errors.
        std::fputs("ssrt: error: out of memory\n", stderr);
        return ssrt::cli::kExitFailure;
    }
}
