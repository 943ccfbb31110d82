// EXR files read through OpenEXR (inside io/ only): part 0, its data window, every channel as
// float, in the order OpenImageIO 2.4 presents them (by layer, then R, G, B, A, ... before the
// other names; see exr_input.cpp), so that a comparison or a channel list reads the same.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// Whether the bytes start with EXR's magic number.
bool isExr(const uint8_t* bytes, std::size_t size);

// DecodeFailure when part 0's header gives a size over io/image_limits.h's limits, read by
// OpenEXR's core library, which parses the header alone: OpenEXR's InputFile reads a table of
// one entry per block of rows when it opens a file, so a corrupt height costs memory (and a
// truncated file another message) before its header could be checked. A file too short for
// the chunks its header declares is refused too. A header the core library cannot parse is
// left for InputFile to report.
void checkExrSize(const std::string& path);
// The same for an EXR in memory (which OpenImageIO decodes).
void checkExrSize(const uint8_t* bytes, std::size_t size);

// Every channel as float. Empty for a file whose channels OpenEXR would convert otherwise
// than OpenImageIO (32-bit unsigned integers, which it scales to [0, 1]) or that it cannot
// lay out (subsampled channels): OpenImageIO reads those.
std::optional<DecodedImage> readExr(const std::string& path);

// The channel names readExr gives, from the header alone.
std::vector<std::string> readExrChannelNames(const std::string& path);

}  // namespace ssrt::io_detail
