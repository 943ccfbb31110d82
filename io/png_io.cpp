#include "io/png_io.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>

#include "io/io_errors.h"

namespace ssrt::io_detail {

namespace {

// ---------------------------------------------------------------------------------------
// libpng's errors: the text is kept, then libpng longjmps back to the setjmp of the
// function that called it (each such function below holds only plain data).

struct PngErrorText {
    char text[200] = "PNG library error";
};

void onPngError(png_structp png, png_const_charp message) {
    auto* error = static_cast<PngErrorText*>(png_get_error_ptr(png));
    std::snprintf(error->text, sizeof error->text, "%s", message);
    png_longjmp(png, 1);
}

// Warnings are not errors, and OpenImageIO ignores them too, with one exception. libpng
// 1.6.39 only warns of a chunk longer than the chunk limit (startRead's, over anything the file
// holds), then allocates and zeroes the buffer for it anyway, and fails only when the file
// ends: that warning is an error here, said before the allocation.
void onPngWarning(png_structp png, png_const_charp message) {
    constexpr std::string_view kTooLarge = "chunk data is too large";
    const std::string_view text = message;
    if (text.size() < kTooLarge.size() || text.substr(text.size() - kTooLarge.size()) != kTooLarge)
        return;
    // (Plain data only from here: png_longjmp skips destructors.)
    auto* error = static_cast<PngErrorText*>(png_get_error_ptr(png));
    std::snprintf(error->text, sizeof error->text, "%s: longer than the file", message);
    png_longjmp(png, 1);
}

// Bytes in memory, read by libpng in pieces.
struct MemoryReader {
    const uint8_t* bytes;
    std::size_t size, offset;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
    auto* in = static_cast<MemoryReader*>(png_get_io_ptr(png));
    if (length > in->size - in->offset) png_error(png, "the file is truncated");
    std::memcpy(out, in->bytes + in->offset, length);
    in->offset += length;
}

// The header, with OpenImageIO's transformations: palette to RGB, grey below 8 bits to 8,
// tRNS to alpha, 16-bit samples little-endian; interlaced images deinterlaced.
bool readHeader(png_structp png, png_infop info) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_info(png, info);
    png_set_expand(png);
    png_set_swap(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    return true;
}

// The rows. png_read_end is not called: OpenImageIO never reads past the last row, so a file
// with a damaged chunk after its pixels loads there and must load here.
bool readRows(png_structp png, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    return true;
}

// Owns libpng's read state.
struct PngRead {
    png_structp png = nullptr;
    png_infop info = nullptr;
    PngErrorText error;
    ~PngRead() { png_destroy_read_struct(&png, info ? &info : nullptr, nullptr); }
};

// OpenImageIO's colour space for a PNG: sRGB with an sRGB chunk or without gamma, else the
// gamma (rounded to hundredths) that its alpha association uses.
void readColourSpace(png_structp png, png_infop info, bool& srgb, float& gamma) {
    int intent = 0;
    double fileGamma = 0.0;
    srgb = true;
    gamma = 1.0f;
    if (png_get_sRGB(png, info, &intent)) return;
    if (png_get_gAMA(png, info, &fileGamma) && fileGamma > 0.0) {
        srgb = false;
        gamma = std::round(100.0f * float(1.0 / fileGamma)) / 100.0f;
    }
}

// OpenImageIO 2.4's png_associateAlpha, operation for operation (its results are the
// reference: integer rounding down, and pow in float for a gamma other than 1).
template <class T>
void associateAlpha(T* data, std::size_t pixels, int channels, int alphaChannel, float gamma) {
    const T max = std::numeric_limits<T>::max();
    const float invMax = float(1.0 / max);
    for (std::size_t x = 0; x < pixels; ++x, data += channels) {
        const float alpha = gamma == 1.0f ? 0.0f : std::pow(data[alphaChannel] * invMax, gamma);
        for (int c = 0; c < channels; ++c) {
            if (c == alphaChannel) continue;
            if (gamma == 1.0f) data[c] = T((unsigned(data[c]) * data[alphaChannel]) / max);
            else data[c] = static_cast<T>(data[c] * alpha);
        }
    }
}

// The header alone (the texts before the pixels are in it).
bool readInfo(png_structp png, png_infop info) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_info(png, info);
    return true;
}

// libpng's read and info structs in `r`, reading from `reader` (which outlives them).
void startRead(PngRead& r, MemoryReader& reader) {
    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r.error, onPngError, onPngWarning);
    if (r.png) r.info = png_create_info_struct(r.png);
    if (!r.info) failDecode("out of memory");
    png_set_read_fn(r.png, &reader, readFromMemory);
    // A chunk's data is read into a buffer libpng allocates and zeroes at the length the chunk
    // claims, before reading it. Over the chunk limit libpng only warns (onPngWarning makes that
    // an error: a 608-byte file claiming a 1.8 GB text chunk took 8.5 s and 2 GB), and the
    // limit Debian's libpng is built with is 8,000,000 bytes whatever the file's size. No chunk
    // holds more than the file does; compressed text (which ssrt does not read) may inflate to
    // more, so the limit is four times the file, and 1 MiB at least. Image data has libpng's own
    // limit, from the image's size.
    png_set_chunk_malloc_max(r.png, std::max<png_alloc_size_t>(4 * png_alloc_size_t(reader.size),
                                                               png_alloc_size_t(1) << 20));
}

}  // namespace

