#include "io/exr_input.h"

#include <OpenEXR/openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "io/exr_channel_order.h"
#include "io/exr_imf_pixels.h"
#include "io/io_errors.h"

namespace ssrt::io_detail {

namespace {

// What OpenEXR's core library reads through (bytes in memory, or none for a file) and the
// first error it reported.
struct ExrSource {
    const uint8_t* bytes = nullptr;
    std::size_t size = 0;
    std::string error;
};

void keepFirstError(exr_const_context_t context, exr_result_t, const char* message) {
    void* user = nullptr;
    if (exr_get_user_data(context, &user) != EXR_ERR_SUCCESS || !user) return;
    std::string& error = static_cast<ExrSource*>(user)->error;
    if (error.empty()) error = message;
}

int64_t readExrMemory(exr_const_context_t, void* user, void* buffer, uint64_t size, uint64_t offset,
                      exr_stream_error_func_ptr_t) {
    const auto* in = static_cast<const ExrSource*>(user);
    if (offset >= in->size) return 0;
    const std::size_t n = std::size_t(std::min<uint64_t>(size, in->size - offset));
    std::memcpy(buffer, in->bytes + offset, n);
    return int64_t(n);
}

int64_t exrMemorySize(exr_const_context_t, void* user) {
    return int64_t(static_cast<const ExrSource*>(user)->size);
}

// Every chunk of pixels takes at least its offset-table entry (8 bytes) and its own row and
// size fields (8 more): a file shorter than that for its header's chunks is cut short, and is
// refused before a pixel is allocated at the claimed size (the fuzzer's 667-byte file claiming
// a large image).
constexpr std::int64_t kMinChunkBytes = 16;

// A core library context, finished when it goes: a member, so that a constructor that throws
// after opening it still finishes it.
struct ExrContext {
    exr_context_t context = nullptr;
    ExrContext() = default;
    ExrContext(const ExrContext&) = delete;
    ExrContext& operator=(const ExrContext&) = delete;
    ~ExrContext() { exr_finish(&context); }
};

struct ExrDecoder;

// Part 0 of an EXR file or of bytes, opened by the core library with its header checked:
// parsed without a reported error (a damaged attribute may be reported and skipped with
// success: any report counts), a size within io/image_limits.h's limits, and enough bytes for
// its chunks. The one place every reader here opens a file.
class ExrPart {
public:
    // `size` is the file's or the bytes' size; `source.bytes` is null for a file.
    ExrPart(const char* name, ExrSource source, std::int64_t size)
        : name_(name), source_(std::move(source)) {
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        init.error_handler_fn = keepFirstError;  // kept for the message, not printed
        init.user_data = &source_;
        if (source_.bytes) {
            init.read_fn = readExrMemory;
            init.size_fn = exrMemorySize;
        }
        int parts = 0;
        const bool parsed = exr_start_read(&context_, name, &init) == EXR_ERR_SUCCESS &&
                            source_.error.empty() &&
                            exr_get_count(context_, &parts) == EXR_ERR_SUCCESS && parts >= 1 &&
                            exr_get_data_window(context_, 0, &window_) == EXR_ERR_SUCCESS &&
                            exr_get_channels(context_, 0, &channels_) == EXR_ERR_SUCCESS &&
                            exr_get_chunk_count(context_, 0, &chunks_) == EXR_ERR_SUCCESS &&
                            exr_get_storage(context_, 0, &storage_) == EXR_ERR_SUCCESS;
        if (!parsed)
            failDecode("the header is damaged: " +
                       (source_.error.empty() ? std::string("unreadable") : source_.error));
        checkImageSize(width(), height(), channels_->num_channels);
        if (kMinChunkBytes * chunks_ > size)
            failDecode("the file is cut short: its " + std::to_string(width()) + " x " +
                       std::to_string(height()) + " pixels come in " + std::to_string(chunks_) +
                       " chunks, at least " + std::to_string(kMinChunkBytes * chunks_) +
                       " bytes, and the file has " + std::to_string(size));
    }
    ExrPart(const ExrPart&) = delete;
    ExrPart& operator=(const ExrPart&) = delete;

