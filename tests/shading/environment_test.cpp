// The environment and its prefiltered split-sum levels: the lat-long mapping, a constant that
// stays constant, energy kept by prefiltering, the mirror level equal to the source, a lobe
// that widens with roughness, continuity at the poles and the seam, thread-count
// independence, and the split-sum combination with the DFG table.
#include "shading/environment.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/rng.h"
#include "shading/energy_tables.h"
#include "shading/prefiltered_env.h"

using namespace ssrt;
using V3f = lanes::V3<float>;

namespace {

constexpr int kW = 64, kH = 32;  // source size: small, so the suite stays fast

// A random-ish HDR image: a smooth gradient plus per-texel noise, different per channel.
std::vector<float> noiseImage(int w, int h, uint32_t seed) {
    std::vector<float> rgb(std::size_t(3) * w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float n = randomFloat(uint32_t(y * w + x), seed, 0, uint32_t(c));
                const float smooth = 1.0f + 0.5f * float(std::sin(6.28318 * x / w + c));
                rgb[(std::size_t(y) * w + x) * 3 + c] = smooth + 2.0f * n * n;
            }
    return rgb;
}

// Solid angle of one texel of row y of an h-row equirect image of width w.
double texelSolidAngle(int y, int w, int h) {
    return (2.0 * M_PI / w) * (std::cos(M_PI * y / h) - std::cos(M_PI * (y + 1) / h));
}

// Solid-angle-weighted mean of one channel over the sphere.
double sphereMean(const EquirectImage& img, int c) {
    double sum = 0.0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            sum += img.rgb[(std::size_t(y) * img.width + x) * 3 + c] *
                   texelSolidAngle(y, img.width, img.height);
    return sum / (4.0 * M_PI);
}

V3f texelDirection(int x, int y, int w, int h) {
    return env::uvToDirection((float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h));
}

bool finite(Rgb c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }
float maxDiff(Rgb a, Rgb b) {
    return std::max({std::fabs(a.r - b.r), std::fabs(a.g - b.g), std::fabs(a.b - b.b)});
}

PrefilterSettings smallSettings(int threads = 0) {
    PrefilterSettings s;
    s.threads = threads;
    return s;
}

}  // namespace

TEST_CASE("environment: lat-long mapping conventions and round trip") {
    float u, v;
    env::directionToUv(V3f{0.0f, 0.0f, -1.0f}, u, v);
    CHECK(u == doctest::Approx(0.5f));
    CHECK(v == doctest::Approx(0.5f));
    env::directionToUv(V3f{1.0f, 0.0f, 0.0f}, u, v);
    CHECK(u == doctest::Approx(0.75f));
    env::directionToUv(V3f{0.0f, 1.0f, 0.0f}, u, v);
    CHECK(v == doctest::Approx(0.0f));
    env::directionToUv(V3f{0.0f, -1.0f, 0.0f}, u, v);
    CHECK(v == doctest::Approx(1.0f));
    CHECK_THROWS_AS(Environment::equirect(4, 2, std::vector<float>(23)), std::invalid_argument);
    // Texel centres map to directions and back to the same (u, v)
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            env::directionToUv(texelDirection(x, y, kW, kH), u, v);
            REQUIRE(u == doctest::Approx((x + 0.5) / kW).epsilon(1e-5));
            REQUIRE(v == doctest::Approx((y + 0.5) / kH).epsilon(1e-5));
        }
}

