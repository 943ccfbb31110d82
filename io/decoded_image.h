// A decoded image file as io/'s readers share it (inside io/ only): the samples as the file
// stores them (8-bit, 16-bit or float), the channel names and the colour space, as
// OpenImageIO 2.4 reports them, so that every reader gives the callers the same values
// whichever library decoded the file (io/image_decode.h picks it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace ssrt::io_detail {

// std::allocator, except that resize() leaves new samples uninitialised: a decoder writes
// every sample or fails, and zeroing first would touch every page a header claims. A file of
// a few bytes may claim 16384 x 8192 pixels; cut short, it is refused having touched only the
// rows it held, not after the kernel has faulted in and zeroed gigabytes.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitialisedAllocator<U>;
    };
    UninitialisedAllocator() = default;
    template <class U>
    UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;  // default-initialised: no value for a sample type
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// A decoder's samples (io/ only; callers get std::vector<float> from toFloat and the readers).
template <class T>
using Samples = std::vector<T, UninitialisedAllocator<T>>;

enum class SampleType { U8, U16, F32 };

// How a decoder returns an image with alpha. PNG stores straight alpha; OpenImageIO
// associates (premultiplies) it unless asked not to, and the readers that never asked
// (sky images, ssrt diff) have always seen it associated.
enum class AlphaMode { Associated, Straight };

struct DecodedImage {
    int width = 0, height = 0, channels = 0;
    std::vector<std::string> channelNames;  // OpenImageIO's names and order ("R", "Y", "A", ...)
    SampleType type = SampleType::U8;
    Samples<uint8_t> u8;  // interleaved, row 0 first; the one vector `type` names is used
    Samples<uint16_t> u16;
    Samples<float> f32;
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
