#include "io/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <fcntl.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "core/color.h"
#include "io/exr_input.h"
#include "io/image_decode.h"
#include "io/io_errors.h"
#include "io/png_io.h"

namespace ssrt {

namespace fs = std::filesystem;

using io_detail::lowerExtension;

namespace {

// ---------------------------------------------------------------------------------------
// Paths and messages

std::string joinedExtensions() {
    std::string out;
    for (const std::string& ext : supportedImageExtensions())
        out += (out.empty() ? "" : ", ") + ext;
    return out;
}

using io_detail::failRead;
using io_detail::failWrite;

// Returns the lower-case extension, or throws if writeImage cannot write it.
std::string checkedExtension(const std::string& path) {
    const std::string ext = lowerExtension(path);
    const auto& known = supportedImageExtensions();
    if (std::find(known.begin(), known.end(), ext) == known.end()) {
        const std::string what =
            ext.empty() ? "has no extension" : "has an unsupported extension '" + ext + "'";
        throw std::invalid_argument("image file '" + path + "' " + what +
                                    " (supported: " + joinedExtensions() + ")");
    }
    return ext;
}

fs::path directoryOf(const std::string& path) {
    fs::path dir = fs::path(path).parent_path();
    return dir.empty() ? fs::path(".") : dir;
}

// The directory must exist and be a directory, and the target must not be a directory.
void checkDirectory(const std::string& path) {
    const fs::path dir = directoryOf(path);
    std::error_code ec;
    const fs::file_status status = fs::status(dir, ec);
    if (!fs::exists(status)) failWrite(path, "directory '" + dir.string() + "' does not exist");
    if (!fs::is_directory(status)) failWrite(path, "'" + dir.string() + "' is not a directory");
    if (fs::is_directory(fs::status(path, ec))) failWrite(path, "it is a directory");
}

// This machine's name as a file name may hold it (letters, digits, '-', '.'; others '_').
std::string hostTag() {
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) != 0) return "host";
    std::string tag(host);
    for (char& c : tag)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    return tag.empty() ? "host" : tag;
}

// A hidden name beside the target that keeps its extension (a reader may pick the format by
// it) and cannot collide with another writer in this or another process, on this machine or
// another sharing the folder (a cluster's shared cache: process ids repeat across nodes).
fs::path temporaryPathFor(const std::string& path, const std::string& ext) {
    static std::atomic<unsigned> counter{0};
    static const std::string host = hostTag();
    // Built with append: GCC 12 gives a false -Wrestrict for "." + std::string.
    std::string name(1, '.');
    name.append(fs::path(path).filename().string()).append(".tmp-").append(host).append("-");
    name.append(std::to_string(::getpid())).append("-").append(std::to_string(counter++));
    name.append(ext);
    return directoryOf(path) / name;
}

// ---------------------------------------------------------------------------------------
// Temporaries in flight, for removeTemporariesInFlight
//
// A signal handler may read this table at any moment, so it holds plain characters in fixed
// slots and lock-free atomics: no allocation, no lock. A slot's state goes free -> filling ->
// set (the path may be read) -> free; the handler claims a set slot (set -> claimed) before
// reading its path, so a writer that finishes at that moment never frees the slot under it.

