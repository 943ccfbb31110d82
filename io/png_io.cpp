#include "io/png_io.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>
#include <thread>

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
// Writing: the chunks by hand, the pixels through zlib in bands of rows compressed side by
// side (as pigz does): each band its own raw deflate stream, ended by a sync flush (the last
// by the final block), the streams concatenated into one zlib stream. The bands are fixed
// (kBandRows), so the bytes do not depend on the thread count.

namespace {

constexpr int kBandRows = 64;

void putU32(std::vector<uint8_t>& out, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(v >> shift));
}

// A chunk: its length, type, data and the CRC of type and data.
void putChunk(std::vector<uint8_t>& out, const char (&type)[5], const uint8_t* data,
              std::size_t size) {
    putU32(out, uint32_t(size));
    const std::size_t at = out.size();
    out.insert(out.end(), type, type + 4);
    if (size > 0) out.insert(out.end(), data, data + size);
    putU32(out, uint32_t(crc32(0, out.data() + at, uInt(size + 4))));
}

// A tEXt chunk (keywords of 1 to 79 characters, as libpng checks them).
void putText(std::vector<uint8_t>& out, const std::string& path, const std::string& key,
             const std::string& value) {
    if (key.empty() || key.size() > 79 || key.find('\0') != std::string::npos)
        failWrite(path, "invalid PNG text keyword '" + key + "'");
    std::vector<uint8_t> data(key.begin(), key.end());
    data.push_back(0);
    data.insert(data.end(), value.begin(), value.end());
    putChunk(out, "tEXt", data.data(), data.size());
}

// One band of rows, filtered and deflated.
struct Band {
    std::vector<uint8_t> bytes;
    uLong adler = 1;
    std::size_t rawSize = 0;
    bool failed = false;
};

// A thread's buffers, reused band after band (a band keeps only its compressed bytes): the
// filtered rows, the deflated band, and the rows above and at y unfiltered.
struct BandBuffers {
    std::vector<uint8_t> raw, packed, above, row;
};

// Each row with PNG's Up filter (type 2: the byte above subtracted; the first row's "above" is
// zeros) and the band deflated with zlib's run-length strategy: on rendered images the pair is
// both smaller and faster to compress than no filter with the default strategy (1080p cornell
// at level 1, one thread: 0.78 MB in 60 ms against 1.18 MB in 69 ms; perf/README.md).
void compressBand(const PngRows& rows, int width, int y0, int y1, bool last, int level,
                  BandBuffers& b, Band& band) {
    const std::size_t bytes = std::size_t(width) * 3, line = bytes + 1;
    std::vector<uint8_t>& raw = b.raw;
    std::vector<uint8_t>& packed = b.packed;
    raw.resize(line * std::size_t(y1 - y0));
    b.above.assign(bytes, 0);
    b.row.resize(bytes);
    if (y0 > 0) rows(y0 - 1, b.above.data());
    for (int y = y0; y < y1; ++y) {
        uint8_t* r = raw.data() + line * std::size_t(y - y0);
        r[0] = 2;
        rows(y, b.row.data());
        const uint8_t *cur = b.row.data(), *up = b.above.data();
        for (std::size_t i = 0; i < bytes; ++i) r[1 + i] = uint8_t(cur[i] - up[i]);
        std::swap(b.row, b.above);
    }
    band.rawSize = raw.size();
    band.adler = adler32(1, raw.data(), uInt(raw.size()));
    z_stream z{};
    if (deflateInit2(&z, level, Z_DEFLATED, -15, 8, Z_RLE) != Z_OK) {
        band.failed = true;
        return;
    }
    packed.resize(deflateBound(&z, uLong(raw.size())) + 16);
    z.next_in = raw.data();
    z.avail_in = uInt(raw.size());
    z.next_out = packed.data();
    z.avail_out = uInt(packed.size());
    const int rc = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
    // (A sync flush that filled the buffer may hold more back: deflateBound says it cannot.)
    band.failed = last ? rc != Z_STREAM_END : (rc != Z_OK || z.avail_in != 0 || z.avail_out == 0);
    band.bytes.assign(packed.begin(), packed.begin() + std::ptrdiff_t(z.total_out));
    deflateEnd(&z);
}

}  // namespace

void writePngRgb8(const std::string& path, const std::string& file, int width, int height,
                  const PngRows& rows, int compressionLevel, const PngTexts& texts, int threads) {
    if (width <= 0 || height <= 0) failWrite(path, "the image is empty");
    std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    // IHDR: 8-bit RGB, deflate, filter method 0, not interlaced.
    std::vector<uint8_t> header;
    putU32(header, uint32_t(width));
    putU32(header, uint32_t(height));
    header.insert(header.end(), {8, 2, 0, 0, 0});
    putChunk(out, "IHDR", header.data(), header.size());
    // oFFs at 0, 0 in pixels (as OpenImageIO wrote it).
    const uint8_t offsets[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    putChunk(out, "oFFs", offsets, sizeof offsets);
    putText(out, path, "Software", "ssrt");
    for (const auto& [key, value] : texts) putText(out, path, key, value);

    const int bands = (height + kBandRows - 1) / kBandRows;
    std::vector<Band> done(static_cast<std::size_t>(bands));
    std::atomic<int> next{0};
    const auto work = [&] {
        BandBuffers buffers;
        for (int b = next++; b < bands; b = next++) try {
                compressBand(rows, width, b * kBandRows, std::min(height, (b + 1) * kBandRows),
                             b + 1 == bands, compressionLevel, buffers, done[std::size_t(b)]);
            } catch (...) {  // (out of memory: said below, on the calling thread)
                done[std::size_t(b)].failed = true;
            }
    };
    const int workers =
        std::clamp(threads > 0 ? threads : int(std::thread::hardware_concurrency()), 1, bands);
    {
        std::vector<std::jthread> pool;
        for (int i = 1; i < workers; ++i) pool.emplace_back(work);
        work();
    }
    // The zlib stream: its header (deflate, 32 KiB window, the level's flag), the bands, the
    // Adler-32 of every filtered row.
    const int level = compressionLevel < 0 ? 6 : compressionLevel;
    const int cmf = 0x78, flg = (level < 2 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3) << 6;
    std::vector<uint8_t> idat = {uint8_t(cmf), uint8_t(flg + (31 - (cmf * 256 + flg) % 31) % 31)};
    uLong adler = 1;
    for (const Band& b : done) {
        if (b.failed) failWrite(path, "zlib failed to compress the pixels");
        idat.insert(idat.end(), b.bytes.begin(), b.bytes.end());
        adler = adler32_combine(adler, b.adler, z_off_t(b.rawSize));
    }
    putU32(idat, uint32_t(adler));
    putChunk(out, "IDAT", idat.data(), idat.size());
    putChunk(out, "IEND", nullptr, 0);

    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (!f) failWrite(path, std::strerror(errno));
    const bool written = std::fwrite(out.data(), 1, out.size(), f) == out.size();
    // A full disk shows at the write, the flush or the close.
    const bool flushed = written && std::fflush(f) == 0 && !std::ferror(f);
    const int err = errno;
    const bool closed = std::fclose(f) == 0;
    if (!flushed || !closed) failWrite(path, std::strerror(err));
}

}  // namespace ssrt::io_detail