TEST_CASE("environment: a constant prefilters to the same constant at every roughness") {
    const Rgb color{0.25f, 1.5f, 40.0f};
    // The constant type short-cuts
    const PrefilteredEnvironment constant(Environment::constant(color));
    CHECK(maxDiff(constant.lookup(V3f{0.3f, -0.2f, 0.9f}, 0.7f), color) == 0.0f);
    // An image of one colour goes through the whole estimator and must come out unchanged
    std::vector<float> rgb(std::size_t(3) * kW * kH);
    for (std::size_t i = 0; i < rgb.size(); i += 3)
        rgb[i] = color.r, rgb[i + 1] = color.g, rgb[i + 2] = color.b;
    const PrefilteredEnvironment pre(Environment::equirect(kW, kH, rgb), smallSettings());
    double worst = 0.0;
    for (int i = 0; i < pre.levelCount(); ++i) {
        const EquirectImage& lv = pre.level(i);
        for (int y = 0; y < lv.height; ++y)
            for (int x = 0; x < lv.width; ++x) {
                const Rgb c = lv.texel(x, y);
                worst = std::max({worst, std::fabs(c.r / color.r - 1.0),
                                  std::fabs(c.g / color.g - 1.0), std::fabs(c.b / color.b - 1.0)});
            }
    }
    for (int k = 0; k < 200; ++k) {
        const V3f d{randomFloat(k, 1, 0, 0) - 0.5f, randomFloat(k, 1, 0, 1) - 0.5f,
                    randomFloat(k, 1, 0, 2) - 0.5f};
        const Rgb c = pre.lookup(d, randomFloat(k, 1, 0, 3));
        worst = std::max({worst, std::fabs(c.r / color.r - 1.0), std::fabs(c.g / color.g - 1.0),
                          std::fabs(c.b / color.b - 1.0)});
    }
    MESSAGE("constant image: worst relative error " << worst);
    CHECK(worst < 1e-4);
}

TEST_CASE("environment: prefiltering keeps the mean radiance") {
    const Environment src = Environment::equirect(kW, kH, noiseImage(kW, kH, 7));
    const PrefilteredEnvironment pre(src, smallSettings());
    for (int c = 0; c < 3; ++c) {
        const double ref = sphereMean(src.mip(0), c);
        for (int i = 1; i < pre.levelCount(); ++i) {
            const double m = sphereMean(pre.level(i), c);
            const double rel = m / ref - 1.0;
            MESSAGE("channel " << c << " level " << i << " (r = " << pre.levelRoughness(i) << ", "
                               << pre.level(i).width << "x" << pre.level(i).height << "): mean "
                               << m << " vs " << ref << ", rel " << rel);
            CHECK(std::fabs(rel) < 0.01);
        }
    }
}

TEST_CASE("environment: roughness 0 reproduces the source") {
    const Environment src = Environment::equirect(kW, kH, noiseImage(kW, kH, 11));
    const PrefilteredEnvironment pre(src, smallSettings());
    float worstLookup = 0.0f, worstRadiance = 0.0f;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const Rgb ref = src.mip(0).texel(x, y);
            const V3f d = texelDirection(x, y, kW, kH);
            worstLookup = std::max(worstLookup, maxDiff(pre.lookup(d, 0.0f), ref));
            worstRadiance = std::max(worstRadiance, maxDiff(src.radiance(d), ref));
        }
    MESSAGE("max abs error at texel centres (texels in [0.5, 3.5]): lookup "
            << worstLookup << ", radiance " << worstRadiance);
    CHECK(worstLookup < 1e-4f);
    CHECK(worstRadiance < 1e-4f);

    // Through the estimator itself: alpha = 1e-3 is a lobe far narrower than a texel (though
    // near the poles it spans several texels of u, so a smooth source: linear in direction).
    std::vector<float> rgb(std::size_t(3) * kW * kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const V3f d = texelDirection(x, y, kW, kH);
            for (int c = 0; c < 3; ++c)
                rgb[(std::size_t(y) * kW + x) * 3 + c] =
                    1.5f + 0.5f * d.x + 0.3f * d.y - 0.2f * c * d.z;
        }
    const Environment smooth = Environment::equirect(kW, kH, rgb);
    PrefilterSettings settings;
    settings.samples = 64;
    const EquirectImage mirror = prefilterLevel(smooth, 0.0f, kW, kH, settings);
    float worstLevel = 0.0f;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            worstLevel =
                std::max(worstLevel, maxDiff(mirror.texel(x, y), smooth.mip(0).texel(x, y)));
    MESSAGE("prefiltered at r = 0 against a smooth source: max abs error "
            << worstLevel << " (texels in [0.5, 2.5])");
    CHECK(worstLevel < 0.01f);
}