constexpr int kInFlightSlots = 64;  // writes at once in one process (check's jobs, ...)
constexpr std::size_t kInFlightPathBytes = 4096;  // PATH_MAX
enum InFlightState : int { kFree, kFilling, kSet, kClaimed };
struct InFlightSlot {
    std::atomic<int> state{kFree};
    char path[kInFlightPathBytes];
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads these");
InFlightSlot gInFlight[kInFlightSlots];

// Registers a temporary's path for the lifetime of a write, before the file is created (a
// signal may come the instant it exists). A path too long for a slot, or a slot table that is
// full, goes unregistered: such a temporary is then removed by the write's own error path only.
class InFlight {
public:
    explicit InFlight(const fs::path& path) {
        const std::string& text = path.native();
        if (text.size() >= kInFlightPathBytes) return;
        for (int i = 0; i < kInFlightSlots && slot_ < 0; ++i) {
            int expected = kFree;
            if (!gInFlight[i].state.compare_exchange_strong(expected, kFilling)) continue;
            std::memcpy(gInFlight[i].path, text.c_str(), text.size() + 1);
            gInFlight[i].state.store(kSet, std::memory_order_release);
            slot_ = i;
        }
    }
    ~InFlight() {
        if (slot_ < 0) return;
        // A slot a handler claimed stays claimed: the process is ending.
        int expected = kSet;
        gInFlight[slot_].state.compare_exchange_strong(expected, kFree);
    }
    InFlight(const InFlight&) = delete;
    InFlight& operator=(const InFlight&) = delete;

private:
    int slot_ = -1;
};

// Creates the temporary file exclusively, so the reason a directory refuses us comes from the
// operating system itself (permissions, read-only file system, ...) rather than a guess.
void createTemporary(const std::string& path, const fs::path& tmp) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int err = errno;
        // (The OS's reason as it is: "No such file or directory" for a folder that is not
        // there, "Read-only file system", "Permission denied".)
        failWrite(path, "cannot create a file in '" + directoryOf(path).string() + "' (" +
                            std::strerror(err) + ")");
    }
    ::close(fd);
}

// Writes `tmp` (registered in flight, created, filled by `fill`) and renames it over `path`;
// on any failure the temporary is removed and the error passed on.
template <class Fill>
void writeThroughTemporary(const std::string& path, const std::string& ext, Fill&& fill) {
    const fs::path tmp = temporaryPathFor(path, ext);
    const InFlight inFlight(tmp);
    createTemporary(path, tmp);
    try {
        fill(tmp);
        // rename() within one directory replaces the target atomically: readers see the old
        // file or the new one, never a half-written one.
        std::error_code ec;
        fs::rename(tmp, path, ec);
        if (ec) failWrite(path, ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

// ---------------------------------------------------------------------------------------
// Frames

constexpr const char* kDisplayPlanes[] = {"display.R", "display.G", "display.B"};
constexpr const char* kDefaultColourChannels[] = {"R", "G", "B"};

const PlaneF* findPlane(const ImageLayers& image, std::string_view name) {
    for (const LayerRef& p : image.layers)
        if (p.name == name) return p.plane;
    return nullptr;
}

// Every plane must match the frame size and carry a unique, non-empty name; a PNG preview
// needs the display planes.
void checkFrame(const std::string& path, const ImageLayers& image, const std::string& ext) {
    const auto fail = [&](const std::string& why) {
        throw std::invalid_argument("cannot write '" + path + "': " + why);
    };
    if (image.width <= 0 || image.height <= 0) fail("the frame is empty");
    if (image.layers.empty()) fail("the frame has no planes");
    std::set<std::string_view> seen;
    for (const LayerRef& p : image.layers) {
        const std::string name(p.name);
        if (name.empty()) fail("a plane has no name");
        if (!seen.insert(p.name).second) fail("two planes are named '" + name + "'");
        if (p.plane->width() != image.width || p.plane->height() != image.height)
            fail("plane '" + name + "' is not the size of the frame");
    }
    if (ext != ".png") return;
    for (const char* name : kDisplayPlanes)
        if (!findPlane(image, name)) fail(std::string("the frame has no '") + name + "' plane");
}

// round(clamp(v, 0, 1) * 255), halves away from zero (std::lround's rounding, without the
// call); the comparisons are written so that NaN lands on 0. (x - int(x) is exact for
// 0 <= x < 2^23, so the comparison with 0.5 decides as lround does.)
uint8_t quantise(float v) {
    const float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    const float x = c * 255.0f;
    const int whole = int(x);
    return uint8_t(whole + (x - float(whole) >= 0.5f ? 1 : 0));
}

// quantise() over a row, 16 values at a time with SSE2 (every x86-64 has it; the compiler does
// not vectorise quantise's branches itself): the same steps in lanes, so the same bytes. maxps
// gives its second operand for NaN (0, as quantise's v > 0 test does) and for +-0; minps its
// first where it is below 1; the conversion truncates as int(x) does.
void quantiseRow(const float* src, uint8_t* dst, std::size_t n) {
    std::size_t x = 0;
#if defined(__SSE2__)
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
    const __m128 scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f);
    const auto four = [&](const float* p) {
        const __m128 v = _mm_mul_ps(_mm_min_ps(_mm_max_ps(_mm_loadu_ps(p), zero), one), scale);
        const __m128i whole = _mm_cvttps_epi32(v);
        const __m128 up = _mm_cmpge_ps(_mm_sub_ps(v, _mm_cvtepi32_ps(whole)), half);
        return _mm_sub_epi32(whole, _mm_castps_si128(up));  // (true is -1)
    };
    for (; x + 16 <= n; x += 16) {
        const __m128i lo = _mm_packs_epi32(four(src + x), four(src + x + 4));
        const __m128i hi = _mm_packs_epi32(four(src + x + 8), four(src + x + 12));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + x), _mm_packus_epi16(lo, hi));
    }
#endif
    for (; x < n; ++x) dst[x] = quantise(src[x]);
}

