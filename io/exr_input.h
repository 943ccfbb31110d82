// EXR files read through OpenEXR's core library (inside io/ only): part 0, its data window,
// every channel as float, in the order OpenImageIO 2.4 presents them (io/exr_channel_order.h),
// so that a comparison or a channel list reads the same whichever library read the file.
//
// The core library, not OpenEXR's InputFile: the header that is checked is the header that is
// read. InputFile (3.1) parses a damaged header its own way, and small files that the core
// library's header passed still cost it seconds and gigabytes (a 280-byte file read as a
// 4005380 x 4 image, compressor buffers sized by a window no chunk holds). Here every size is
// checked before it is allocated, and each chunk is decoded into the image on its own: a
// damaged chunk stops the read with its reason, having cost the bytes the file holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// Whether the bytes start with EXR's magic number.
bool isExr(const uint8_t* bytes, std::size_t size);

// Every channel as float (half exactly; 32-bit unsigned integers scaled to [0, 1] as
// OpenImageIO does), scanlines or tiles (level 0). DecodeFailure, with the reason, for a
// header over io/image_limits.h's limits or damaged, deep data, subsampled channels (luminance
// and chroma images, which no renderer's output uses), and a chunk missing or damaged.
DecodedImage readExr(const std::string& path);
DecodedImage readExr(const uint8_t* bytes, std::size_t size);

// The channel names readExr gives, from the header alone (checked as readExr checks it).
std::vector<std::string> readExrChannelNames(const std::string& path);

// Part 0's string attributes by name (ssrt's own metadata: the shot, the version).
std::map<std::string, std::string> exrStringAttributes(const std::string& path);

}  // namespace ssrt::io_detail
