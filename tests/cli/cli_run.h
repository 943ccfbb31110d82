// Runs the ssrt command in-process for the CLI tests: exit status, stdout and stderr.
#pragma once

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"

namespace ssrt::test {

struct CliResult {
    int code = -1;
    std::string out, err;
};

// `args` without the program name.
inline CliResult runSsrt(std::vector<std::string> args) {
    args.insert(args.begin(), "ssrt");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    CliResult r;
    r.code = cli::runCli(int(argv.size()), argv.data(), out, err);
    r.out = out.str();
    r.err = err.str();
    return r;
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Exactly one line, starting "ssrt: error: ".
inline bool isOneErrorLine(const std::string& err) {
    return err.rfind("ssrt: error: ", 0) == 0 && std::count(err.begin(), err.end(), '\n') == 1 &&
           err.back() == '\n';
}

}  // namespace ssrt::test
