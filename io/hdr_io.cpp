#include "io/hdr_io.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
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

namespace {

// A Radiance resolution line's two sizes, in order: "-Y 512 +X 1024" is 512 scanlines of 1024
// pixels; any of the 8 orientations ("+X 1024 -Y 512": 1024 columns of 512).
struct RadianceSize {
    std::int64_t scanlines = 0, scanlineLength = 0;
};

// One "[+-][XY] N" field of `line` from `at`; its N, or -1.
std::int64_t radianceField(const std::string& line, std::size_t& at, char& axis) {
    if (at + 2 > line.size() || (line[at] != '+' && line[at] != '-') ||
        (line[at + 1] != 'X' && line[at + 1] != 'Y'))
        return -1;
    axis = line[at + 1];
    at += 2;
    while (at < line.size() && line[at] == ' ') ++at;
    std::int64_t n = 0;
    const std::size_t first = at;
    while (at < line.size() && line[at] >= '0' && line[at] <= '9' && at - first < 10)
        n = n * 10 + (line[at++] - '0');
    while (at < line.size() && line[at] == ' ') ++at;
    return at > first ? n : -1;
}

// The resolution line after the header's blank line, as a lenient reader (OpenImageIO's)
// takes it: whatever the first line says, any orientation. Nothing when there is none.
std::optional<RadianceSize> radianceSize(const uint8_t* bytes, std::size_t size) {
    std::size_t at = 0;
    bool blank = false;
    while (at < size && !blank) {  // header lines up to the first empty one
        const std::size_t start = at;
        while (at < size && bytes[at] != '\n') ++at;
        blank = at == start && start > 0;
        ++at;
    }
    if (!blank || at >= size) return std::nullopt;
    std::string line;
    while (at < size && bytes[at] != '\n' && line.size() < 64) line += char(bytes[at++]);
    std::size_t i = 0;
    char first = 0, second = 0;
    const std::int64_t a = radianceField(line, i, first);
    const std::int64_t b = radianceField(line, i, second);
    if (a < 0 || b < 0 || first == second) return std::nullopt;
    return RadianceSize{a, b};
}

}  // namespace

void checkRadianceClaim(const uint8_t* bytes, std::size_t size) {
    // The header's size first, in every orientation, for stb_image and for OpenImageIO (which
    // reads the files stb_image refuses) alike: either would allocate whatever it claims, and
    // read a flat file cut short as zeros to its end (the sky fuzzer's 68-byte file whose
    // first line stb_image refuses claimed 60000 x 2000: 7.8 s in OpenImageIO under ASan).
    const std::optional<RadianceSize> claim = radianceSize(bytes, size);
    if (!claim) return;
    const std::int64_t width = claim->scanlineLength, height = claim->scanlines;
    checkImageSize(width, height, 3);
    // The fewest bytes its pixels can take: a run-length scanline is 4 bytes of header
    // and, for each of its 4 components, a 2-byte run per 127 pixels; a flat one (widths
    // under 8 or from 32768, and any scanline not marked as runs) 4 bytes a pixel.
    const std::int64_t runLine = 4 + 8 * ((width + 126) / 127);
    const std::int64_t lineBytes = width < 8 || width >= 32768 ? 4 * width : runLine;
    if (std::int64_t(size) < lineBytes * height)
        failDecode("the file is cut short: its " + std::to_string(width) + " x " +
                   std::to_string(height) + " pixels take at least " +
                   std::to_string(lineBytes * height) + " bytes, and the file has " +
                   std::to_string(size));
}

std::optional<DecodedImage> decodeRadianceHdr(const uint8_t* bytes, std::size_t size) {
    if (size > std::size_t(std::numeric_limits<int>::max())) return std::nullopt;
    checkRadianceClaim(bytes, size);
    int width = 0, height = 0, fileChannels = 0;
    if (!stbi_info_from_memory(bytes, int(size), &width, &height, &fileChannels))
        return std::nullopt;
    checkImageSize(width, height, 3);  // (the same size, unless stb_image reads it otherwise)
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
