// Runs the ssrt command in-process for the CLI tests: exit status, stdout and stderr.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "text_files.h"

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

inline std::vector<std::string> textLines(const std::string& text) {
    std::vector<std::string> out;
    std::string line;
    std::istringstream in(text);
    while (std::getline(in, line)) out.push_back(line);
    return out;
}

// A CSV line's cells (no quoting: the tests' CSVs have none), a trailing empty cell kept.
inline std::vector<std::string> csvCells(const std::string& line) {
    std::vector<std::string> out;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, ',')) out.push_back(cell);
    if (!line.empty() && line.back() == ',') out.push_back("");
    return out;
}

// Sets an environment variable (or unsets it: null) for one scope and restores the old value.
struct ScopedEnv {
    std::string name;
    std::optional<std::string> old;
    ScopedEnv(const std::string& n, const char* value) : name(n) {
        if (const char* v = std::getenv(n.c_str())) old = v;
        if (value) ::setenv(n.c_str(), value, 1);
        else ::unsetenv(n.c_str());
    }
    ~ScopedEnv() {
        if (old) ::setenv(name.c_str(), old->c_str(), 1);
        else ::unsetenv(name.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;
};

}  // namespace ssrt::test
