// The ssrt command: everything lives in runCli so tests can drive it without a process.
#include <iostream>

#include "cli/cli.h"
#include "cli/interrupt.h"

int main(int argc, char** argv) {
    // The process's own handlers: tests that call runCli in-process keep theirs.
    ssrt::cli::installInterruptHandlers();
    return ssrt::cli::runCli(argc, argv, std::cout, std::cerr);
}
