#include "io/texture_io.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/color.h"
#include "io/image_decode.h"
#include "io/io_errors.h"

namespace ssrt {

namespace {

using io_detail::DecodedImage;
using io_detail::SampleType;

[[noreturn]] void fail(const std::string& name, const std::string& problem) {
    std::string line = name + ": " + problem;
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    throw std::runtime_error(line);
}

// Whether channel c of an image with `channels` channels is colour (sRGB encoded in a base-
// colour image) rather than alpha or an extra channel.
bool colourChannel(std::size_t c, int channels) { return channels <= 2 ? c == 0 : c < 3; }

// RGBA from 1 (grey), 2 (grey, alpha), 3 (RGB) or 4+ (RGBA, extra channels dropped).
std::vector<float> toRgba(const std::vector<float>& pixels, int channels, std::size_t count) {
    std::vector<float> out(count * 4);
    for (std::size_t i = 0; i < count; ++i) {
        const float* p = pixels.data() + i * std::size_t(channels);
        float* t = out.data() + i * 4;
        t[3] = 1.0f;
        if (channels <= 2) {
            t[0] = t[1] = t[2] = p[0];
            if (channels == 2) t[3] = p[1];
        } else {
            t[0] = p[0];
            t[1] = p[1];
            t[2] = p[2];
            if (channels >= 4) t[3] = p[3];
        }
    }
    return out;
}

// srgbToLinear(v / 255) for every 8-bit value: the same bits as calling it per texel, about
// a hundred times cheaper for a large image.
const std::array<float, 256>& srgb8Table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int v = 0; v < 256; ++v) t[v] = srgbToLinear(float(v) / 255.0f);
        return t;
    }();
    return table;
}

// Normalizes T values by one division each (8-bit sRGB colour by the table).
template <class T>
std::vector<float> normalized(const io_detail::Samples<T>& raw, int channels, float maxValue,
                              bool srgb) {
    std::vector<float> out(raw.size());
    const std::size_t n = std::size_t(channels);
    for (std::size_t c = 0; c < n; ++c) {
        const bool colour = srgb && colourChannel(c, channels);
        if (colour && sizeof(T) == 1) {
            const std::array<float, 256>& table = srgb8Table();
            for (std::size_t i = c; i < raw.size(); i += n) out[i] = table[raw[i]];
        } else if (colour) {
            for (std::size_t i = c; i < raw.size(); i += n)
                out[i] = srgbToLinear(float(raw[i]) / maxValue);
        } else {
            for (std::size_t i = c; i < raw.size(); i += n) out[i] = float(raw[i]) / maxValue;
        }
    }
    return out;
}

std::vector<float> linearFloat(std::vector<float> out, int channels, bool srgb) {
    const std::size_t n = std::size_t(channels);
    for (std::size_t c = 0; srgb && c < n; ++c)
        if (colourChannel(c, channels))
            for (std::size_t i = c; i < out.size(); i += n) out[i] = srgbToLinear(out[i]);
    return out;
}

// 8- and 16-bit images are normalized here, by one division per value, rather than by a
// library's conversion, whose SIMD paths need not round alike on every CPU.
InterleavedImage toTexture(const std::string& name, const DecodedImage& image,
                           TextureEncoding encoding) {
    if (image.width < 1 || image.height < 1 || image.channels < 1) fail(name, "the image is empty");
    // (Its size is within io/image_limits.h's: the decoder checked the header.)
    const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
    const bool srgb = encoding == TextureEncoding::Srgb;
    const int n = image.channels;
    std::vector<float> pixels;
    switch (image.type) {
        case SampleType::U8: pixels = normalized(image.u8, n, 255.0f, srgb); break;
        case SampleType::U16: pixels = normalized(image.u16, n, 65535.0f, srgb); break;
        case SampleType::F32:
            pixels = linearFloat({image.f32.begin(), image.f32.end()}, n, srgb);
            break;
    }
    InterleavedImage out{image.width, image.height, 4, toRgba(pixels, n, count)};
    for (const float v : out.pixels)
        if (!std::isfinite(v)) fail(name, "the image has texels that are not finite");
    return out;
}

}  // namespace

// Texels exactly as stored: glTF's alpha is straight (unassociated), never premultiplied.
InterleavedImage readTextureImage(const std::string& path, TextureEncoding encoding) {
    DecodedImage image;
    try {
        image = io_detail::decodeImageFile(path, io_detail::AlphaMode::Straight);
    } catch (const io_detail::DecodeFailure& e) {
        fail(path, std::string("cannot read the image: ") + e.what());
    }
    return toTexture(path, image, encoding);
}

InterleavedImage decodeTextureImage(const std::string& name, const void* bytes, std::size_t size,
                                    const std::string& formatHint, TextureEncoding encoding) {
    if (size == 0) fail(name, "the image data is empty");
    DecodedImage image;
    try {
        image =
            io_detail::decodeImageBytes(bytes, size, formatHint, io_detail::AlphaMode::Straight);
    } catch (const io_detail::DecodeFailure& e) {
        fail(name, std::string("cannot decode the image: ") + e.what());
    }
    return toTexture(name, image, encoding);
}

}  // namespace ssrt
