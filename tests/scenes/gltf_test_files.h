// Writing glTF test files (base64 for data URIs, the GLB container, whole files) and checking
// that the loader refuses one.
#pragma once

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "scenes/gltf_loader.h"
#include "text_files.h"

namespace ssrt::test {

inline std::string base64(const std::vector<unsigned char>& in) {
    static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < in.size(); i += 3) {
        const uint32_t n = in[i] << 16 | (i + 1 < in.size() ? in[i + 1] << 8 : 0) |
                           (i + 2 < in.size() ? in[i + 2] : 0);
        out += abc[n >> 18 & 63];
        out += abc[n >> 12 & 63];
        out += i + 1 < in.size() ? abc[n >> 6 & 63] : '=';
        out += i + 2 < in.size() ? abc[n & 63] : '=';
    }
    return out;
}

inline std::string dataUri(const std::vector<unsigned char>& bytes) {
    return "data:application/octet-stream;base64," + base64(bytes);
}

inline void appendU32(std::string& s, uint32_t v) {
    s.append(reinterpret_cast<const char*>(&v), 4);
}

// GLB (glTF 2.0 section 4.4): a 12-byte header, then a JSON chunk padded with spaces and a
// BIN chunk padded with zeros.
inline std::string glbOf(std::string json, std::vector<unsigned char> bin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin.push_back(0);
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    appendU32(out, uint32_t(json.size()));
    appendU32(out, 0x4E4F534A);  // "JSON"
    out += json;
    appendU32(out, uint32_t(bin.size()));
    appendU32(out, 0x004E4942);  // "BIN\0"
    out.append(bin.begin(), bin.end());
    return out;
}

// A file of Debian's assimp-testmodels (its path under /usr/share/assimp/models/glTF2), or ""
// with a message saying the test is skipped when the package is not installed.
inline std::string assimpModel(const std::string& relative) {
    const std::string path = "/usr/share/assimp/models/glTF2/" + relative;
    if (std::ifstream(path).good()) return path;
    MESSAGE("skipped: assimp-testmodels is not installed (" << path << ")");
    return {};
}

// The loader's message for a file it must refuse (a test failure when it loads).
inline std::string loadError(const std::string& path) {
    try {
        loadGltf(path);
    } catch (const SceneLoadError& e) {
        return e.what();
    }
    FAIL("no SceneLoadError for " << path);
    return {};
}

// Refused with one line that names the file and holds `keyword`.
inline void checkRefused(const std::string& path, const std::string& keyword) {
    const std::string msg = loadError(path);
    INFO(msg);
    CHECK(msg.find(path) != std::string::npos);
    CHECK(msg.find(keyword) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
}

}  // namespace ssrt::test