// ---------------------------------------------------------------------------------------
// Writers (into an already reserved temporary)

// zlib's fastest level: a preview written for a look, where libpng's default level 6
// spent about half a second on one 1920x1080 frame (as long as rendering it).
constexpr int kPngCompressionLevel = 1;

// 8-bit RGB from the display planes (io/png_io.h), quantised row by row as the bands are
// compressed, on the write's threads.
void writePng(const std::string& path, const fs::path& tmp, const ImageLayers& image,
              const WriteOptions& options) {
    const PlaneF* planes[3];
    for (int c = 0; c < 3; ++c) planes[c] = findPlane(image, kDisplayPlanes[c]);
    const std::size_t w = std::size_t(image.width);
    const auto row = [&](int y, uint8_t* rgb) {
        // Each plane's row quantised on its own (quantiseRow, in lanes), then interleaved:
        // quantising straight into every third byte, one value at a time, took 63
        // instructions a pixel, a third of the write's.
        thread_local std::vector<uint8_t> q;
        q.resize(3 * w);
        for (int c = 0; c < 3; ++c)
            quantiseRow(planes[c]->row(y), q.data() + std::size_t(c) * w, w);
        const uint8_t *r = q.data(), *g = r + w, *b = g + w;
        for (std::size_t x = 0; x < w; ++x)
            rgb[3 * x] = r[x], rgb[3 * x + 1] = g[x], rgb[3 * x + 2] = b[x];
    };
    io_detail::writePngRgb8(path, tmp.string(), image.width, image.height, row,
                            kPngCompressionLevel, image.attributes, options.threads);
}

// OpenEXR's compression for ours (all lossless).
Imf::Compression exrCompression(ExrCompression c) {
    switch (c) {
        case ExrCompression::None: return Imf::NO_COMPRESSION;
        case ExrCompression::Rle: return Imf::RLE_COMPRESSION;
        case ExrCompression::Zips: return Imf::ZIPS_COMPRESSION;
        case ExrCompression::Zip: return Imf::ZIP_COMPRESSION;
        case ExrCompression::Piz: return Imf::PIZ_COMPRESSION;
    }
    throw std::logic_error("unknown EXR compression");
}

