// An EXR's pixels that OpenEXR 3.1's core library cannot decompress (DWAA and DWAB: "not yet
// implemented in C"), read by OpenEXR's InputFile (inside io/ only, for io/exr_input.cpp).
// Only after the core library has checked the header and found every chunk's place within the
// file, and only if InputFile reads the header as the core library did: InputFile parses a
// damaged header its own way (a 280-byte file that the core library read as 64 x 64 was
// 4005380 x 4 to it) and sizes its buffers by what it read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// What the core library read from part 0's header.
struct ExrHeaderFacts {
    int minX = 0, minY = 0, maxX = 0, maxY = 0;  // the data window
    int compression = 0;                         // exr_compression_t
    bool tiled = false;
    std::vector<std::string> channelNames;  // in the file's order
    std::vector<int> channelTypes;          // exr_pixel_type_t, likewise
};

// Fills `image` (sized, its channels in `outputOf`'s order: file channel i goes to channel
// outputOf[i]) from the file `name`, or from `bytes` when they are not null. Unsigned channels
// are left as their bits, as the core library's decoding leaves them. DecodeFailure when
// InputFile reads the header otherwise, or fails.
void readPixelsWithInputFile(const std::string& name, const uint8_t* bytes, std::size_t size,
                             const ExrHeaderFacts& facts, const std::vector<int>& outputOf,
                             DecodedImage& image);

}  // namespace ssrt::io_detail