    // In 64 bits: a corrupt window may span more than an int (checkImageSize refuses it).
    std::int64_t width() const { return std::int64_t(window_.max.x) - window_.min.x + 1; }
    std::int64_t height() const { return std::int64_t(window_.max.y) - window_.min.y + 1; }

    // The channels' names in the file's order.
    std::vector<std::string> channelNames() const {
        std::vector<std::string> names;
        for (int i = 0; i < channels_->num_channels; ++i)
            names.emplace_back(channels_->entries[i].name.str,
                               std::size_t(channels_->entries[i].name.length));
        return names;
    }

    std::map<std::string, std::string> stringAttributes() const {
        std::map<std::string, std::string> out;
        int32_t count = 0;
        exr_get_attribute_count(context_, 0, &count);
        for (int32_t i = 0; i < count; ++i) {
            const exr_attribute_t* a = nullptr;
            if (exr_get_attribute_by_index(context_, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) ==
                    EXR_ERR_SUCCESS &&
                a->type == EXR_ATTR_STRING && a->string)
                out.emplace(a->name, std::string(a->string->str, std::size_t(a->string->length)));
        }
        return out;
    }

    DecodedImage pixels();

private:
    // The core library's first message, or its code's.
    [[noreturn]] void failChunk(int chunk, exr_result_t result) const {
        failDecode("chunk " + std::to_string(chunk) + " of " + std::to_string(chunks_) +
                   " cannot be read: " +
                   (source_.error.empty() ? std::string(exr_get_default_error_message(result))
                                          : source_.error));
    }
    void checkChannels() const;
    template <class Visit>
    void forEachChunk(Visit visit);
    void decodeChunk(ExrDecoder& decoding, int index, const exr_chunk_info_t& chunk, std::int64_t x,
                     std::int64_t y, const std::vector<int>& outputOf, DecodedImage& image);

