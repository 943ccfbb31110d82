// The ssrt command: everything lives in runCli so tests can drive it without a process.
#include <iostream>

#include "cli/cli.h"

int main(int argc, char** argv) { return ssrt::cli::runCli(argc, argv, std::cout, std::cerr); }
