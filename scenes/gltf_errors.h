// The glTF readers' error helpers, shared by the extension decoders (draco, meshopt) and the
// texture reader: one definition, so that a unity build, which compiles several sources as
// one, meets each once.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace ssrt::gltf {

// Every glTF reading error is a std::runtime_error; the loader adds the file's name.
[[noreturn]] inline void fail(const std::string& problem) { throw std::runtime_error(problem); }

inline std::string str(std::size_t n) { return std::to_string(n); }

}  // namespace ssrt::gltf
