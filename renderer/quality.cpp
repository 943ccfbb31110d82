#include "renderer/quality.h"

#include <array>
#include <stdexcept>
#include <string>

#include "renderer/settings_fields.h"

namespace ssrt {

namespace {

constexpr double kFull = double(TraceLayout::Full);
constexpr double kCheckerboard = double(TraceLayout::Checkerboard);
constexpr double kHalf = double(TraceLayout::Half);

// What each preset traces and how the denoiser treats it. Every preset names the same keys,
// so that applying one after another leaves no trace of the first. Measured (README): time
// and error of each at 1920x1080 and 640x360.
// ultra: today's full-resolution tracing, denoised.
constexpr std::array kUltra = {
    PresetValue{"ssrLayout", kFull}, PresetValue{"ssgiLayout", kFull}, PresetValue{"maxSteps", 512},
    PresetValue{"diffusePrepassRadius", 30}, PresetValue{"specularPrepassRadius", 50}};
// high: SSGI in a checkerboard, SSR at every pixel.
constexpr std::array kHigh = {PresetValue{"ssrLayout", kFull},
                              PresetValue{"ssgiLayout", kCheckerboard},
                              PresetValue{"maxSteps", 512}, PresetValue{"diffusePrepassRadius", 30},
                              PresetValue{"specularPrepassRadius", 50}};
// medium (the default): SSR in a checkerboard, SSGI at half resolution.
constexpr std::array kMedium = {PresetValue{"ssrLayout", kCheckerboard},
                                PresetValue{"ssgiLayout", kHalf}, PresetValue{"maxSteps", 512},
                                PresetValue{"diffusePrepassRadius", 30},
                                PresetValue{"specularPrepassRadius", 50}};
// low: medium with a march of at most 48 Hi-Z iterations and no pre-blur (NRD's defaults
// elsewhere): about 100 of the denoiser's 460 ms at 1080p, at the price of a blotchier first
// frame; on cornell its relMSE is no worse (the pre-blur's bias offsets its smoothing).
constexpr std::array kLow = {PresetValue{"ssrLayout", kCheckerboard},
                             PresetValue{"ssgiLayout", kHalf}, PresetValue{"maxSteps", 48},
                             PresetValue{"diffusePrepassRadius", 0},
                             PresetValue{"specularPrepassRadius", 0}};

constexpr std::string_view kNames[kQualityCount] = {"low", "medium", "high", "ultra"};

const Field<RenderSettings>& fieldNamed(std::string_view key) {
    for (const auto& f : kRenderFields)
        if (f.key == key) return f;
    throw std::logic_error("quality preset: no setting " + std::string(key));
}

}  // namespace

std::string_view qualityName(Quality q) { return kNames[int(q)]; }

std::optional<Quality> parseQuality(std::string_view name) {
    for (int i = 0; i < kQualityCount; ++i)
        if (kNames[i] == name) return Quality(i);
    return std::nullopt;
}

std::string_view qualityList() { return "low, medium, high, ultra"; }

std::span<const PresetValue> qualityValues(Quality q) {
    switch (q) {
        case Quality::Low: return kLow;
        case Quality::Medium: return kMedium;
        case Quality::High: return kHigh;
        case Quality::Ultra: return kUltra;
    }
    return {};
}

void applyQuality(Quality q, RenderSettings& s) {
    for (const PresetValue& v : qualityValues(q)) fieldNamed(v.key).set(s, v.value);
}

}  // namespace ssrt
