#include "io/texture_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/color.h"

namespace ssrt {

namespace {

namespace OIIO = OIIO_NAMESPACE;

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

// Reads T values and normalizes them by one division each (8-bit sRGB colour by the table).
template <class T>
bool readNormalized(OIIO::ImageInput* in, int channels, std::vector<float>& out, float maxValue,
                    bool srgb) {
    std::vector<T> raw(out.size());
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDescFromC<T>::value(), raw.data()))
        return false;
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
    return true;
}

bool readFloat(OIIO::ImageInput* in, int channels, std::vector<float>& out, bool srgb) {
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, out.data())) return false;
    const std::size_t n = std::size_t(channels);
    for (std::size_t c = 0; srgb && c < n; ++c)
        if (colourChannel(c, channels))
            for (std::size_t i = c; i < out.size(); i += n) out[i] = srgbToLinear(out[i]);
    return true;
}

InterleavedImage readOpened(const std::string& name, OIIO::ImageInput* in,
                            TextureEncoding encoding) {
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) fail(name, "the image is empty");
    if (spec.depth > 1) fail(name, "volume images are not textures");
    const std::size_t count = std::size_t(spec.width) * std::size_t(spec.height);
    if (count > (std::size_t(1) << 28)) fail(name, "the image is too large for a texture");
    const int channels = spec.nchannels;
    std::vector<float> pixels(count * std::size_t(channels));
    // 8- and 16-bit images are normalized here, by one division per value, rather than by
    // OIIO's conversion, whose SIMD paths need not round alike on every CPU.
    const bool srgb = encoding == TextureEncoding::Srgb;
    bool ok = false;
    if (spec.format == OIIO::TypeDesc::UINT8) {
        ok = readNormalized<uint8_t>(in, channels, pixels, 255.0f, srgb);
    } else if (spec.format == OIIO::TypeDesc::UINT16) {
        ok = readNormalized<uint16_t>(in, channels, pixels, 65535.0f, srgb);
    } else {
        ok = readFloat(in, channels, pixels, srgb);
    }
    if (!ok) fail(name, "cannot decode the image: " + in->geterror());
    InterleavedImage out{spec.width, spec.height, 4, toRgba(pixels, channels, count)};
    for (const float v : out.pixels)
        if (!std::isfinite(v)) fail(name, "the image has texels that are not finite");
    return out;
}

// Texels exactly as stored: glTF's alpha is straight (unassociated), and OIIO would
// otherwise premultiply colour by it while reading PNG.
OIIO::ImageSpec readConfig() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

}  // namespace

InterleavedImage readTextureImage(const std::string& path, TextureEncoding encoding) {
    const OIIO::ImageSpec config = readConfig();
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) fail(path, "cannot read the image: " + OIIO::geterror());
    return readOpened(path, in.get(), encoding);
}

InterleavedImage decodeTextureImage(const std::string& name, const void* bytes, std::size_t size,
                                    const std::string& formatHint, TextureEncoding encoding) {
    if (size == 0) fail(name, "the image data is empty");
    OIIO::Filesystem::IOMemReader reader(bytes, size);
    // With a configuration, OIIO 2.4 takes the proxy from it, not from open()'s argument.
    OIIO::ImageSpec config = readConfig();
    OIIO::Filesystem::IOProxy* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    // OIIO picks the decoder by the extension of a file name ("x.png"; ".png" alone is read
    // as a name without one).
    const std::string ext = std::filesystem::path(formatHint).extension().string();
    auto in = OIIO::ImageInput::open("memory" + (ext.empty() ? formatHint : ext), &config, &reader);
    if (!in) fail(name, "cannot decode the image: " + OIIO::geterror());
    return readOpened(name, in.get(), encoding);
}

}  // namespace ssrt
