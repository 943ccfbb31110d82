#include "io/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

#include "core/image.h"
#include "core/rel_mse.h"
#include "io/image_decode.h"
#include "io/image_io.h"
#include "io/io_errors.h"

namespace ssrt {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------
// Files

// Every channel of subimage 0 as float, interleaved (pixel by pixel, row by row).
using LoadedImage = io_detail::FloatImage;

// ---------------------------------------------------------------------------------------
// Layers

bool isDefaultChannel(const std::string& name) {
    return name == "R" || name == "G" || name == "B" || name == "A" || name == "Y";
}

// The layer a channel belongs to; "" for the default colour layer (R, G, B, A, Y).
std::string layerKey(const std::string& channel) {
    const std::size_t dot = channel.rfind('.');
    if (dot != std::string::npos) return channel.substr(0, dot);
    return isDefaultChannel(channel) ? std::string() : channel;
}

// A layer as both files hold it: its channels' indices in each.
struct LayerPlan {
    std::string key, name;
    std::vector<std::string> both, onlyA, onlyB;  // channel names
};

int indexOf(const std::vector<std::string>& names, const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
}

// The layers of either file: the reference's order, then those only in A.
std::vector<LayerPlan> planLayers(const std::vector<std::string>& a,
                                  const std::vector<std::string>& b) {
    std::vector<LayerPlan> plans;
    const auto planFor = [&](const std::string& key) -> LayerPlan& {
        for (LayerPlan& p : plans)
            if (p.key == key) return p;
        plans.push_back(LayerPlan{key, key, {}, {}, {}});
        return plans.back();
    };
    for (const std::string& c : b) {
        LayerPlan& p = planFor(layerKey(c));
        (indexOf(a, c) >= 0 ? p.both : p.onlyB).push_back(c);
    }
    for (const std::string& c : a)
        if (indexOf(b, c) < 0) planFor(layerKey(c)).onlyA.push_back(c);
    // The default layer is named after its channels: "RGB", "RGBA".
    for (LayerPlan& p : plans) {
        if (!p.key.empty()) continue;
        for (const auto* list : {&p.both, &p.onlyB, &p.onlyA})
            for (const std::string& c : *list) p.name += c;
    }
    return plans;
}

// The channels of `image` a comparison sees: all of them, but R, G and B where they are a copy
// of the colour layer, as ssrt's EXRs carry it for viewers (io/image_io.h): bit for bit the
// same values as color.R, .G, .B (a reference's: ref.color.R, .G, .B). The copy is compared as
// that layer, not a second time (nor reported missing against a file written without it);
// R, G, B that differ from the colour are a layer of their own, as in any file.
bool sameBits(float a, float b);

std::vector<std::string> comparedChannels(const LoadedImage& image) {
    const auto& names = image.names;
    const std::size_t n = std::size_t(image.channels);
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    const auto copies = [&](const std::string& layer) {
        for (const char* c : {"R", "G", "B"}) {
            const int p = indexOf(names, c), l = indexOf(names, layer + "." + c);
            if (p < 0 || l < 0) return false;
            for (std::size_t i = 0; i < pixels; ++i)
                if (!sameBits(image.values[i * n + std::size_t(p)],
                              image.values[i * n + std::size_t(l)]))
                    return false;
        }
        return true;
    };
    if (!copies("color") && !copies("ref.color")) return names;
    std::vector<std::string> kept;
    for (const std::string& c : names)
        if (c != "R" && c != "G" && c != "B") kept.push_back(c);
    return kept;
}

// Keeps the layers named in `wanted` (all when empty); a name neither file has throws.
std::vector<LayerPlan> chosen(std::vector<LayerPlan> plans,
                              const std::vector<std::string>& wanted) {
    if (wanted.empty()) return plans;
    std::string known;
    for (const LayerPlan& p : plans) known += (known.empty() ? "" : ", ") + p.name;
    for (const std::string& name : wanted)
        if (std::none_of(plans.begin(), plans.end(),
                         [&](const LayerPlan& p) { return p.name == name; }))
            throw std::invalid_argument("no layer '" + name +
                                        "' in either image (layers: " + known + ")");
    plans.erase(std::remove_if(plans.begin(), plans.end(),
                               [&](const LayerPlan& p) {
                                   return std::find(wanted.begin(), wanted.end(), p.name) ==
                                          wanted.end();
                               }),
                plans.end());
    return plans;
}

// ---------------------------------------------------------------------------------------
// Values

// The difference of a against the reference b (the header's rules): 0 for the same value
// (+0 and -0, the same infinity) or two NaNs, +inf when a non-finite value meets another.
double difference(float a, float b) {
    if (a == b || (std::isnan(a) && std::isnan(b))) return 0.0;
    if (std::isfinite(a) && std::isfinite(b)) return std::abs(double(a) - double(b));
    return kInf;
}

// A difference as the heat map's float: +inf stays +inf, a finite one past the float range
// (two huge values of opposite signs) becomes the largest float.
float heatValue(double d) {
    constexpr double kMax = std::numeric_limits<float>::max();
    return d == kInf ? std::numeric_limits<float>::infinity() : float(std::min(d, kMax));
}

constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ull;

// One value's four bytes into a 64-bit FNV-1a hash, low byte first.
uint64_t fnvBits(uint64_t h, float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 4; ++i) h = (h ^ ((bits >> (8 * i)) & 0xffu)) * 0x100000001b3ull;
    return h;
}

