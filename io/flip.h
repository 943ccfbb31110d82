// FLIP: a perceptual difference between a test image and a reference, per pixel in [0, 1].
//
//   LDR-FLIP  Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild, "FLIP: A
//             Difference Evaluator for Alternating Images", HPG 2020: a colour difference of
//             the images as an observer sees them (filtered by the contrast sensitivity of
//             each opponent channel, compared in Hunt-adjusted L*a*b* by HyAB), raised to a
//             power that edges and points present in one image only lower.
//   HDR-FLIP  Andersson, Nilsson, Shirley and Akenine-Moller, "Visualizing Errors in Rendered
//             High Dynamic Range Images", Eurographics 2021 short papers: the largest LDR-FLIP
//             over a range of exposures, each image tone-mapped (ACES fit) at each one; the
//             range from the reference's largest and median luminance.
//
// Written from the papers' equations; the constants are the papers' (FlipConstants below).
// Deterministic: scalar code of + - * / and sqrt with the project's own exp2/log2/pow
// (core/lane_math.h), no FMA contraction, separable filters with their taps summed in one
// fixed order, threads over rows each writing only its own pixels, and the statistics summed
// in pixel order by one thread. So the same inputs give the same bits on every ISA and for
// every thread count (tests/io/flip_test.cpp). The error maps are those of the papers; the
// filters' weights are made in float by the project's exp, so they may differ in their last
// bits from other implementations'.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"

namespace ssrt {

// The papers' viewing condition: a 0.7 m wide 3840-pixel monitor seen from 0.7 m, pixels per
// degree of visual angle = distance * (pixels / width) * pi / 180.
inline constexpr double kFlipPixelsPerDegree =
    0.7 * (3840.0 / 0.7) * 3.14159265358979323846 / 180.0;

// A linear RGB image: a plane per channel, all of one size.
struct RgbImage {
    PlaneF r, g, b;
    int width() const { return r.width(); }
    int height() const { return r.height(); }
};

// What a FLIP map pools to: the mean, the weighted median (the error e at which the errors up
// to e, sorted, first hold more than half of the sum of all errors: the error of the pixels that
// carry the middle of the total) and the largest.
struct FlipStats {
    double mean = 0.0, weightedMedian = 0.0, max = 0.0;
};

// An error map with how it was made.
struct FlipResult {
    PlaneF error;  // per pixel, in [0, 1]
    FlipStats stats;
    bool hdr = false;
    // HDR-FLIP only: the exposures (stops, the image scaled by 2^exposure before the tone
    // map), from start to stop in `exposures` even steps.
    int exposures = 0;
    double startExposure = 0.0, stopExposure = 0.0;
};

// LDR-FLIP of `test` against `reference`, both linear RGB (clamped to [0, 1] first), seen at
// `ppd` pixels per degree, on `threads` worker threads (0: every core).
FlipResult ldrFlip(const RgbImage& test, const RgbImage& reference,
                   double ppd = kFlipPixelsPerDegree, int threads = 0);

// HDR-FLIP of `test` against `reference`, both linear RGB of any range (NaN and negative values
// count as 0, +inf as the largest float); exposures from the reference (the header above).
FlipResult hdrFlip(const RgbImage& test, const RgbImage& reference,
                   double ppd = kFlipPixelsPerDegree, int threads = 0);

// The mean, weighted median and largest of an error map (summed in double, in pixel order).
FlipStats flipStats(const PlaneF& error);

// Two image files: `a` the test, `b` the reference. Each file's colour is its layer `color`
// (color.R/G/B), else its plain R, G, B channels, else a grey Y (as R = G = B); a file that
// holds display values (sRGB: PNG, JPEG) is decoded to linear first. HDR-FLIP when both files
// hold linear values (EXR, Radiance .hdr), LDR-FLIP otherwise. Writes the heat map (a .png,
// heatmap non-empty) once both files were read and compared. Throws std::runtime_error (one
// line naming the file) when a file cannot be read, has no colour or the sizes differ,
// std::invalid_argument for a heat map that is not a .png.
struct FlipFileOptions {
    std::string heatmap;  // a .png to write, or empty
    double ppd = kFlipPixelsPerDegree;
    int threads = 0;
};
FlipResult flipImages(const std::string& a, const std::string& b,
                      const FlipFileOptions& options = {});

// The papers' heat map: each pixel's error on the magma colour map (display RGB), written as
// an 8-bit PNG through io/image_io.h's writeImage.
void writeFlipHeatmap(const std::string& path, const PlaneF& error);
// Magma at t in [0, 1] (clamped; NaN as 1): the nearest of its 256 entries, display RGB.
void magmaColour(float t, float rgb[3]);

// The pieces, for tests.
namespace flip_detail {

// The papers' constants.
struct FlipConstants {
    static constexpr float qc = 0.7f;   // exponent on the HyAB colour difference
    static constexpr float pc = 0.4f;   // share of cmax ...
    static constexpr float pt = 0.95f;  // ... mapped to this error
    static constexpr float qf = 0.5f;   // exponent on the feature difference
    static constexpr float w = 0.082f;  // edge detector's peak to trough, in degrees
};

// Linear RGB to the opponent space YCxCz (linearized CIELAB: Y' = 116 Y/Yw - 16,
// Cx = 500 (X/Xw - Y/Yw), Cz = 200 (Y/Yw - Z/Zw)), white being linear RGB (1, 1, 1).
void linearRgbToYCxCz(const float rgb[3], float out[3]);
void yCxCzToLinearRgb(const float ycxcz[3], float out[3]);
// Linear RGB to CIELAB with the same white, and the Hunt adjustment (L, 0.01 L a, 0.01 L b).
void linearRgbToHuntLab(const float rgb[3], float out[3]);
// The largest HyAB difference raised to qc: between green and blue, Hunt-adjusted.
float flipColourMax();

// One channel's contrast sensitivity filter, separated: the 2D filter is
// sum_i share[i] * (taps[i] along x, then along y), each taps[i] summing to 1 and the shares to
// 1 (the achromatic and red-green channels have one Gaussian: share[1] = 0).
struct SpatialFilter {
    int radius = 0;
    std::vector<float> taps[2];
    float share[2] = {1.0f, 0.0f};
};
// channel: 0 achromatic (Y), 1 red-green (Cx), 2 blue-yellow (Cz).
SpatialFilter spatialFilter(int channel, double ppd);

// The feature detectors' 1D taps: a Gaussian summing to 1, its first and second derivatives
// with their positive taps summing to 1 and negative ones to -1.
struct FeatureFilter {
    int radius = 0;
    std::vector<float> gauss, edge, point;
};
FeatureFilter featureFilter(double ppd);

}  // namespace flip_detail

}  // namespace ssrt