// OpenEXR directly rather than through OpenImageIO: its frame buffer reads each plane where it
// lies (a slice per plane, with the plane's stride), so nothing is interleaved or copied, and
// one writePixels call over every row lets its thread pool compress blocks of rows in
// parallel (one scanline at a time, as OpenImageIO hands them over, cannot be).
void writeExr(const std::string& path, const fs::path& tmp, const ImageLayers& image,
              const WriteOptions& options) {
    Imf::Header header(image.width, image.height);
    header.compression() = exrCompression(options.compression);
    header.insert("software", Imf::StringAttribute("ssrt"));
    for (const auto& [name, value] : image.attributes)
        header.insert(name, Imf::StringAttribute(value));
    Imf::FrameBuffer buffer;
    const auto addChannel = [&](const std::string& name, const PlaneF& plane) {
        header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        // OpenEXR's slices take a non-const base; an output file only reads through it.
        char* base = reinterpret_cast<char*>(const_cast<float*>(plane.row(0)));
        buffer.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                       std::size_t(plane.stride()) * sizeof(float)));
    };
    for (const LayerRef& p : image.layers) addChannel(std::string(p.name), *p.plane);
    // The colour layer (a frame's color, else a reference's ref.color) once more as the
    // default channels R, G, B, which viewers and `oiiotool --stats` show when they are not
    // told a layer; readers that know the layers (io/image_compare.h) take these as the copy
    // they are, and a merge or copy that writes the layer again writes its copy with it.
    if (!findPlane(image, "R") && !findPlane(image, "G") && !findPlane(image, "B"))
        for (const std::string layer : {"color", "ref.color"}) {
            const PlaneF* colour[3] = {findPlane(image, layer + ".R"),
                                       findPlane(image, layer + ".G"),
                                       findPlane(image, layer + ".B")};
            if (!colour[0] || !colour[1] || !colour[2]) continue;
            for (int c = 0; c < 3; ++c) addChannel(kDefaultColourChannels[c], *colour[c]);
            break;
        }
    // The pool is OpenEXR's, process-wide; the file's own count is how many blocks of rows it
    // keeps in flight. Neither changes the bytes written.
    const int threads =
        options.threads > 0 ? options.threads : int(std::thread::hardware_concurrency());
    if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
    try {
        Imf::OutputFile file(tmp.c_str(), header, threads);
        file.setFrameBuffer(buffer);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        // OpenEXR names the temporary, which is removed: the line names the target alone.
        std::string why = e.what();
        const std::string named = " \"" + tmp.string() + "\"";
        for (std::size_t at; (at = why.find(named)) != std::string::npos;)
            why.erase(at, named.size());
        failWrite(path, why);
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Public

const std::vector<std::string>& supportedImageExtensions() {
    static const std::vector<std::string> kExtensions{".png", ".exr"};
    return kExtensions;
}

void checkWritable(const std::string& path) {
    const std::string ext = checkedExtension(path);
    checkDirectory(path);
    const fs::path probe = temporaryPathFor(path, ext);
    const InFlight inFlight(probe);
    createTemporary(path, probe);
    std::error_code ec;
    fs::remove(probe, ec);
}

bool isExrPath(const std::string& path) { return lowerExtension(path) == ".exr"; }

bool isPngPath(const std::string& path) { return lowerExtension(path) == ".png"; }

void checkPngOutput(const std::string& path, const std::string& what) {
    if (!isPngPath(path)) throw std::invalid_argument(what + " '" + path + "' must be a .png file");
    checkWritable(path);
}

void writeDisplayPng(const std::string& path, const PlaneF& r, const PlaneF& g, const PlaneF& b) {
    writeImage(path, ImageLayers{r.width(),
                                 r.height(),
                                 {{"display.R", &r}, {"display.G", &g}, {"display.B", &b}}});
}

void writeImage(const std::string& path, const ImageLayers& image, const WriteOptions& options) {
    const std::string ext = checkedExtension(path);
    checkFrame(path, image, ext);
    checkDirectory(path);
    writeThroughTemporary(path, ext, [&](const fs::path& tmp) {
        if (ext == ".png") writePng(path, tmp, image, options);
        else writeExr(path, tmp, image, options);
    });
}

void writeTextWhole(const std::string& path, const std::string& text) {
    checkDirectory(path);
    writeThroughTemporary(path, lowerExtension(path), [&](const fs::path& tmp) {
        errno = 0;
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        const int err = errno;  // (the stream keeps no reason; the failed write's errno is it)
        if (!out) failWrite(path, err ? std::strerror(err) : "the write failed");
        out.close();
        if (!out) failWrite(path, std::strerror(errno));
    });
}

void removeTemporariesInFlight() noexcept {
    for (InFlightSlot& slot : gInFlight) {
        int expected = kSet;
        if (slot.state.compare_exchange_strong(expected, kClaimed, std::memory_order_acquire))
            ::unlink(slot.path);
    }
}

namespace {

// The channel called `name`, or -1.
int channelIndex(const std::vector<std::string>& names, const char* name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
}

}  // namespace

InterleavedImage readSkyImage(const std::string& path) {
    const io_detail::FloatImage in = io_detail::readFloatImage(path);
    const int w = in.width, h = in.height, n = in.channels;
    // Which file channel feeds R, G and B.
    int src[3] = {0, 0, 0};
    const int r = channelIndex(in.names, "R"), g = channelIndex(in.names, "G"),
              b = channelIndex(in.names, "B");
    if (r >= 0 && g >= 0 && b >= 0) src[0] = r, src[1] = g, src[2] = b;
    else if (n >= 3) src[0] = 0, src[1] = 1, src[2] = 2;
    InterleavedImage img{w, h, 3, std::vector<float>(std::size_t(3) * w * h)};
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i)
        for (int c = 0; c < 3; ++c) {
            float v = in.values[i * n + src[c]];
            if (!std::isfinite(v))
                failRead(path, "texel (" + std::to_string(i % w) + ", " + std::to_string(i / w) +
                                   ") is not finite");
            if (in.srgb) v = srgbToLinear(std::clamp(v, 0.0f, 1.0f));  // the project's own pow
            img.pixels[i * 3 + c] = v > 0.0f ? v : 0.0f;
        }
    return img;
}