bool sameBits(float a, float b) {
    uint32_t x, y;
    std::memcpy(&x, &a, sizeof x);
    std::memcpy(&y, &b, sizeof y);
    return x == y;
}

// Compares one layer's channels pixel by pixel, and raises `heat` (when given) to each
// pixel's largest difference. Sums in double in row order: the same files give the same bits.
// One loop of our own rather than OpenImageIO's ImageBufAlgo::compare and absdiff: compare
// counts no NaN against a number as a failure nor as the largest error (a case in
// tests/io/image_compare_test.cpp shows it), absdiff makes NaN against NaN a NaN where we
// want 0, and relMSE needs a pass over the values anyway.
LayerDiff compareLayer(const LayerPlan& plan, const LoadedImage& a, const LoadedImage& b, int width,
                       int height, const ImageCompareOptions& options, PlaneF* heat) {
    LayerDiff d;
    d.pixelsOverEach.assign(options.moreThresholds.size(), 0);
    d.hashA = d.hashB = kFnvOffset;
    d.name = plan.name;
    d.channels = plan.both;
    d.identical = true;
    const std::size_t n = plan.both.size();
    std::vector<int> ia(n), ib(n);
    for (std::size_t k = 0; k < n; ++k) {
        ia[k] = indexOf(a.names, plan.both[k]);
        ib[k] = indexOf(b.names, plan.both[k]);
    }
    double rel = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t pixel = std::size_t(y) * width + x;
            const float* pa = a.values.data() + pixel * std::size_t(a.channels);
            const float* pb = b.values.data() + pixel * std::size_t(b.channels);
            double pixelMax = 0.0;
            for (std::size_t k = 0; k < n; ++k) {
                const float va = pa[ia[k]], vb = pb[ib[k]];
                d.identical = d.identical && sameBits(va, vb);
                d.hashA = fnvBits(d.hashA, va);
                d.hashB = fnvBits(d.hashB, vb);
                const double diff = difference(va, vb);
                if (diff > d.maxError) {
                    d.maxError = diff;
                    d.maxX = x, d.maxY = y;
                    d.maxChannel = plan.both[k];
                }
                if (diff > 0.0 && diff < kInf) rel += relSquaredError(va, vb);
                pixelMax = std::max(pixelMax, diff);
            }
            if (pixelMax == kInf) ++d.nonFinite;
            if (pixelMax > options.threshold) ++d.pixelsOver;
            for (std::size_t t = 0; t < options.moreThresholds.size(); ++t)
                if (pixelMax > options.moreThresholds[t]) ++d.pixelsOverEach[t];
            if (heat) heat->at(x, y) = std::max(heat->at(x, y), heatValue(pixelMax));
        }
    const double pixels = double(width) * double(height);
    d.relMse = d.nonFinite > 0 ? kInf : rel / (pixels * double(n));
    d.shareOver = double(d.pixelsOver) / pixels;
    return d;
}

// ---------------------------------------------------------------------------------------
// The heat map

// The layer the heat map shows (ImageCompareOptions::heatmapLayer): the one named, else the
// colour (`color`, else the plain R, G, B layer), else the first in both files; null when no
// layer is in both. A name that is not a compared layer in both files throws.
const LayerPlan* heatmapPlan(const std::vector<LayerPlan>& plans,
                             const ImageCompareOptions& options) {
    std::vector<const LayerPlan*> both;
    for (const LayerPlan& p : plans)
        if (!p.both.empty()) both.push_back(&p);
    if (!options.heatmapLayer.empty()) {
        for (const LayerPlan* p : both)
            if (p->name == options.heatmapLayer) return p;
        std::string known;
        for (const LayerPlan* p : both) known += (known.empty() ? "" : ", ") + p->name;
        throw std::invalid_argument("no layer '" + options.heatmapLayer +
                                    "' compared in both images for the heat map (layers: " +
                                    (known.empty() ? std::string("none") : known) + ")");
    }
    for (const char* key : {"color", ""})
        for (const LayerPlan* p : both)
            if (p->key == key) return p;
    return both.empty() ? nullptr : both.front();
}

