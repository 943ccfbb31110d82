#include "io/exr_input.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/openexr.h>
#include <strings.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "io/decoded_image.h"
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

namespace {

// What OpenEXR's core library reads through (bytes in memory, or none for a file) and the
// first error it reported.
struct ExrMemory {
    const uint8_t* bytes = nullptr;
    std::size_t size = 0;
    std::string error;
};

void keepFirstError(exr_const_context_t context, exr_result_t, const char* message) {
    void* user = nullptr;
    if (exr_get_user_data(context, &user) != EXR_ERR_SUCCESS || !user) return;
    std::string& error = static_cast<ExrMemory*>(user)->error;
    if (error.empty()) error = message;
}

int64_t readExrMemory(exr_const_context_t, void* user, void* buffer, uint64_t size, uint64_t offset,
                      exr_stream_error_func_ptr_t) {
    const auto* in = static_cast<const ExrMemory*>(user);
    if (offset >= in->size) return 0;
    const std::size_t n = std::size_t(std::min<uint64_t>(size, in->size - offset));
    std::memcpy(buffer, in->bytes + offset, n);
    return int64_t(n);
}

int64_t exrMemorySize(exr_const_context_t, void* user) {
    return int64_t(static_cast<const ExrMemory*>(user)->size);
}

// Every chunk of pixels takes at least its offset-table entry (8 bytes) and its own row and
// size fields (8 more): a file shorter than that for its header's chunks is cut short, and is
// refused before OpenEXR rebuilds its table and a pixel buffer is allocated at the claimed
// size (the fuzzer's 667-byte file claiming a large image took 40 s and gigabytes).
constexpr std::int64_t kMinChunkBytes = 16;

// checkExrSize's work; `name` is the file, or a name for bytes that `init` reads, `size` the
// bytes there are.
// A header the core library refuses is refused with its reason: OpenEXR's InputFile (3.1)
// reads some of those (a string attribute's size beyond the file, a channel sampled every
// 1.7e9 rows) and then spends seconds on them.
void checkExrHeader(const char* name, exr_context_initializer_t& init, std::int64_t size,
                    ExrMemory& memory) {
    init.error_handler_fn = keepFirstError;  // kept, not printed
    init.user_data = &memory;
    exr_context_t context = nullptr;
    exr_attr_box2i_t window{};
    const exr_attr_chlist_t* channels = nullptr;
    int32_t chunks = 0;
    int parts = 0;
    // (A damaged attribute may be reported and skipped with success: any report counts.)
    const bool parsed = exr_start_read(&context, name, &init) == EXR_ERR_SUCCESS &&
                        memory.error.empty() && exr_get_count(context, &parts) == EXR_ERR_SUCCESS &&
                        parts >= 1 && exr_get_data_window(context, 0, &window) == EXR_ERR_SUCCESS &&
                        exr_get_channels(context, 0, &channels) == EXR_ERR_SUCCESS &&
                        exr_get_chunk_count(context, 0, &chunks) == EXR_ERR_SUCCESS;
    const int channelCount = parsed ? channels->num_channels : 0;
    exr_finish(&context);
    if (!parsed)
        failDecode("the header is damaged: " +
                   (memory.error.empty() ? std::string("unreadable") : memory.error));
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    checkImageSize(width, height, channelCount);
    if (kMinChunkBytes * chunks > size)
        failDecode("the file is cut short: its " + std::to_string(width) + " x " +
                   std::to_string(height) + " pixels come in " + std::to_string(chunks) +
                   " chunks, at least " + std::to_string(kMinChunkBytes * chunks) +
                   " bytes, and the file has " + std::to_string(size));
}

}  // namespace

void checkExrSize(const std::string& path) {
    std::error_code error;
    const auto size = std::filesystem::file_size(path, error);
    if (error) return;  // InputFile says why it cannot be read
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    ExrMemory none;  // read from the file
    checkExrHeader(path.c_str(), init, std::int64_t(size), none);
}

void checkExrSize(const uint8_t* bytes, std::size_t size) {
    ExrMemory memory{bytes, size, {}};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.read_fn = readExrMemory;
    init.size_fn = exrMemorySize;
    checkExrHeader("memory.exr", init, std::int64_t(size), memory);
}

bool isExr(const uint8_t* bytes, std::size_t size) {
    return size >= 4 && bytes[0] == 0x76 && bytes[1] == 0x2f && bytes[2] == 0x31 &&
           bytes[3] == 0x01;
}

std::optional<DecodedImage> readExr(const std::string& path) {
    checkExrSize(path);
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        if (!readableAsFloat(header.channels())) return std::nullopt;
        const Imath::Box2i window = header.dataWindow();
        DecodedImage image;
        image.channelNames = channelOrder(header.channels());
        // In 64 bits: a corrupt window may span more than an int.
        checkImageSize(std::int64_t(window.max.x) - window.min.x + 1,
                       std::int64_t(window.max.y) - window.min.y + 1,
                       std::int64_t(image.channelNames.size()));
        image.width = window.max.x - window.min.x + 1;
        image.height = window.max.y - window.min.y + 1;
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
    checkExrSize(path);
    try {
        const Imf::InputFile file(path.c_str());
        return channelOrder(file.header().channels());
    } catch (const std::exception& e) {
        failDecode(e.what());
    }
}

}  // namespace ssrt::io_detail
