#include "io/image_decode.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "io/exr_input.h"
#include "io/hdr_io.h"
#include "io/io_errors.h"
#include "io/jpeg_io.h"
#include "io/oiio_module.h"
#include "io/png_io.h"

namespace ssrt::io_detail {

namespace {

// The whole file, or DecodeFailure with the system's reason.
std::vector<uint8_t> fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) failDecode(std::strerror(errno));
    std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                               std::istreambuf_iterator<char>()};
    if (in.bad()) failDecode(std::strerror(errno));
    return bytes;
}

// An EXR's first four bytes, read without reading the rest.
bool isExrFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    uint8_t magic[4] = {};
    in.read(reinterpret_cast<char*>(magic), sizeof magic);
    return in && isExr(magic, sizeof magic);
}

DecodedImage viaOiio(bool ok, DecodedImage&& image, const std::string& error) {
    if (!ok) failDecode(error);
    return std::move(image);
}

DecodedImage oiioFile(const std::string& path, AlphaMode alpha) {
    DecodedImage image;
    std::string error;
    const bool ok = oiioModule().decodeFile(path, alpha, image, error);
    return viaOiio(ok, std::move(image), error);
}

DecodedImage oiioBytes(const uint8_t* bytes, std::size_t size, const std::string& hint,
                       AlphaMode alpha) {
    DecodedImage image;
    std::string error;
    const bool ok = oiioModule().decodeBytes(bytes, size, hint, alpha, image, error);
    return viaOiio(ok, std::move(image), error);
}

// What is checked before bytes that our decoders leave go to OpenImageIO: a Radiance header's
// claim when it reads them as Radiance by their name (its reader takes a header without "#?",
// which ours do not see as Radiance).
void checkBeforeOiio(const uint8_t* bytes, std::size_t size, const std::string& name) {
    const std::string ext = lowerExtension(name);
    if (ext == ".hdr" || ext == ".rgbe") checkRadianceClaim(bytes, size);
}

// Our own decoders for what they read; nothing when the bytes are for OpenImageIO.
std::optional<DecodedImage> decodeOwn(const uint8_t* bytes, std::size_t size, AlphaMode alpha) {
    if (isPng(bytes, size)) return decodePng(bytes, size, alpha);
    if (isJpeg(bytes, size)) return decodeJpeg(bytes, size);
    if (isRadianceHdr(bytes, size)) return decodeRadianceHdr(bytes, size);
    return std::nullopt;
}

}  // namespace

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

DecodedImage decodeImageFile(const std::string& path, AlphaMode alpha) {
    if (isExrFile(path)) return readExr(path);
    const std::vector<uint8_t> bytes = fileBytes(path);
    if (std::optional<DecodedImage> image = decodeOwn(bytes.data(), bytes.size(), alpha))
        return std::move(*image);
    checkBeforeOiio(bytes.data(), bytes.size(), path);
    return oiioFile(path, alpha);
}

DecodedImage decodeImageBytes(const void* bytes, std::size_t size, const std::string& formatHint,
                              AlphaMode alpha) {
    const auto* data = static_cast<const uint8_t*>(bytes);
    if (std::optional<DecodedImage> image = decodeOwn(data, size, alpha)) return std::move(*image);
    if (isExr(data, size)) return readExr(data, size);  // EXR by its bytes, as ours go
    checkBeforeOiio(data, size, formatHint);
    return oiioBytes(data, size, formatHint, alpha);
}

DecodedImage readImageFile(const std::string& path, AlphaMode alpha) {
    try {
        return decodeImageFile(path, alpha);
    } catch (const DecodeFailure& e) {
        failRead(path, e.what());
    }
}

FloatImage readFloatImage(const std::string& path) {
    const DecodedImage decoded = readImageFile(path, AlphaMode::Associated);
    return FloatImage{decoded.width,        decoded.height,   decoded.channels,
                      decoded.channelNames, toFloat(decoded), decoded.srgb};
}

std::vector<std::string> imageChannelNames(const std::string& path) {
    try {
        if (isExrFile(path)) return readExrChannelNames(path);
    } catch (const DecodeFailure& e) {
        failRead(path, e.what());
    }
    return readImageFile(path, AlphaMode::Associated).channelNames;
}

}  // namespace ssrt::io_detail
