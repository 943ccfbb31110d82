// A decoded image file as io/'s readers share it (inside io/ only): the samples as the file
// stores them (8-bit, 16-bit or float), the channel names and the colour space, as
// OpenImageIO 2.4 reports them, so that every reader gives the callers the same values
// whichever library decoded the file (io/image_decode.h picks it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ssrt::io_detail {

enum class SampleType { U8, U16, F32 };

// How a decoder returns an image with alpha. PNG stores straight alpha; OpenImageIO
// associates (premultiplies) it unless asked not to, and the readers that never asked
// (sky images, ssrt diff) have always seen it associated.
enum class AlphaMode { Associated, Straight };

struct DecodedImage {
    int width = 0, height = 0, channels = 0;
    std::vector<std::string> channelNames;  // OpenImageIO's names and order ("R", "Y", "A", ...)
    SampleType type = SampleType::U8;
    std::vector<uint8_t> u8;  // interleaved, row 0 first; the one vector `type` names is used
    std::vector<uint16_t> u16;
    std::vector<float> f32;
    bool srgb = false;  // OpenImageIO's "oiio:ColorSpace" is "sRGB"

    std::size_t sampleCount() const { return std::size_t(width) * height * channels; }
};

// DecodeFailure (io/io_errors.h) when a header's size is over io/image_limits.h's limits:
// every decoder calls it before allocating the pixels.
void checkImageSize(std::int64_t width, std::int64_t height, std::int64_t channels);

// OpenImageIO's default channel names for n channels (ImageSpec::default_channel_names):
// "Y" for one, R, G, B, A for up to four, then "channel4", ...
std::vector<std::string> defaultChannelNames(int n);

// Every sample as float, the way OpenImageIO converts them (8- and 16-bit samples times
// 1/255 and 1/65535 in float; tests/io/decoders_vs_oiio_test.cpp holds this to its bits).
std::vector<float> toFloat(const DecodedImage& image);

}  // namespace ssrt::io_detail
