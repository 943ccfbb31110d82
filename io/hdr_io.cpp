#include "io/hdr_io.h"

#include <cstdlib>
#include <cstring>
#include <limits>

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