// Angular spread of the prefiltered lobe of one bright texel: the RMS angle from the texel's
// direction, weighted by radiance and solid angle, over a fixed grid of lookups.
TEST_CASE("environment: a bright texel spreads wider as roughness grows") {
    std::vector<float> rgb(std::size_t(3) * kW * kH, 0.0f);
    const int bx = kW / 2, by = kH / 2;
    for (int c = 0; c < 3; ++c) rgb[(std::size_t(by) * kW + bx) * 3 + c] = 1000.0f;
    const V3f bright = texelDirection(bx, by, kW, kH);
    const PrefilteredEnvironment pre(Environment::equirect(kW, kH, rgb), smallSettings());
    constexpr int gw = 128, gh = 64;
    double previous = -1.0;
    for (int i = 0; i < pre.levelCount(); ++i) {
        double sum = 0.0, moment = 0.0;
        for (int y = 0; y < gh; ++y)
            for (int x = 0; x < gw; ++x) {
                const V3f d = texelDirection(x, y, gw, gh);
                const double cosA = std::clamp(double(lanes::dot(d, bright)), -1.0, 1.0);
                const double w =
                    pre.lookup(d, pre.levelRoughness(i)).g * texelSolidAngle(y, gw, gh);
                sum += w;
                moment += w * std::acos(cosA) * std::acos(cosA);
            }
        const double width = std::sqrt(moment / sum);
        MESSAGE("r = " << pre.levelRoughness(i) << ": RMS lobe angle " << width << " rad");
        CHECK(std::isfinite(width));
        CHECK(width > previous);
        previous = width;
    }
}

TEST_CASE("environment: lookups at the poles and the seam are finite and continuous") {
    const Environment src = Environment::equirect(kW, kH, noiseImage(kW, kH, 3));
    const PrefilteredEnvironment pre(src, smallSettings());
    const float roughness[] = {0.0f, 0.1f, 0.5f, 1.0f};
    for (float r : roughness) {
        // Exactly at the poles, and the zero vector
        for (V3f d : {V3f{0, 1, 0}, V3f{0, -1, 0}, V3f{0, 0, 0}, V3f{0, 0, 1}, V3f{-0.0f, 0, 1}}) {
            CHECK(finite(pre.lookup(d, r)));
            CHECK(finite(src.radiance(d)));
        }
        // Around each pole, every azimuth a hair away must agree with the pole
        for (float pole : {1.0f, -1.0f}) {
            const Rgb at = pre.lookup(V3f{0, pole, 0}, r);
            float spread = 0.0f;
            for (int k = 0; k < 32; ++k) {
                const float phi = 6.2831853f * float(k) / 32.0f;
                const V3f d{1e-4f * std::cos(phi), pole, 1e-4f * std::sin(phi)};
                spread = std::max(spread, maxDiff(pre.lookup(d, r), at));
            }
            MESSAGE("r = " << r << ", pole " << pole << ": spread " << spread);
            CHECK(spread < 0.01f);
        }
        // Across the seam u = 0 = 1 (+Z), at several heights
        for (float h : {-0.9f, -0.3f, 0.0f, 0.5f, 0.95f}) {
            const Rgb left = pre.lookup(V3f{-1e-5f, h, 1.0f}, r);
            const Rgb right = pre.lookup(V3f{1e-5f, h, 1.0f}, r);
            CHECK(finite(left));
            CHECK(maxDiff(left, right) < 0.01f);
        }
    }
}

// Krivanek and Colbert 2008: reading the mip that matches each sample's solid angle lets a
// few samples stand for many. Against a 4096-sample reference of a noisy source, 32 filtered
// samples must be close, and closer than 32 unfiltered ones by a wide margin.
TEST_CASE("environment: filtered importance sampling converges with few samples") {
    const Environment src = Environment::equirect(kW, kH, noiseImage(kW, kH, 13));
    PrefilterSettings s;
    s.samples = 4096;
    s.filtered = false;
    const EquirectImage ref = prefilterLevel(src, 0.5f, 16, 8, s);
    auto rmsError = [&](bool filtered) {
        s.samples = 32;
        s.filtered = filtered;
        const EquirectImage img = prefilterLevel(src, 0.5f, 16, 8, s);
        double sum = 0.0;
        for (std::size_t i = 0; i < img.rgb.size(); ++i)
            sum += (img.rgb[i] - ref.rgb[i]) * double(img.rgb[i] - ref.rgb[i]);
        return std::sqrt(sum / double(img.rgb.size()));
    };
    const double withFis = rmsError(true), without = rmsError(false);
    MESSAGE("r = 0.5, 32 samples, RMS error against 4096: filtered " << withFis << ", unfiltered "
                                                                     << without);
    CHECK(withFis < 0.05);
    CHECK(withFis * 2.0 < without);
}

