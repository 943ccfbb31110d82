// Two image files compared layer by layer against thresholds: what differs, by how much and
// where (ssrt diff, ssrt render --compare). io/image_decode.h reads the files and its
// libraries stay behind this header.
//
// A layer is the channels that share the name before their last '.': color.R, color.G and
// color.B are the layer "color"; viewZ, a channel without a dot, is a layer of its own. The
// dotless colour channels R, G, B, A and Y (a plain PNG's, an EXR's default layer) are one
// layer named after them in file order ("RGB", "RGBA", "Y"). R, G and B that are bit for bit
// a file's color layer, or its ref.color (ssrt's EXRs carry that copy for viewers:
// io/image_io.h), are left out: the layer is compared once, and a file written without the
// copy compares the same.
//
// Per value, a is the first file's and b the reference's (the second file):
//   difference  |a - b|; 0 when both are NaN or both the same infinity; +inf when only one
//               is NaN or an infinity, or they are opposite infinities (a NaN against a
//               number differs, never hides: it is over every threshold)
//   relMSE      mean over pixels and the layer's channels of core/rel_mse.h's term
//               (a - b)^2 / (b^2 + 0.01), the values that match as above counting 0; +inf
//               when any value's difference is +inf
//   identical   every value has the same bits (a NaN matches only a NaN with its bits)
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ssrt {

// Which layers to compare, the per-channel threshold and the heat map.
struct ImageCompareOptions {
    // A pixel of a layer "differs" when any of its channels differs by more than this (>= 0).
    double threshold = 0.0;
    // Layer names to compare (empty: every layer of either file). A name in neither file is
    // an error (std::invalid_argument).
    std::vector<std::string> layers;
    // More thresholds (each >= 0) whose pixel counts LayerDiff::pixelsOverEach gives, in this
    // order: a golden-image suite's buckets (cli/suite_file.h) count several in one pass.
    std::vector<double> moreThresholds;
    // A PNG to write, or empty: per pixel the largest difference over one layer's channels,
    // on a colour ramp (heatColour). Written only when both files were read and compared,
    // through a temporary and a rename (io/image_io.h's writeImage).
    std::string heatmap;
    // The layer the heat map shows, compared and in both files (else std::invalid_argument).
    // Empty: the colour, `color` (else a plain file's RGB layer), else the first layer in
    // both files. One layer, so that another's range (march steps up to 100, depths in
    // metres) cannot make the colour's differences all dark.
    std::string heatmapLayer;
    // The difference drawn white (> 0), the same for every pair of files; unset: the shown
    // layer's largest finite difference.
    std::optional<double> heatmapScale;
};

// One layer of the comparison.
struct LayerDiff {
    enum class Presence { Both, MissingInA, MissingInB };
    std::string name;
    std::vector<std::string> channels;  // the full channel names, the reference's order
    Presence presence = Presence::Both;
    // The rest are for a layer in both files (Presence::Both).
    bool identical = false;                // bit for bit
    double maxError = 0.0;                 // the largest difference; +inf for a non-finite mismatch
    int maxX = 0, maxY = 0;                // where it is (the first such value in row order)
    std::string maxChannel;                // and in which channel
    double relMse = 0.0;                   // +inf when a value's difference is +inf
    uint64_t nonFinite = 0;                // pixels where a NaN or infinity meets a different value
    uint64_t pixelsOver = 0;               // pixels with a channel's difference above the threshold
    double shareOver = 0.0;                // pixelsOver over the pixel count
    std::vector<uint64_t> pixelsOverEach;  // pixels over each of moreThresholds, in order
    // 64-bit FNV-1a over the layer's values' bits (its channels in order, pixel by pixel) in
    // each file: equal bits give equal hashes, so a report can show what a layer was.
    uint64_t hashA = 0, hashB = 0;
};

// The whole comparison.
struct ImageDiff {
    int width = 0, height = 0;
    std::vector<LayerDiff> layers;  // the reference's layer order, then those only in A
    std::string heatLayer;          // with a heat map, the layer it shows
    double heatScale = 0.0;         // and its top: the scale given, else the layer's largest
                                    // finite difference
    bool identical() const;         // every layer in both files, each bit-identical
};

// Limits a comparison must stay within. A layer missing in either file never passes, nor
// one with a NaN or infinity against a different value (LayerDiff::nonFinite), whatever the
// limits.
struct DiffThresholds {
    std::optional<double> maxError;   // the largest difference allowed (unset: any)
    std::optional<double> maxRelMse;  // the largest relMSE allowed (unset: any)
    double maxShare = 0.0;            // share of pixels over the threshold allowed, in [0, 1]
};

// Whether one layer stays within the limits; `why` (if given) gets the first one broken,
// "missing in A", "missing in B", "NaN or inf", "max error", "relMSE" or
// "share over threshold".
bool withinThresholds(const LayerDiff& layer, const DiffThresholds& limits,
                      std::string* why = nullptr);

// Compares `a` against the reference `b` (any image file io/ reads; subimage 0, values as
// float: an 8-bit PNG's are 0..1, as OpenImageIO converts them). Throws std::runtime_error
// (one line naming the file) when a file cannot be read or the two differ in size,
// std::invalid_argument for a bad option; then no heat map is written.
ImageDiff compareImages(const std::string& a, const std::string& b,
                        const ImageCompareOptions& options = {});

// The heat map: a pixel's largest difference d over heatScale (ImageDiff's) gives t on a
// ramp from black (t = 0: equal) through dark red, red, orange and yellow to white (t = 1:
// the shown layer's largest finite difference, or the scale given; above it, white too). A pixel
// that differs at all is drawn at t >= kHeatFloor, so the smallest difference shows; a non-finite
// mismatch is blue, off the ramp.
inline constexpr double kHeatFloor = 0.15;
// The ramp's colour at t (clamped to [0, 1]), display RGB in [0, 1].
void heatColour(double t, float rgb[3]);
// Blue: a NaN or infinity against a different value.
inline constexpr float kHeatNonFinite[3] = {0.2f, 0.5f, 1.0f};

}  // namespace ssrt
