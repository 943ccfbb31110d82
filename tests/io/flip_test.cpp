// FLIP (io/flip.h) on images ssrt renders: exactly 0 for identical images, a larger value for
// a larger change, the same bits for every thread count; the filters' weights and the colour
// transform of white; `ssrt diff --flip` and its heat map. perf/flip_check.sh compares it with
// the values the FLIP authors publish.
#include "io/flip.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "cli/cli_run.h"
#include "io/image_io.h"
#include "plane_compare.h"
#include "temp_dir.h"
#include "thread_counts.h"

// Renders through the ssrt_cli_lib target, which defines SSRT_CLI_LIB for those linking it.
#ifdef SSRT_CLI_LIB

using namespace ssrt;
using test::TempDir;

namespace {

constexpr int kW = 96, kH = 54;

// spheres at kW x kH, at exposure `exposure`, as PNG (display values) and EXR (linear colour).
struct Render {
    std::string png, exr;
};

// Each exposure rendered once for the whole run.
const Render& rendered(const std::string& exposure) {
    static TempDir dir("ssrt-flip");
    static std::map<std::string, Render> cache;  // references stay valid as it grows
    if (const auto it = cache.find(exposure); it != cache.end()) return it->second;
    Render r{dir.file("e" + exposure + ".png"), dir.file("e" + exposure + ".exr")};
    for (const std::string& out : {r.png, r.exr}) {
        const auto run = test::runSsrt(
            {"render", "--scene", "spheres", "--width", std::to_string(kW), "--height",
             std::to_string(kH), "--exposure", exposure, "--layers", "color", "-q", "-o", out});
        REQUIRE_MESSAGE(run.code == 0, run.err);
    }
    return cache.emplace(exposure, r).first->second;
}

RgbImage readColour(const std::string& exr) {
    RgbImage rgb;
    PlaneF* planes[3] = {&rgb.r, &rgb.g, &rgb.b};
    const char* names[3] = {"color.R", "color.G", "color.B"};
    for (int c = 0; c < 3; ++c) {
        int w = 0, h = 0;
        const std::vector<float> v = readChannel(exr, names[c], w, h);
        *planes[c] = PlaneF(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) planes[c]->at(x, y) = v[std::size_t(y) * w + x];
    }
    return rgb;
}

using test::sameBits;

bool allZero(const PlaneF& p) {
    for (int y = 0; y < p.height(); ++y)
        for (int x = 0; x < p.width(); ++x)
            if (p.at(x, y) != 0.0f) return false;
    return true;
}

}  // namespace

TEST_CASE("flip: identical images give exactly 0, LDR and HDR") {
    const Render& r = rendered("1");
    for (const std::string& file : {r.png, r.exr}) {
        CAPTURE(file);
        const FlipResult f = flipImages(file, file);
        CHECK(f.hdr == (file == r.exr));
        CHECK(f.stats.mean == 0.0);
        CHECK(f.stats.weightedMedian == 0.0);
        CHECK(f.stats.max == 0.0);
        CHECK(allZero(f.error));
    }
}

TEST_CASE("flip: a small change gives more than 0, a larger change more") {
    const Render& reference = rendered("1");
    const Render& small = rendered("1.05");
    const Render& large = rendered("1.6");
    for (const bool hdr : {false, true}) {
        CAPTURE(hdr);
        const auto file = [&](const Render& r) { return hdr ? r.exr : r.png; };
        const FlipResult a = flipImages(file(small), file(reference));
        const FlipResult b = flipImages(file(large), file(reference));
        CHECK(a.hdr == hdr);
        CHECK(a.stats.mean > 0.0);
        CHECK(b.stats.mean > a.stats.mean);
        CHECK(b.stats.max > a.stats.max);
        CHECK(b.stats.weightedMedian > a.stats.weightedMedian);
        CHECK(b.stats.max <= 1.0);
        CHECK(a.stats.weightedMedian <= a.stats.max);
    }
}

TEST_CASE("flip: the same bits on 1, 2 and 8 threads") {
    const RgbImage reference = readColour(rendered("1").exr);
    const RgbImage test = readColour(rendered("1.6").exr);
    // LDR-FLIP on the linear colour (clamped to [0, 1]) and HDR-FLIP.
    const FlipResult ldr1 = ldrFlip(test, reference, kFlipPixelsPerDegree, 1);
    const FlipResult hdr1 = hdrFlip(test, reference, kFlipPixelsPerDegree, 1);
    REQUIRE(ldr1.stats.mean > 0.0);
    REQUIRE(hdr1.stats.mean > 0.0);
    for (const int threads : testThreadCounts({2, 8})) {
        CAPTURE(threads);
        const FlipResult ldr = ldrFlip(test, reference, kFlipPixelsPerDegree, threads);
        const FlipResult hdr = hdrFlip(test, reference, kFlipPixelsPerDegree, threads);
        CHECK(sameBits(ldr.error, ldr1.error));
        CHECK(sameBits(hdr.error, hdr1.error));
        CHECK(ldr.stats.mean == ldr1.stats.mean);
        CHECK(hdr.stats.weightedMedian == hdr1.stats.weightedMedian);
        CHECK(hdr.exposures == hdr1.exposures);
    }
}

