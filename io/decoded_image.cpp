#include "io/decoded_image.h"

#include "io/image_limits.h"
#include "io/io_errors.h"

namespace ssrt::io_detail {

void checkImageSize(std::int64_t width, std::int64_t height, std::int64_t channels) {
    if (const std::optional<std::string> problem = imageSizeProblem(width, height, channels))
        failDecode(*problem);
}

std::vector<std::string> defaultChannelNames(int n) {
    if (n == 1) return {"Y"};
    static const char* const kRgba[] = {"R", "G", "B", "A"};
    std::vector<std::string> names;
    for (int c = 0; c < n; ++c) names.push_back(c < 4 ? kRgba[c] : "channel" + std::to_string(c));
    return names;
}

namespace {

// OpenImageIO's convert_type for an integer sample: the value times 1 / max, in float.
template <class T>
std::vector<float> scaled(const Samples<T>& samples, float max) {
    const float scale = 1.0f / max;
    std::vector<float> out(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) out[i] = float(samples[i]) * scale;
    return out;
}

}  // namespace

std::vector<float> toFloat(const DecodedImage& image) {
    switch (image.type) {
        case SampleType::U8: return scaled(image.u8, 255.0f);
        case SampleType::U16: return scaled(image.u16, 65535.0f);
        case SampleType::F32: return {image.f32.begin(), image.f32.end()};
    }
    return {};
}

}  // namespace ssrt::io_detail