    std::string name_;
    ExrSource source_;
    ExrContext owned_;
    exr_context_t& context_ = owned_.context;
    exr_attr_box2i_t window_{};
    const exr_attr_chlist_t* channels_ = nullptr;
    int32_t chunks_ = 0;
    exr_storage_t storage_ = EXR_STORAGE_SCANLINE;
};

// Every channel is one sample per pixel, of a type this reader converts.
void ExrPart::checkChannels() const {
    if (storage_ != EXR_STORAGE_SCANLINE && storage_ != EXR_STORAGE_TILED)
        failDecode("deep data (several samples per pixel) is not an image ssrt reads");
    for (int i = 0; i < channels_->num_channels; ++i) {
        const exr_attr_chlist_entry_t& c = channels_->entries[i];
        if (c.x_sampling != 1 || c.y_sampling != 1)
            failDecode("channel '" + std::string(c.name.str) + "' is subsampled (" +
                       std::to_string(c.x_sampling) + " x " + std::to_string(c.y_sampling) +
                       "): subsampled channels are not read");
    }
}

// The core library's decoding of one chunk after another, its buffers kept from chunk to chunk
// (made anew for each, they were a third of a large file's read: every one a fresh mapping).
struct ExrDecoder {
    exr_const_context_t context;
    exr_decode_pipeline_t pipeline = EXR_DECODE_PIPELINE_INITIALIZER;
    bool started = false;
    explicit ExrDecoder(exr_const_context_t c) : context(c) {}
    ExrDecoder(const ExrDecoder&) = delete;
    ExrDecoder& operator=(const ExrDecoder&) = delete;
    ~ExrDecoder() {
        if (started) exr_decoding_destroy(context, &pipeline);
    }
    // Set up for `chunk`: the first time, or again with the buffers kept.
    exr_result_t start(const exr_chunk_info_t& chunk) {
        if (started) return exr_decoding_update(context, 0, &chunk, &pipeline);
        started = true;
        return exr_decoding_initialize(context, 0, &chunk, &pipeline);
    }
};

// Decodes one chunk, whose first pixel is (x, y) of the image, into its place: channel i of
// the file becomes channel outputOf[i] of `image`, as float (unsigned integers as they are, for
// pixels() to scale).
void ExrPart::decodeChunk(ExrDecoder& decoding, int index, const exr_chunk_info_t& chunk,
                          std::int64_t x, std::int64_t y, const std::vector<int>& outputOf,
                          DecodedImage& image) {
    // The core library sizes chunks from the header; a chunk outside the image is a bug there,
    // which must not become a write outside the pixels.
    if (x < 0 || y < 0 || chunk.width < 0 || chunk.height < 0 || x + chunk.width > image.width ||
        y + chunk.height > image.height)
        failDecode("chunk " + std::to_string(index) + " lies outside the image");
    exr_decode_pipeline_t& decoder = decoding.pipeline;
    exr_result_t result = decoding.start(chunk);
    const std::size_t pixelBytes = sizeof(float) * std::size_t(image.channels);
    if (result == EXR_ERR_SUCCESS && decoder.channel_count != channels_->num_channels)
        result = EXR_ERR_INCORRECT_CHUNK;
    for (int i = 0; result == EXR_ERR_SUCCESS && i < decoder.channel_count; ++i) {
        exr_coding_channel_info_t& c = decoder.channels[i];
        float* first = image.f32.data() +
                       (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) *
                           std::size_t(image.channels) +
                       std::size_t(outputOf[std::size_t(i)]);
        c.decode_to_ptr = reinterpret_cast<uint8_t*>(first);
        c.user_pixel_stride = int32_t(pixelBytes);
        c.user_line_stride = int32_t(pixelBytes * std::size_t(image.width));
        c.user_bytes_per_element = 4;
        c.user_data_type = c.data_type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT : EXR_PIXEL_FLOAT;
    }
    if (result == EXR_ERR_SUCCESS)
        result = exr_decoding_choose_default_routines(context_, 0, &decoder);
    if (result == EXR_ERR_SUCCESS) result = exr_decoding_run(context_, 0, &decoder);
    if (result != EXR_ERR_SUCCESS) failChunk(index, result);
}

// 32-bit unsigned channels, decoded as they are into their float's place, scaled to [0, 1] as
// OpenImageIO converts them (its convert_type: float(u) * (1.0f / 4294967295.0f), in float).
void scaleUnsigned(const exr_attr_chlist_t& channels, const std::vector<int>& outputOf,
                   DecodedImage& image) {
    for (int i = 0; i < channels.num_channels; ++i) {
        if (channels.entries[i].pixel_type != EXR_PIXEL_UINT) continue;
        const std::size_t c = std::size_t(outputOf[std::size_t(i)]);
        for (std::size_t at = c; at < image.f32.size(); at += std::size_t(image.channels)) {
            uint32_t u = 0;
            std::memcpy(&u, &image.f32[at], sizeof u);
            image.f32[at] = float(u) * (1.0f / 4294967295.0f);
        }
    }
}

// Calls visit(index, chunk, x, y) for every chunk of level 0 in the file's order, (x, y) its
// first pixel in the image, each chunk's place in the file found by the core library (within
// the file, its size within the file), or DecodeFailure.
template <class Visit>
void ExrPart::forEachChunk(Visit visit) {
    if (storage_ == EXR_STORAGE_SCANLINE) {
        int32_t lines = 0;
        if (exr_get_scanlines_per_chunk(context_, 0, &lines) != EXR_ERR_SUCCESS || lines < 1)
            failDecode("the header is damaged: no scanlines per chunk");
        for (int i = 0; i < chunks_; ++i) {
            exr_chunk_info_t chunk{};
            const std::int64_t y = std::int64_t(i) * lines;
            const exr_result_t result =
                exr_read_scanline_chunk_info(context_, 0, int(window_.min.y + y), &chunk);
            if (result != EXR_ERR_SUCCESS) failChunk(i, result);
            visit(i, chunk, std::int64_t(chunk.start_x) - window_.min.x,
                  std::int64_t(chunk.start_y) - window_.min.y);
        }
        return;
    }
    uint32_t tileWidth = 0, tileHeight = 0;
    int32_t levelWidth = 0, levelHeight = 0;
    if (exr_get_tile_descriptor(context_, 0, &tileWidth, &tileHeight, nullptr, nullptr) !=
            EXR_ERR_SUCCESS ||
        exr_get_level_sizes(context_, 0, 0, 0, &levelWidth, &levelHeight) != EXR_ERR_SUCCESS ||
        tileWidth < 1 || tileHeight < 1 || levelWidth != width() || levelHeight != height())
        failDecode("the header is damaged: its tiles do not cover the image");
    const std::int64_t across = (levelWidth + std::int64_t(tileWidth) - 1) / tileWidth;
    const std::int64_t down = (levelHeight + std::int64_t(tileHeight) - 1) / tileHeight;
    int index = 0;
    for (int ty = 0; ty < down; ++ty)
        for (int tx = 0; tx < across; ++tx, ++index) {
            exr_chunk_info_t chunk{};
            const exr_result_t result = exr_read_tile_chunk_info(context_, 0, tx, ty, 0, 0, &chunk);
            if (result != EXR_ERR_SUCCESS) failChunk(index, result);
            visit(index, chunk, std::int64_t(tx) * tileWidth, std::int64_t(ty) * tileHeight);
        }
}

DecodedImage ExrPart::pixels() {
    checkChannels();
    DecodedImage image;
    const std::vector<std::string> fileOrder = channelNames();
    image.channelNames = exrChannelOrder(fileOrder);
    image.width = int(width());
    image.height = int(height());
    image.channels = int(image.channelNames.size());
    image.type = SampleType::F32;
    image.f32.resize(image.sampleCount());  // not zeroed: every chunk is written or we fail
    std::vector<int> outputOf(fileOrder.size());
    for (std::size_t i = 0; i < fileOrder.size(); ++i)
        outputOf[i] =
            int(std::find(image.channelNames.begin(), image.channelNames.end(), fileOrder[i]) -
                image.channelNames.begin());
    exr_compression_t compression = EXR_COMPRESSION_NONE;
    exr_get_compression(context_, 0, &compression);
    if (compression == EXR_COMPRESSION_DWAA || compression == EXR_COMPRESSION_DWAB) {
        forEachChunk([](int, const exr_chunk_info_t&, std::int64_t, std::int64_t) {});
        ExrHeaderFacts facts{window_.min.x,    window_.min.y,
                             window_.max.x,    window_.max.y,
                             int(compression), storage_ == EXR_STORAGE_TILED,
                             fileOrder,        {}};
        for (int i = 0; i < channels_->num_channels; ++i)
            facts.channelTypes.push_back(int(channels_->entries[i].pixel_type));
        readPixelsWithInputFile(name_, source_.bytes, source_.size, facts, outputOf, image);
    } else {
        ExrDecoder decoding(context_);
        forEachChunk([&](int index, const exr_chunk_info_t& chunk, std::int64_t x, std::int64_t y) {
            decodeChunk(decoding, index, chunk, x, y, outputOf, image);
        });
    }
    scaleUnsigned(*channels_, outputOf, image);
    return image;
}

}  // namespace

bool isExr(const uint8_t* bytes, std::size_t size) {
    return size >= 4 && bytes[0] == 0x76 && bytes[1] == 0x2f && bytes[2] == 0x31 &&
           bytes[3] == 0x01;
}

namespace {

// A file's part 0, or DecodeFailure.
template <class Read>
auto withFile(const std::string& path, Read read) {
    std::error_code error;
    const auto size = std::filesystem::file_size(path, error);
    if (error) failDecode("cannot open the file: " + error.message());
    ExrPart part(path.c_str(), ExrSource{}, std::int64_t(size));
    return read(part);
}

}  // namespace

DecodedImage readExr(const std::string& path) {
    return withFile(path, [](ExrPart& part) { return part.pixels(); });
}

DecodedImage readExr(const uint8_t* bytes, std::size_t size) {
    ExrPart part("memory.exr", ExrSource{bytes, size, {}}, std::int64_t(size));
    return part.pixels();
}

std::vector<std::string> readExrChannelNames(const std::string& path) {
    return withFile(path, [](ExrPart& part) { return exrChannelOrder(part.channelNames()); });
}

std::map<std::string, std::string> exrStringAttributes(const std::string& path) {
    return withFile(path, [](ExrPart& part) { return part.stringAttributes(); });
}

}  // namespace ssrt::io_detail
