// One entry for decoding an image, from a file or from bytes in memory (inside io/ only): the
// format is chosen by the file's first bytes, as OpenImageIO does when an extension lies.
//   PNG        libpng (io/png_io.h)
//   JPEG       libjpeg (io/jpeg_io.h; grey and colour files, CMYK goes to OpenImageIO)
//   Radiance   stb_image (io/hdr_io.h; the usual -Y +X orientation, others to OpenImageIO)
//   EXR        OpenEXR's core library (io/exr_input.h; files and bytes; half, float and
//              unsigned channels, scanlines and tiles)
//   the rest   OpenImageIO, loaded on first need (io/oiio_module.h), in the format the file's
//              name (or the bytes' hint) says and no other
// Each gives the samples, channel names and colour space OpenImageIO would
// (tests/io/decoders_vs_oiio_test.cpp). Errors: DecodeFailure (io/io_errors.h), the reason in
// one line, which the public readers word with the file's or the image's name.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// A path's extension, lower case (".exr"; "" for none).
std::string lowerExtension(const std::string& path);

DecodedImage decodeImageFile(const std::string& path, AlphaMode alpha);

// `formatHint` is a file name or extension, used only when the bytes go to OpenImageIO (EXR
// goes by its bytes).
DecodedImage decodeImageBytes(const void* bytes, std::size_t size, const std::string& formatHint,
                              AlphaMode alpha);

// decodeImageFile, a failure worded "cannot read 'path': reason" (io_errors.h's failRead).
DecodedImage readImageFile(const std::string& path, AlphaMode alpha);

// Every channel as float, as OpenImageIO's readers gave them (alpha associated; toFloat).
struct FloatImage {
    int width = 0, height = 0, channels = 0;
    std::vector<std::string> names;
    std::vector<float> values;  // interleaved, row 0 first
    bool srgb = false;
};

// readImageFile's image as float; fails as it does.
FloatImage readFloatImage(const std::string& path);

// The channel names decodeImageFile would give, reading only an EXR's header; fails as
// readImageFile does.
std::vector<std::string> imageChannelNames(const std::string& path);

}  // namespace ssrt::io_detail