// The fetch is lane-generic for kernels that look up misses: a batch of the architecture's
// baseline (SSE2 on x86-64, NEON on aarch64: xsimd's default for this file's flags) must give
// the scalar bits, at random directions and exactly at the poles.
TEST_CASE("environment: the lane-generic fetch equals the scalar one to the bit") {
    using B = xsimd::batch<float>;
    constexpr int kLanes = int(B::size);
    const Environment src = Environment::equirect(kW, kH, noiseImage(kW, kH, 17));
    const EquirectView view = src.mip(0).view();
    for (int k = 0; k < 256; k += kLanes) {
        alignas(16) float dx[kLanes], dy[kLanes], dz[kLanes], out[3][kLanes];
        for (int i = 0; i < kLanes; ++i) {
            dx[i] = randomFloat(k + i, 9, 0, 0) - 0.5f;
            dy[i] = k == 0 ? (i % 2 ? 1.0f : -1.0f) : randomFloat(k + i, 9, 0, 1) - 0.5f;
            dz[i] = randomFloat(k + i, 9, 0, 2) - 0.5f;
            if (k == 0) dx[i] = dz[i] = 0.0f;
        }
        B u, v;
        env::directionToUv(
            lanes::V3<B>{B::load_aligned(dx), B::load_aligned(dy), B::load_aligned(dz)}, u, v);
        const lanes::V3<B> c = env::sampleBilinear(view, u, v);
        c.x.store_aligned(out[0]), c.y.store_aligned(out[1]), c.z.store_aligned(out[2]);
        for (int i = 0; i < kLanes; ++i) {
            const Rgb s = sampleEquirect(src.mip(0), V3f{dx[i], dy[i], dz[i]});
            REQUIRE(std::memcmp(&s.r, &out[0][i], 4) == 0);
            REQUIRE(std::memcmp(&s.g, &out[1][i], 4) == 0);
            REQUIRE(std::memcmp(&s.b, &out[2][i], 4) == 0);
        }
    }
}

TEST_CASE("environment: prefiltering is bit-identical for 1 and 2 threads") {
    const Environment src = Environment::equirect(kW, kH, noiseImage(kW, kH, 5));
    const PrefilteredEnvironment one(src, smallSettings(1)), two(src, smallSettings(2));
    REQUIRE(one.levelCount() == two.levelCount());
    for (int i = 0; i < one.levelCount(); ++i) {
        const EquirectImage &a = one.level(i), &b = two.level(i);
        REQUIRE(a.rgb.size() == b.rgb.size());
        CHECK(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0);
    }
}

TEST_CASE("environment: split sum is LD (F0 A + F90 B) with the DFG table") {
    const EnergyTables& t = energyTables();
    constexpr int N = kEnergyTableSize;
    // At a table node the lookup returns the node
    const int i = 20, j = 10;
    const float x = float(i) / (N - 1), r = float(j) / (N - 1);
    const DfgTerms dfg = dfgTerms(x * x, r);
    CHECK(dfg.a == doctest::Approx(t.dfgA[j * N + i]).epsilon(1e-5));
    CHECK(dfg.b == doctest::Approx(t.dfgB[j * N + i]).epsilon(1e-5));
    // White furnace of the split sum: F0 = F90 = 1 in a unit sky gives A + B = E
    const PrefilteredEnvironment white(Environment::constant({1.0f, 1.0f, 1.0f}));
    const Rgb e = splitSumSpecular(white, V3f{0, 0, 1}, x * x, r, {1, 1, 1}, {1, 1, 1});
    CHECK(e.g == doctest::Approx(t.e[j * N + i]).epsilon(1e-3));
    // Colour: each channel its own F0 against the LD of that channel
    const PrefilteredEnvironment sky(Environment::constant({2.0f, 3.0f, 4.0f}));
    const Rgb f0{0.04f, 0.5f, 1.0f};
    const Rgb s = splitSumSpecular(sky, V3f{0, 0, 1}, x * x, r, f0);
    CHECK(s.r == doctest::Approx(2.0f * (0.04f * dfg.a + dfg.b)));
    CHECK(s.g == doctest::Approx(3.0f * (0.5f * dfg.a + dfg.b)));
    CHECK(s.b == doctest::Approx(4.0f * (1.0f * dfg.a + dfg.b)));
}