std::map<std::string, std::string> readExrStringAttributes(const std::string& path) {
    try {
        return io_detail::exrStringAttributes(path);
    } catch (const io_detail::DecodeFailure& e) {
        failRead(path, e.what());
    }
}

std::map<std::string, std::string> readImageAttributes(const std::string& path) {
    if (isExrPath(path)) return readExrStringAttributes(path);
    if (!isPngPath(path)) failRead(path, "only EXR and PNG files hold attributes here");
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    if (!in && !in.eof()) failRead(path, "cannot read the file");
    std::map<std::string, std::string> out;
    try {
        for (const auto& [key, value] : io_detail::readPngTexts(bytes.data(), bytes.size()))
            out[key] = value;
    } catch (const std::exception& e) {
        failRead(path, e.what());
    }
    return out;
}

void copyImageWithAttributes(const std::string& from, const std::string& to,
                             const std::vector<std::pair<std::string, std::string>>& attributes) {
    if (lowerExtension(from) != lowerExtension(to))
        throw std::invalid_argument("cannot copy '" + from + "' to '" + to + "': formats differ");
    const bool png = isPngPath(to);
    const std::vector<std::string> names =
        png ? std::vector<std::string>{"R", "G", "B"} : readChannelNames(from);
    int w = 0, h = 0;
    const std::vector<std::vector<float>> values = readChannels(from, names, w, h);
    std::vector<PlaneF> planes;
    planes.reserve(names.size());
    ImageLayers image{w, h, {}, attributes};
    for (std::size_t i = 0; i < names.size(); ++i) {
        planes.emplace_back(w, h);
        for (int y = 0; y < h; ++y)
            std::copy_n(values[i].data() + std::size_t(y) * w, w, planes[i].row(y));
    }
    // A PNG is written from display planes (its values already display values).
    static const std::string kDisplay[3] = {"display.R", "display.G", "display.B"};
    for (std::size_t i = 0; i < names.size(); ++i)
        image.layers.push_back({png ? kDisplay[i] : names[i], &planes[i]});
    // ZIP: lossless and the smallest for renders (a reference is kept, often in git).
    WriteOptions options;
    options.compression = ExrCompression::Zip;
    writeImage(to, image, options);
}

std::vector<std::string> readChannelNames(const std::string& path) {
    return io_detail::imageChannelNames(path);
}

std::vector<float> readChannel(const std::string& path, const std::string& channel, int& width,
                               int& height) {
    return std::move(readChannels(path, {channel}, width, height).front());
}

std::vector<std::vector<float>> readChannels(const std::string& path,
                                             const std::vector<std::string>& channels, int& width,
                                             int& height) {
    const io_detail::FloatImage in = io_detail::readFloatImage(path);
    std::vector<std::size_t> index;
    for (const std::string& channel : channels) {
        const auto it = std::find(in.names.begin(), in.names.end(), channel);
        if (it == in.names.end()) failRead(path, "it has no channel '" + channel + "'");
        index.push_back(std::size_t(it - in.names.begin()));
    }
    const std::size_t pixels = std::size_t(in.width) * in.height;
    const std::size_t n = std::size_t(in.channels);
    std::vector<std::vector<float>> out(channels.size(), std::vector<float>(pixels));
    for (std::size_t k = 0; k < channels.size(); ++k)
        for (std::size_t p = 0; p < pixels; ++p) out[k][p] = in.values[p * n + index[k]];
    width = in.width;
    height = in.height;
    return out;
}

}  // namespace ssrt