PngTexts readPngTexts(const uint8_t* bytes, std::size_t size) {
    PngRead r;
    MemoryReader reader{bytes, size, 0};
    startRead(r, reader);
    if (!readInfo(r.png, r.info)) failDecode(r.error.text);
    png_textp texts = nullptr;
    const int n = png_get_text(r.png, r.info, &texts, nullptr);
    PngTexts out;
    for (int i = 0; i < n; ++i) out.emplace_back(texts[i].key, texts[i].text ? texts[i].text : "");
    return out;
}

bool isPng(const uint8_t* bytes, std::size_t size) {
    return size >= 8 && png_sig_cmp(bytes, 0, 8) == 0;
}

DecodedImage decodePng(const uint8_t* bytes, std::size_t size, AlphaMode alpha) {
    PngRead r;
    MemoryReader reader{bytes, size, 0};
    startRead(r, reader);
    if (!readHeader(r.png, r.info)) failDecode(r.error.text);

    checkImageSize(png_get_image_width(r.png, r.info), png_get_image_height(r.png, r.info),
                   png_get_channels(r.png, r.info));
    DecodedImage image;
    image.width = int(png_get_image_width(r.png, r.info));
    image.height = int(png_get_image_height(r.png, r.info));
    image.channels = png_get_channels(r.png, r.info);
    image.channelNames = defaultChannelNames(image.channels);
    if (image.channels == 2) image.channelNames = {"Y", "A"};  // PNG's grey and alpha
    const bool wide = png_get_bit_depth(r.png, r.info) == 16;
    image.type = wide ? SampleType::U16 : SampleType::U8;
    float gamma = 1.0f;
    readColourSpace(r.png, r.info, image.srgb, gamma);

    const std::size_t rowBytes = png_get_rowbytes(r.png, r.info);
    uint8_t* pixels = nullptr;
    if (wide) image.u16.resize(image.sampleCount());
    else image.u8.resize(image.sampleCount());
    pixels = wide ? reinterpret_cast<uint8_t*>(image.u16.data()) : image.u8.data();
    std::vector<png_bytep> rows(std::size_t(image.height));
    for (int y = 0; y < image.height; ++y) rows[y] = pixels + std::size_t(y) * rowBytes;
    if (!readRows(r.png, rows.data())) failDecode(r.error.text);

    const int alphaChannel = image.channels == 2 ? 1 : image.channels == 4 ? 3 : -1;
    if (alphaChannel >= 0 && alpha == AlphaMode::Associated) {
        const std::size_t count = std::size_t(image.width) * image.height;
        if (wide) associateAlpha(image.u16.data(), count, image.channels, alphaChannel, gamma);
        else associateAlpha(image.u8.data(), count, image.channels, alphaChannel, gamma);
    }
    return image;
}

// ---------------------------------------------------------------------------------------
// Writing

namespace {

// Owns libpng's write state.
struct PngWrite {
    png_structp png = nullptr;
    png_infop info = nullptr;
    PngErrorText error;
    ~PngWrite() { png_destroy_write_struct(&png, info ? &info : nullptr); }
};

// OpenImageIO 2.4's PNG writer's calls, in its order, for 8-bit RGB and its default settings.
bool writeRgb8(png_structp png, png_infop info, std::FILE* file, png_uint_32 width,
               png_uint_32 height, png_bytepp rows, int level, png_textp more, int moreCount) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_compression_level(png, level);
    png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
    png_set_filter(png, 0, PNG_NO_FILTERS);
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
    char key[] = "Software", value[] = "ssrt";
    png_text text{};
    text.compression = PNG_TEXT_COMPRESSION_NONE;
    text.key = key;
    text.text = value;
    png_set_text(png, info, &text, 1);
    if (moreCount > 0) png_set_text(png, info, more, moreCount);
    png_write_info(png, info);
    for (png_uint_32 y = 0; y < height; ++y) png_write_row(png, rows[y]);
    png_write_end(png, info);
    return true;
}

}  // namespace

void writePngRgb8(const std::string& path, const std::string& file, int width, int height,
                  const std::vector<uint8_t>& rgb, int compressionLevel, const PngTexts& texts) {
    // libpng takes the texts by pointer; these strings outlive the write.
    std::vector<std::string> keys, values;
    for (const auto& [key, value] : texts) keys.push_back(key), values.push_back(value);
    std::vector<png_text> more(texts.size());
    for (std::size_t i = 0; i < texts.size(); ++i) {
        more[i].compression = PNG_TEXT_COMPRESSION_NONE;
        more[i].key = keys[i].data();
        more[i].text = values[i].data();
    }
    PngWrite w;
    w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w.error, onPngError, onPngWarning);
    if (w.png) w.info = png_create_info_struct(w.png);
    if (!w.info) failWrite(path, "out of memory");
    std::vector<png_bytep> rows(static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        rows[y] = const_cast<png_bytep>(rgb.data() + std::size_t(y) * width * 3);
    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (!out) failWrite(path, std::strerror(errno));
    const bool ok = writeRgb8(w.png, w.info, out, png_uint_32(width), png_uint_32(height),
                              rows.data(), compressionLevel, more.data(), int(more.size()));
    // A full disk shows at the flush or the close, not in libpng.
    const bool flushed = std::fflush(out) == 0 && !std::ferror(out);
    const int err = errno;
    const bool closed = std::fclose(out) == 0;
    if (!ok) failWrite(path, w.error.text);
    if (!flushed || !closed) failWrite(path, std::strerror(err));
}

}  // namespace ssrt::io_detail
