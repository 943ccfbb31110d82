// PNG (inside io/ only): decoding through libpng every PNG OpenImageIO 2.4 reads, to the same
// samples, names and colour space (tests/io/decoders_vs_oiio_test.cpp); and writing ssrt's
// 8-bit RGB previews with zlib (the chunks by hand, the pixels compressed in parallel), which
// decode to the pixels OpenImageIO's writer gave them (tests/io/image_io_test.cpp).
//
// libpng reports an error by longjmp. Every setjmp here sits in a function whose frame holds
// no C++ object with a destructor, and the jump never crosses one: the error's text is kept
// and thrown as a one-line std::runtime_error naming the file once libpng has returned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// Whether the bytes start with PNG's signature.
bool isPng(const uint8_t* bytes, std::size_t size);

// Palette and grey below 8 bits expanded to 8, transparency (tRNS) to an alpha channel,
// 16-bit samples in native order; alpha associated as OpenImageIO does unless Straight.
DecodedImage decodePng(const uint8_t* bytes, std::size_t size, AlphaMode alpha);

// A PNG's tEXt chunks: keyword and text (keywords of 1 to 79 Latin-1 characters).
using PngTexts = std::vector<std::pair<std::string, std::string>>;

// Fills row y's 8-bit RGB (width * 3 bytes); called for every row (and again for the row
// above each band of rows), from several threads.
using PngRows = std::function<void(int y, uint8_t* rgb)>;

// Writes 8-bit RGB to `file` with the chunks OpenImageIO 2.4 gave ssrt's previews (an oFFs
// chunk at 0, 0, the text "Software" = "ssrt", then `texts`, if any, before the pixels), its
// rows with PNG's Up filter deflated at `compressionLevel` (zlib's run-length strategy) in
// fixed bands of rows on `threads` threads (0: every core; the bytes do not depend on it).
// `path` names the file in errors.
void writePngRgb8(const std::string& path, const std::string& file, int width, int height,
                  const PngRows& rows, int compressionLevel, const PngTexts& texts = {},
                  int threads = 0);

// The tEXt chunks before a PNG's pixels, in file order. Throws as decodePng does.
PngTexts readPngTexts(const uint8_t* bytes, std::size_t size);

}  // namespace ssrt::io_detail
