#include "io/exr_input.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <strings.h>

#include <algorithm>
#include <array>
#include <string_view>

#include "io/io_errors.h"

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

std::vector<std::string> channelOrder(const Imf::ChannelList& channels) {
    std::vector<ChannelKey> keys;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        const std::string name = it.name();
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
    std::vector<std::string> names;
    for (const ChannelKey& key : keys) names.push_back(key.name);
    return names;
}

// Whether OpenEXR's float conversion of every channel is OpenImageIO's (float and half: exact).
bool readableAsFloat(const Imf::ChannelList& channels) {
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        const Imf::Channel& c = it.channel();
        if (c.type == Imf::UINT || c.xSampling != 1 || c.ySampling != 1) return false;
    }
    return true;
}

}  // namespace

bool isExr(const uint8_t* bytes, std::size_t size) {
    return size >= 4 && bytes[0] == 0x76 && bytes[1] == 0x2f && bytes[2] == 0x31 &&
           bytes[3] == 0x01;
}

std::optional<DecodedImage> readExr(const std::string& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        if (!readableAsFloat(header.channels())) return std::nullopt;
        const Imath::Box2i window = header.dataWindow();
        DecodedImage image;
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
        image.channelNames = channelOrder(header.channels());
        image.channels = int(image.channelNames.size());
        image.type = SampleType::F32;
        image.f32.resize(image.sampleCount());
        const std::size_t pixelBytes = sizeof(float) * std::size_t(image.channels);
        Imf::FrameBuffer buffer;
        for (int c = 0; c < image.channels; ++c)
            buffer.insert(image.channelNames[std::size_t(c)],
                          Imf::Slice::Make(Imf::FLOAT, image.f32.data() + c, window, pixelBytes,
                                           pixelBytes * std::size_t(image.width)));
        file.setFrameBuffer(buffer);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const std::exception& e) {
        failDecode(e.what());
    }
}

std::vector<std::string> readExrChannelNames(const std::string& path) {
    try {
        const Imf::InputFile file(path.c_str());
        return channelOrder(file.header().channels());
    } catch (const std::exception& e) {
        failDecode(e.what());
    }
}

}  // namespace ssrt::io_detail
