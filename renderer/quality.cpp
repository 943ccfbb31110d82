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

// What each preset traces and how the denoiser treats it: every preset sets the same keys
// (one table, a row per preset), so that applying one after another leaves no trace of the
// first. Measured (README): time and error of each at 1920x1080 and 640x360.
constexpr std::array<std::string_view, 10> kKeys = {
    "ssrLayout",     "ssrSparseFrames",      "ssgiLayout",
    "maxSteps",      "diffusePrepassRadius", "specularPrepassRadius",
    "blurMaxFrames", "postBlurMaxFrames",    "backFaces",
    "ssgiFeedback"};
using PresetRow = std::array<double, kKeys.size()>;  // a value per key, in kKeys' order

constexpr std::array<PresetValue, kKeys.size()> preset(const PresetRow& row) {
    std::array<PresetValue, kKeys.size()> out{};
    for (std::size_t i = 0; i < kKeys.size(); ++i) out[i] = {kKeys[i], row[i]};
    return out;
}

// ultra: today's full-resolution tracing, denoised with every pass (NRD's pre-blur radii),
// and the marchers' depth intervals from the back faces (issue 29: a second raster and rays
// that go on behind thin objects; colour error down on every built-in scene, the frame
// 1.2-1.3x the time, so not in the presets below); and multi-bounce diffuse from the frame
// before (ssgiFeedback), which the back faces make safe (issue 29, perf/feedback.py: on frame
// 30 of a still camera against all the light, cornell 0.0348 -> 0.0265, corridor 0.094 ->
// 0.057, bunny and occluded lower, spheres 4 % higher, 2CylinderEngine 0.0107 -> 0.0125; a
// frame 1.02-1.05x the CPU time). Without the back faces the thickness guess's false hits
// feed light back: the engine's error more than doubles (0.020 -> 0.047), so not below.
constexpr auto kUltra = preset({kFull, 64, kFull, 512, 30, 50, 64, 64, 1, 1});
// high: SSGI in a checkerboard, SSR at every pixel, the back faces and feedback as ultra.
constexpr auto kHigh = preset({kFull, 64, kCheckerboard, 512, 30, 50, 64, 64, 1, 1});
// medium (the default): SSR in a checkerboard, SSGI at half resolution; the denoiser without
// its pre-blur, and one spatial pass (the post-blur) for pixels with 4 frames of history or
// more (issue 18: half the denoiser's time; on cornell relMSE 0.0251 / 0.0239 on frames 1 /
// 30 against 0.0255 / 0.0242 with both, camera paths within their bar, flicker 0.0025
// against 0.0010).
constexpr auto kMedium = preset({kCheckerboard, 64, kHalf, 512, 0, 0, 4, 64, 0, 0});
// low: medium with a march of at most 48 Hi-Z iterations, and where 8 frames of history or
// more: no post-blur of steady pixels (issue 48: the post-blur 0.25x its time at frame 30;
// relMSE within 1-4 % of medium's on cornell, corridor, spheres and bunny, but flicker up
// 7-39 %, so not in medium) and SSR's checkerboard thinned to one pixel of a 2x2 block a
// frame (relMSE at frame 30 -4 to +0.4 %, flicker +0.3 to +1.7 %: not in medium either).
constexpr auto kLow = preset({kCheckerboard, 8, kHalf, 48, 0, 0, 4, 8, 0, 0});

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