void writeHeatmap(const std::string& path, const PlaneF& heat, double scale) {
    const int w = heat.width(), h = heat.height();
    PlaneF planes[3] = {PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float d = heat.at(x, y);
            float rgb[3];
            if (std::isinf(d)) std::copy(kHeatNonFinite, kHeatNonFinite + 3, rgb);
            else if (d <= 0.0f) heatColour(0.0, rgb);
            else heatColour(std::max(kHeatFloor, scale > 0.0 ? double(d) / scale : 1.0), rgb);
            for (int c = 0; c < 3; ++c) planes[c].at(x, y) = rgb[c];
        }
    writeDisplayPng(path, planes[0], planes[1], planes[2]);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Public

bool ImageDiff::identical() const {
    return !layers.empty() && std::all_of(layers.begin(), layers.end(), [](const LayerDiff& l) {
        return l.presence == LayerDiff::Presence::Both && l.identical;
    });
}

bool withinThresholds(const LayerDiff& layer, const DiffThresholds& limits, std::string* why) {
    const auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    if (layer.presence == LayerDiff::Presence::MissingInA) return fail("missing in A");
    if (layer.presence == LayerDiff::Presence::MissingInB) return fail("missing in B");
    // A NaN or infinity where the other file has something else is a bug, never noise.
    if (layer.nonFinite > 0) return fail("NaN or inf");
    // Written as !(x <= limit) so that a NaN could never pass.
    if (limits.maxError && !(layer.maxError <= *limits.maxError)) return fail("max error");
    if (limits.maxRelMse && !(layer.relMse <= *limits.maxRelMse)) return fail("relMSE");
    if (!(layer.shareOver <= limits.maxShare)) return fail("share over threshold");
    return true;
}

void heatColour(double t, float rgb[3]) {
    // Stops at t = 0, 0.2, ..., 1: black, dark red, red, orange, yellow, white.
    static constexpr float kStops[6][3] = {{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f},
                                           {1.0f, 0.0f, 0.0f}, {1.0f, 0.5f, 0.0f},
                                           {1.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
    const double s = std::clamp(std::isnan(t) ? 1.0 : t, 0.0, 1.0) * 5.0;
    const int i = std::min(int(s), 4);
    const float f = float(s - i);
    for (int c = 0; c < 3; ++c) rgb[c] = kStops[i][c] + (kStops[i + 1][c] - kStops[i][c]) * f;
}

ImageDiff compareImages(const std::string& pathA, const std::string& pathB,
                        const ImageCompareOptions& options) {
    if (!(options.threshold >= 0.0))
        throw std::invalid_argument("the pixel threshold must be a number >= 0");
    for (double t : options.moreThresholds)
        if (!(t >= 0.0)) throw std::invalid_argument("every pixel threshold must be a number >= 0");
    if (options.heatmapScale &&
        !(std::isfinite(*options.heatmapScale) && *options.heatmapScale > 0.0))
        throw std::invalid_argument("the heat map's scale must be a finite number > 0");
    if (!options.heatmap.empty()) checkPngOutput(options.heatmap, "the heat map");
    const LoadedImage a = io_detail::readFloatImage(pathA);
    const LoadedImage b = io_detail::readFloatImage(pathB);
    if (a.width != b.width || a.height != b.height)
        throw std::runtime_error("cannot compare '" + pathA + "' (" + std::to_string(a.width) +
                                 "x" + std::to_string(a.height) + ") with '" + pathB + "' (" +
                                 std::to_string(b.width) + "x" + std::to_string(b.height) +
                                 "): the sizes differ");
    const std::vector<LayerPlan> plans =
        chosen(planLayers(comparedChannels(a), comparedChannels(b)), options.layers);
    const LayerPlan* heatPlan = options.heatmap.empty() ? nullptr : heatmapPlan(plans, options);

    ImageDiff diff;
    diff.width = a.width;
    diff.height = a.height;
    std::unique_ptr<PlaneF> heat;
    if (!options.heatmap.empty()) heat = std::make_unique<PlaneF>(diff.width, diff.height, 0.0f);
    for (const LayerPlan& plan : plans) {
        if (!plan.both.empty())
            diff.layers.push_back(compareLayer(plan, a, b, diff.width, diff.height, options,
                                               &plan == heatPlan ? heat.get() : nullptr));
        // Channels only one file has: reported, never compared.
        for (const auto& [list, presence] :
             {std::pair{&plan.onlyB, LayerDiff::Presence::MissingInA},
              std::pair{&plan.onlyA, LayerDiff::Presence::MissingInB}}) {
            if (list->empty()) continue;
            LayerDiff missing;
            missing.name = plan.name;
            missing.channels = *list;
            missing.presence = presence;
            diff.layers.push_back(std::move(missing));
        }
    }
    if (heat) {
        if (heatPlan) diff.heatLayer = heatPlan->name;
        if (options.heatmapScale) {
            diff.heatScale = *options.heatmapScale;
        } else {
            for (int y = 0; y < diff.height; ++y)
                for (int x = 0; x < diff.width; ++x)
                    if (std::isfinite(heat->at(x, y)))
                        diff.heatScale = std::max(diff.heatScale, double(heat->at(x, y)));
        }
        writeHeatmap(options.heatmap, *heat, diff.heatScale);
    }
    return diff;
}

}  // namespace ssrt