TEST_CASE("flip: each filter's weights sum to 1, white is (100, 0, 0)") {
    using namespace flip_detail;
    const auto sum = [](const std::vector<float>& taps, int sign) {
        double s = 0.0;
        for (const float t : taps)
            if (sign == 0 || (sign > 0) == (t > 0.0f)) s += double(t);
        return s;
    };
    for (int channel = 0; channel < 3; ++channel) {
        CAPTURE(channel);
        const SpatialFilter f = spatialFilter(channel, kFlipPixelsPerDegree);
        CHECK(f.radius == 10);  // ceil(3 sqrt(0.04 / (2 pi^2)) 67.02) = ceil(9.05)
        CHECK(f.share[0] + f.share[1] == doctest::Approx(1.0).epsilon(1e-6));
        // The 2D filter: sum_i share_i (sum of taps_i)^2.
        double total = 0.0;
        for (int i = 0; i < 2; ++i)
            if (f.share[i] > 0.0f) total += f.share[i] * sum(f.taps[i], 0) * sum(f.taps[i], 0);
        CHECK(total == doctest::Approx(1.0).epsilon(1e-6));
    }
    CHECK(spatialFilter(0, kFlipPixelsPerDegree).share[1] == 0.0f);
    CHECK(spatialFilter(2, kFlipPixelsPerDegree).share[1] > 0.0f);  // blue-yellow: two Gaussians
    const FeatureFilter f = featureFilter(kFlipPixelsPerDegree);
    CHECK(f.radius == 9);  // ceil(3 * 0.5 * 0.082 * 67.02) = ceil(8.24)
    CHECK(sum(f.gauss, 0) == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(sum(f.edge, 1) == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(sum(f.edge, -1) == doctest::Approx(-1.0).epsilon(1e-6));
    CHECK(sum(f.point, 1) == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(sum(f.point, -1) == doctest::Approx(-1.0).epsilon(1e-6));

    const float white[3] = {1.0f, 1.0f, 1.0f}, black[3] = {0.0f, 0.0f, 0.0f};
    float o[3], lab[3], back[3];
    linearRgbToYCxCz(white, o);
    CHECK(o[0] == doctest::Approx(100.0).epsilon(1e-5));
    CHECK(std::abs(o[1]) < 1e-4);
    CHECK(std::abs(o[2]) < 1e-4);
    yCxCzToLinearRgb(o, back);
    for (const float v : back) CHECK(v == doctest::Approx(1.0).epsilon(1e-5));
    linearRgbToHuntLab(white, lab);
    CHECK(lab[0] == doctest::Approx(100.0).epsilon(1e-5));
    CHECK(std::abs(lab[1]) < 1e-3);
    CHECK(std::abs(lab[2]) < 1e-3);
    linearRgbToHuntLab(black, lab);
    for (const float v : lab) CHECK(std::abs(v) < 1e-5);
}

TEST_CASE("flip: ssrt diff --flip prints it, --flip-heatmap writes the magma map") {
    TempDir dir;
    const Render& reference = rendered("1");
    const Render& large = rendered("1.6");
    auto r = test::runSsrt({"diff", reference.png, reference.png, "--flip"});
    CHECK(r.code == 0);
    CHECK(test::contains(r.out,
                         "LDR-FLIP (67.02 pixels per degree): mean 0.000000, weighted "
                         "median 0.000000, max 0.000000"));
    const std::string heat = dir.file("flip.png");
    r = test::runSsrt(
        {"diff", large.exr, reference.exr, "--layers", "color", "--flip-heatmap", heat});
    CHECK(r.code == 1);  // the layer differs; FLIP sets no exit status of its own
    CHECK(test::contains(r.out, "HDR-FLIP ("));
    CHECK(test::contains(r.out, "FLIP heat map " + heat));
    int w = 0, h = 0;
    const std::vector<float> red = readChannel(heat, "R", w, h);
    CHECK(w == kW);
    CHECK(h == kH);
    // Magma's black end is not quite black, and somewhere the change shows brighter.
    float brightest = 0.0f;
    for (const float v : red) brightest = std::max(brightest, v);
    CHECK(brightest > 0.1f);
    r = test::runSsrt({"diff", large.png, reference.png, "--flip-heatmap", dir.file("f.exr")});
    CHECK(r.code == 2);
    CHECK(test::isOneErrorLine(r.err));
    float rgb[3];
    magmaColour(0.0f, rgb);
    CHECK(rgb[0] < 0.01f);
    magmaColour(1.0f, rgb);
    CHECK(rgb[0] > 0.98f);
}

TEST_CASE("flip: ssrt diff --max-flip-mean makes FLIP's mean a verdict") {
    const Render& reference = rendered("1");
    const Render& large = rendered("1.6");
    // Within the layers' thresholds, so FLIP alone decides.
    const std::vector<std::string> loose{"--threshold", "10", "--max-share", "1"};
    const auto diff = [&](const std::string& limit) {
        std::vector<std::string> args{"diff", large.png, reference.png, "--max-flip-mean", limit};
        args.insert(args.end(), loose.begin(), loose.end());
        return test::runSsrt(args);
    };
    std::vector<std::string> plain{"diff", large.png, reference.png, "--flip"};
    plain.insert(plain.end(), loose.begin(), loose.end());
    auto r = test::runSsrt(plain);
    CHECK(r.code == 0);  // without a limit FLIP only reports
    r = diff("0.001");
    CHECK(r.code == 1);
    CHECK(test::contains(r.out, "> --max-flip-mean 0.001"));
    CHECK(test::contains(r.out, "DIFFER: "));
    r = diff("0.9");
    CHECK(r.code == 0);
    CHECK(test::contains(r.out, "LDR-FLIP ("));
    r = diff("1.5");
    CHECK(r.code == 2);
    CHECK(test::isOneErrorLine(r.err));
}

#endif  // SSRT_CLI_LIB
