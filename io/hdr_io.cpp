#include "io/hdr_io.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

// The decoder itself, compiled here once: Radiance only, no stdio, no failure strings.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#define STBI_NO_FAILURE_STRINGS
#include <stb/stb_image.h>

#include "io/io_errors.h"

namespace ssrt::io_detail {

bool isRadianceHdr(const uint8_t* bytes, std::size_t size) {
    return size >= 2 && bytes[0] == '#' && bytes[1] == '?';
}

std::optional<DecodedImage> decodeRadianceHdr(const uint8_t* bytes, std::size_t size) {
    if (size > std::size_t(std::numeric_limits<int>::max())) return std::nullopt;
    int width = 0, height = 0, fileChannels = 0;
    // The header's size first: stb_image would allocate whatever it claims.
    if (!stbi_info_from_memory(bytes, int(size), &width, &height, &fileChannels))
        return std::nullopt;
    checkImageSize(width, height, 3);
    // The fewest bytes its pixels can take: a run-length scanline is 4 bytes of header and, for
    // each of its 4 components, a 2-byte run per 127 pixels; a flat one (stb_image reads widths
    // under 8 or from 32768 so, and any scanline not marked as runs) 4 bytes a pixel. stb_image
    // reads a flat file cut short as zeros to its end, decoding every pixel the header claims.
    const std::int64_t runLine = 4 + 8 * ((std::int64_t(width) + 126) / 127);
    const std::int64_t lineBytes = width < 8 || width >= 32768 ? 4 * std::int64_t(width) : runLine;
    if (std::int64_t(size) < lineBytes * height)
        failDecode("the file is cut short: its " + std::to_string(width) + " x " +
                   std::to_string(height) + " pixels take at least " +
                   std::to_string(lineBytes * height) + " bytes, and the file has " +
                   std::to_string(size));
    float* texels = stbi_loadf_from_memory(bytes, int(size), &width, &height, &fileChannels, 3);
    if (!texels) return std::nullopt;
    DecodedImage image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.channelNames = defaultChannelNames(3);
    image.type = SampleType::F32;
    image.f32.assign(texels, texels + image.sampleCount());
    stbi_image_free(texels);
    return image;
}

}  // namespace ssrt::io_detail
