// JPEG through libjpeg (Debian's libjpeg-turbo, the library OpenImageIO 2.4 decodes JPEG with
// too; inside io/ only): grey and colour files, decoded with libjpeg's defaults, as
// OpenImageIO does, so the samples are the same bits.
//
// libjpeg reports a fatal error by calling error_exit, which must not return: ours longjmps
// to a setjmp in a function whose frame holds no C++ object with a destructor, keeps the
// message, and the caller throws it as a one-line std::runtime_error naming the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// Whether the bytes start with JPEG's start-of-image marker.
bool isJpeg(const uint8_t* bytes, std::size_t size);

// The decoded image: "Y" or R, G, B, 8-bit, sRGB. Empty for a file libjpeg reads but we
// leave to OpenImageIO (CMYK and YCCK, which it converts to RGB its own way).
std::optional<DecodedImage> decodeJpeg(const uint8_t* bytes, std::size_t size);

}  // namespace ssrt::io_detail
