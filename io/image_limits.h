// The largest image ssrt reads, decided from a file's header before a pixel is allocated: a
// 69-byte PNG may claim 60000 x 60000 pixels (about 40 GB as float RGB), and its reader must
// say so in one line rather than fail to allocate. Every decoder of io/ (and OpenImageIO's
// module) checks a header's size here; so does `ssrt merge` for the size a band's header gives.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace ssrt {

// 16384 x 8192: a "16K" equirectangular environment, the largest in common use, and 32 times
// an 8K texture's need; as float RGBA it is 2 GB, which a 4 GB address space still holds.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(16384) * 8192;
// A side of up to 65536 pixels (a long panorama strip), within the pixel limit.
inline constexpr std::int64_t kMaxImageSide = 65536;
// Channels of one image (an EXR may hold many layers): 64 is every layer ssrt writes and more.
inline constexpr std::int64_t kMaxImageChannels = 64;

// Why an image of this size is refused (one line, without the file's name, which the caller
// adds), or nothing when it is within the limits.
inline std::optional<std::string> imageSizeProblem(std::int64_t width, std::int64_t height,
                                                   std::int64_t channels = 1) {
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    if (width < 1 || height < 1) return "the image is " + size + " pixels: empty";
    if (width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxImagePixels)
        return "the image is " + size + " pixels, over the limit of " +
               std::to_string(kMaxImagePixels) + " pixels (16384 x 8192) and " +
               std::to_string(kMaxImageSide) + " a side";
    if (channels < 1 || channels > kMaxImageChannels)
        return "the image has " + std::to_string(channels) + " channels, over the limit of " +
               std::to_string(kMaxImageChannels);
    return std::nullopt;
}

}  // namespace ssrt
