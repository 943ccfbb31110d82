#include "io/exr_channel_order.h"

#include <strings.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <string_view>

namespace ssrt::io_detail {

namespace {

// A channel's place in OpenImageIO's order: its layer (the name before the last '.'), its
// rank among the reserved names, then its suffix.
struct ChannelKey {
    std::string name, layer, suffix;
    int rank = 10000;
};

// OpenImageIO 2.4's reserved names in order (exrinput.cpp, compute_special_index), and the
// order it uses instead for a layer with X and Y or Z (positions, normals).
constexpr std::array<const char*, 20> kReserved = {
    "R",     "Red", "G",  "Green", "B",  "Blue", "Y",  "real", "imag",  "A",
    "Alpha", "AR",  "RA", "AG",    "GA", "AB",   "BA", "Z",    "Depth", "Zback"};
constexpr std::array<const char*, 21> kReservedXyz = {
    "R", "Red",   "G",  "Green", "B",  "Blue", "X",  "Y",  "Z",     "real", "imag",
    "A", "Alpha", "AR", "RA",    "AG", "GA",   "AB", "BA", "Depth", "Zback"};

bool sameName(std::string_view a, const char* b) {
    return a.size() == std::strlen(b) && ::strncasecmp(a.data(), b, a.size()) == 0;
}

template <std::size_t N>
int rankIn(const std::array<const char*, N>& names, std::string_view suffix) {
    for (std::size_t i = 0; i < N; ++i)
        if (sameName(suffix, names[i])) return int(i);
    return 10000;
}

bool layerHas(const std::vector<ChannelKey>& keys, std::size_t begin, std::size_t end,
              const char* suffix) {
    for (std::size_t i = begin; i < end; ++i)
        if (sameName(keys[i].suffix, suffix)) return true;
    return false;
}

}  // namespace

std::vector<std::string> exrChannelOrder(const std::vector<std::string>& names) {
    std::vector<ChannelKey> keys;
    for (const std::string& name : names) {
        const std::size_t dot = name.rfind('.');
        ChannelKey key{name, "", name};
        if (dot != std::string::npos)
            key.layer = name.substr(0, dot), key.suffix = name.substr(dot + 1);
        keys.push_back(std::move(key));
    }
    std::stable_sort(keys.begin(), keys.end(),
                     [](const ChannelKey& a, const ChannelKey& b) { return a.layer < b.layer; });
    for (std::size_t begin = 0; begin < keys.size();) {
        std::size_t end = begin + 1;
        while (end < keys.size() && keys[end].layer == keys[begin].layer) ++end;
        const bool xyz = layerHas(keys, begin, end, "X") &&
                         (layerHas(keys, begin, end, "Y") || layerHas(keys, begin, end, "Z"));
        for (std::size_t i = begin; i < end; ++i)
            keys[i].rank =
                xyz ? rankIn(kReservedXyz, keys[i].suffix) : rankIn(kReserved, keys[i].suffix);
        std::sort(keys.begin() + std::ptrdiff_t(begin), keys.begin() + std::ptrdiff_t(end),
                  [](const ChannelKey& a, const ChannelKey& b) {
                      return a.rank != b.rank ? a.rank < b.rank : a.suffix < b.suffix;
                  });
        begin = end;
    }
    std::vector<std::string> ordered;
    for (const ChannelKey& key : keys) ordered.push_back(key.name);
    return ordered;
}

}  // namespace ssrt::io_detail
