// Every sampler against its own PDF: Pearson's chi-square on a theta x phi histogram of 10^6
// samples (drawn through the SIMD kernels), and the PDFs integrated numerically to one.
#include <doctest/doctest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/rng.h"
#include "sampling_stats.h"

using namespace ssrt;
using namespace ssrt::test;

namespace {

constexpr std::size_t kSamples = 1000000;
constexpr double kDeg = M_PI / 180.0;

struct Config {
    SamplerConfig s;
    double thetaDeg;
    uint32_t seed;
};

Dir viewAt(double thetaDeg) {
    // An azimuth off the axes so anisotropy shows.
    const double t = thetaDeg * kDeg, phi = 0.7;
    return normalized({std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)});
}

// The grid: alpha pairs (isotropic 0.01, 0.1, 0.5, 1 and two anisotropic pairs) x view angles
// (0, 30, 60, 89 degrees; 100 and 135 below the horizon for the cap samplers).
std::vector<Config> buildGrid() {
    const float alphas[][2] = {{0.01f, 0.01f}, {0.1f, 0.1f}, {0.5f, 0.5f},
                               {1.0f, 1.0f},   {0.1f, 0.5f}, {1.0f, 0.25f}};
    const double above[] = {0.0, 30.0, 60.0, 89.0};
    const double below[] = {100.0, 135.0};
    std::vector<Config> grid;
    uint32_t seed = 1;
    grid.push_back({{Sampler::CosineHemisphere, viewAt(0), 1, 1}, 0, seed++});
    grid.push_back({{Sampler::UniformHemisphere, viewAt(0), 1, 1}, 0, seed++});
    for (const auto& a : alphas) {
        grid.push_back({{Sampler::GgxNdf, viewAt(0), a[0], a[1]}, 0, seed++});
        for (Sampler s : kAllSamplers) {
            if (s == Sampler::CosineHemisphere || s == Sampler::UniformHemisphere ||
                s == Sampler::GgxNdf)
                continue;
            for (double t : above) grid.push_back({{s, viewAt(t), a[0], a[1]}, t, seed++});
            const bool caps = s == Sampler::VndfSphericalCaps || s == Sampler::VndfBounded ||
                              s == Sampler::VndfSphericalCapsReflection ||
                              s == Sampler::VndfBoundedReflection;
            if (caps)
                for (double t : below) grid.push_back({{s, viewAt(t), a[0], a[1]}, t, seed++});
        }
    }
    return grid;
}

Histogram histogramFor(const SamplerConfig& s) {
    Histogram h;
    const double amax = std::max(s.ax, s.ay);
    if (s.sampler == Sampler::CosineHemisphere || s.sampler == Sampler::UniformHemisphere) {
        h.c = 0.5;
    } else if (samplerDrawsHalfVector(s.sampler)) {
        // Seen from below, only the far tail of D is visible: no lobe to zoom into.
        h.c = s.wi.z >= 0 ? std::max(0.5 * amax, 0.002) : 0.5;
    } else if (s.sampler == Sampler::GgxNdfReflection && (s.wi.z < 0.5 || amax >= 0.5)) {
        // Its PDF D(h) h.z / (4 |wi.h|) peaks as 1 / |wi + wo| at wo = -wi, with weight where
        // D is large at half vectors normal to wi (grazing views, rough surfaces). Around
        // that pole the cell measure 4 s ds dphi (s = |wo + wi| / 2) cancels the peak.
        h.frame = Frame({-s.wi.x, -s.wi.y, -s.wi.z});
        h.c = amax >= 0.5 ? 0.5 : std::max(amax, 0.004);
    } else if (s.wi.z >= 0) {
        h.frame = Frame({-s.wi.x, -s.wi.y, s.wi.z});  // around the mirror direction
        h.c = std::max(amax, 0.004);
    } else {
        h.c = 0.5;
    }
    return h;
}

struct Outcome {
    Chi2Result chi2;
    double integral = 0;
    uint64_t invalid = 0;
};

