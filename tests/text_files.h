// Whole files as strings, for tests that write inputs and compare outputs byte for byte.
#pragma once

#include <fstream>
#include <iterator>
#include <string>

namespace ssrt::test {

inline void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// The file's bytes (empty if it cannot be read).
inline std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace ssrt::test