Outcome runConfig(const Config& cfg) {
    const Histogram h = histogramFor(cfg.s);
    std::vector<uint64_t> counts(h.cells(), 0);
    Outcome out;
    constexpr std::size_t kChunk = 1 << 16;
    std::vector<float> wx(kChunk, float(cfg.s.wi.x)), wy(kChunk, float(cfg.s.wi.y)),
        wz(kChunk, float(cfg.s.wi.z)), ax(kChunk, cfg.s.ax), ay(kChunk, cfg.s.ay);
    std::vector<float> u1(kChunk), u2(kChunk), ox(kChunk), oy(kChunk), oz(kChunk);
    const Isa isa = defaultIsa();
    for (std::size_t base = 0; base < kSamples; base += kChunk) {
        const std::size_t n = std::min(kChunk, kSamples - base);
        for (std::size_t i = 0; i < n; ++i) {
            u1[i] = randomFloat(uint32_t(base + i), cfg.seed, 0, 0);
            u2[i] = randomFloat(uint32_t(base + i), cfg.seed, 0, 1);
        }
        const SampleBatch a{.wiX = wx.data(),
                            .wiY = wy.data(),
                            .wiZ = wz.data(),
                            .alphaX = ax.data(),
                            .alphaY = ay.data(),
                            .u1 = u1.data(),
                            .u2 = u2.data(),
                            .outX = ox.data(),
                            .outY = oy.data(),
                            .outZ = oz.data()};
        sampleDirections(isa, cfg.s.sampler, a, n);
        for (std::size_t i = 0; i < n; ++i) {
            const int cell = h.cellOf(ox[i], oy[i], oz[i]);
            if (cell < 0) ++out.invalid;
            else ++counts[cell];
        }
    }
    const std::vector<double> prob = cellProbabilities(h, cfg.s, 4);
    std::vector<double> expected(prob.size());
    for (std::size_t i = 0; i < prob.size(); ++i) {
        expected[i] = prob[i] * double(kSamples);
        out.integral += prob[i];
    }
    out.chi2 = chiSquare(counts, expected);
    return out;
}

std::string label(const Config& c) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s alpha=(%g,%g) theta=%g",
                  std::string(samplerName(c.s.sampler)).c_str(), c.s.ax, c.s.ay, c.thetaDeg);
    return buf;
}

// The whole grid, run once (in parallel over configurations) and shared by the test cases.
const std::vector<Outcome>& gridOutcomes() {
    static const std::vector<Outcome> outcomes = [] {
        const std::vector<Config> grid = buildGrid();
        std::vector<Outcome> out(grid.size());
        tbb::parallel_for(std::size_t(0), grid.size(),
                          [&](std::size_t i) { out[i] = runConfig(grid[i]); });
        return out;
    }();
    return outcomes;
}

}  // namespace

TEST_CASE("shading: every sampler passes chi-square against its own PDF") {
    const std::vector<Config> grid = buildGrid();
    const std::vector<Outcome>& outcomes = gridOutcomes();

    // Significance 0.01, Bonferroni-corrected for the number of tests.
    const double alpha = 0.01 / double(grid.size());
    std::map<std::string, std::pair<double, int>> worst;  // sampler -> (min p, configs)
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const std::string name(samplerName(grid[i].s.sampler));
        auto& w = worst.try_emplace(name, 1.0, 0).first->second;
        w.first = std::min(w.first, outcomes[i].chi2.pValue);
        ++w.second;
    }
    std::string table = "chi-square (10^6 samples per configuration), worst p-value per sampler:\n";
    for (const auto& [name, w] : worst) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "  %-32s configs %3d  min p %.4g\n", name.c_str(), w.second,
                      w.first);
        table += buf;
    }
    char buf[128];
    std::snprintf(buf, sizeof buf, "  threshold 0.01 / %zu = %.3g\n", grid.size(), alpha);
    table += buf;
    MESSAGE(table);
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const std::string what = label(grid[i]);
        CAPTURE(what);
        CAPTURE(outcomes[i].chi2.chi2);
        CAPTURE(outcomes[i].chi2.dof);
        CHECK(outcomes[i].invalid == 0);
        CHECK(outcomes[i].chi2.pValue >= alpha);
    }
}

// The same per-cell integrals summed: each PDF over the whole sphere (adaptive quadrature,
// see sampling_stats.h).
TEST_CASE("shading: sampler PDFs integrate to one over their domain") {
    const std::vector<Config> grid = buildGrid();
    const std::vector<Outcome>& outcomes = gridOutcomes();
    double worst = 0;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const std::string what = label(grid[i]);
        const double integral = outcomes[i].integral;
        CAPTURE(what);
        CAPTURE(integral);
        worst = std::max(worst, std::fabs(integral - 1.0));
        CHECK(std::fabs(integral - 1.0) < 1e-3);
    }
    MESSAGE("largest |integral - 1| over " << grid.size() << " configurations: " << worst);
}
