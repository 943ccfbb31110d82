// Statistics for the sampler tests: a histogram of directions around a pole, the PDF
// integrated over each of its cells, and Pearson's chi-square test with pooled cells.
//
// Cells: theta x phi about a pole p (the normal, or the mirror direction for reflections),
// with theta warped so the cells follow the lobe whatever its width:
//   s = sin(theta / 2) = |d - p| / 2,   x = (1 + c) s / (s + c) in [0, 1],
// half the cells in x lie within s < c, the lobe's scale. The solid angle is
// d omega = 4 s ds dphi (since cos theta = 1 - 2 s^2), so with s(x) = c x / (1 + c - x),
// d omega = 4 s(x) s'(x) dx dphi, s'(x) = c (1 + c) / (1 + c - x)^2: smooth, no pole.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/isa.h"
#include "shading/sampling.h"
#include "shading/sampling_kernels.h"

namespace ssrt::test {

struct Dir {
    double x, y, z;
};
inline double dot(Dir a, Dir b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Dir normalized(Dir d) {
    const double l = std::sqrt(dot(d, d));
    return {d.x / l, d.y / l, d.z / l};
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
struct Frame {
    Dir t, b, n;
    explicit Frame(Dir p) : n(p) {
        const double sign = std::copysign(1.0, p.z);
        const double a = -1.0 / (sign + p.z);
        const double bb = p.x * p.y * a;
        t = {1.0 + sign * p.x * p.x * a, sign * bb, -sign * p.x};
        b = {bb, sign + p.y * p.y * a, -p.y};
    }
};

struct Histogram {
    int nx = 16, nphi = 32;
    double c = 0.5;
    Frame frame{Dir{0, 0, 1}};

    int cells() const { return nx * nphi; }

    // Cell index of a direction, -1 when it is not a unit vector (NaN, zero).
    int cellOf(double x, double y, double z) const {
        const double len2 = x * x + y * y + z * z;
        if (!(std::fabs(len2 - 1.0) < 1e-4)) return -1;
        const Dir d{x, y, z};
        const Dir e{x - frame.n.x, y - frame.n.y, z - frame.n.z};
        const double s = std::min(0.5 * std::sqrt(dot(e, e)), 1.0);
        const double u = (1.0 + c) * s / (s + c);
        double phi = std::atan2(dot(d, frame.b), dot(d, frame.t));
        const int ix = std::clamp(int(u * nx), 0, nx - 1);
        const int ip = std::clamp(int((phi + M_PI) * (nphi / (2.0 * M_PI))), 0, nphi - 1);
        return ix * nphi + ip;
    }
};

struct SamplerConfig {
    Sampler sampler;
    Dir wi;
    float ax, ay;
};

// The sampler's own PDF (the scalar instantiation of shading/sampling.h) at a direction.
inline double samplerPdf(const SamplerConfig& cfg, Dir d) {
    namespace sm = ssrt::sampling;
    using V = ssrt::lanes::V3<float>;
    const V wi{float(cfg.wi.x), float(cfg.wi.y), float(cfg.wi.z)};
    const V w{float(d.x), float(d.y), float(d.z)};
    const float ax = cfg.ax, ay = cfg.ay;
    switch (cfg.sampler) {
        case Sampler::CosineHemisphere: return sm::cosineHemispherePdf(w);
        case Sampler::UniformHemisphere: return sm::uniformHemispherePdf(w);
        case Sampler::GgxNdf: return sm::ggxNdfPdf(w, ax, ay);
        case Sampler::GgxNdfReflection: return sm::ggxNdfReflectionPdf(wi, w, ax, ay);
        case Sampler::VndfEllipsoid:
        case Sampler::VndfSphericalCaps: return sm::vndfPdf(wi, w, ax, ay);
        case Sampler::VndfEllipsoidReflection:
        case Sampler::VndfSphericalCapsReflection: return sm::vndfReflectionPdf(wi, w, ax, ay);
        case Sampler::VndfBounded: return sm::vndfBoundedPdf(wi, w, ax, ay);
        case Sampler::VndfBoundedReflection: return sm::vndfBoundedReflectionPdf(wi, w, ax, ay);
    }
    return 0;
}

// PDF times the solid-angle density of the (x, phi) cell coordinates.
inline double cellIntegrand(const Histogram& h, const SamplerConfig& cfg, double x, double phi) {
    const double c = h.c;
    const double s = c * x / (1.0 + c - x);
    const double ds = c * (1.0 + c) / ((1.0 + c - x) * (1.0 + c - x));
    const double cosT = 1.0 - 2.0 * s * s;
    const double sinT = 2.0 * s * std::sqrt(std::max(0.0, 1.0 - s * s));
    const double cp = std::cos(phi), sp = std::sin(phi);
    const Frame& f = h.frame;
    const Dir d{cosT * f.n.x + sinT * (cp * f.t.x + sp * f.b.x),
                cosT * f.n.y + sinT * (cp * f.t.y + sp * f.b.y),
                cosT * f.n.z + sinT * (cp * f.t.z + sp * f.b.z)};
    return samplerPdf(cfg, d) * 4.0 * s * ds;
}

// Adaptive quadrature: Simpson's rule on a 3 x 3 grid of a rectangle, compared with its
// midpoint rule; the rectangle is split in four while the two disagree by more than the
// tolerance (relative, or absolute per unit area) or while some of the nine points see the
// PDF and some do not (every jump of these PDFs is to zero: the horizon, h.z = 0 of a
// reflection, the edge of the bounded cap), down to maxDepth.
struct Quadrature {
    const Histogram& h;
    const SamplerConfig& cfg;
    double relTol = 1e-3, absTolPerArea = 1e-7, cellArea = 1;
    int maxDepth = 7;

    double refine(double x0, double x1, double p0, double p1, int depth) const {
        double f[3][3];
        int nonzero = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                f[i][j] = cellIntegrand(h, cfg, x0 + 0.5 * i * (x1 - x0), p0 + 0.5 * j * (p1 - p0));
                nonzero += f[i][j] > 0;
            }
        const double w[3] = {1.0, 4.0, 1.0};
        double simpson = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) simpson += w[i] * w[j] * f[i][j];
        const double area = (x1 - x0) * (p1 - p0);
        simpson *= area / 36.0;
        const double mid = area * f[1][1];
        const bool mixed = nonzero > 0 && nonzero < 9;
        if (depth >= maxDepth ||
            (!mixed && std::fabs(simpson - mid) <=
                           std::max(relTol * std::fabs(simpson), absTolPerArea * area / cellArea)))
            return simpson;
        const double xm = 0.5 * (x0 + x1), pm = 0.5 * (p0 + p1);
        return refine(x0, xm, p0, pm, depth + 1) + refine(x0, xm, pm, p1, depth + 1) +
               refine(xm, x1, p0, pm, depth + 1) + refine(xm, x1, pm, p1, depth + 1);
    }
};

// Per-cell probability: the PDF integrated over each cell, starting from k x k sub-cells.
inline std::vector<double> cellProbabilities(const Histogram& h, const SamplerConfig& cfg, int k) {
    std::vector<double> prob(h.cells(), 0.0);
    Quadrature q{h, cfg};
    const double dx = 1.0 / (h.nx * k), dp = 2.0 * M_PI / (h.nphi * k);
    q.cellArea = dx * dp * k * k;
    for (int ix = 0; ix < h.nx; ++ix)
        for (int ip = 0; ip < h.nphi; ++ip) {
            double sum = 0;
            for (int a = 0; a < k; ++a)
                for (int b = 0; b < k; ++b) {
                    const double x0 = (ix * k + a) * dx, p0 = -M_PI + (ip * k + b) * dp;
                    sum += q.refine(x0, x0 + dx, p0, p0 + dp, 0);
                }
            prob[ix * h.nphi + ip] = sum;
        }
    return prob;
}

// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes, 2nd ed., 6.2).
inline double gammaQ(double a, double x) {
    if (x <= 0) return 1.0;
    const double lg = std::lgamma(a);
    if (x < a + 1.0) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int i = 0; i < 100000; ++i) {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
        }
        return 1.0 - sum * std::exp(-x + a * std::log(x) - lg);
    }
    double b = x + 1.0 - a, cc = 1.0 / 1e-300, d = 1.0 / b, hh = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < 1e-300) d = 1e-300;
        cc = b + an / cc;
        if (std::fabs(cc) < 1e-300) cc = 1e-300;
        d = 1.0 / d;
        const double del = d * cc;
        hh *= del;
        if (std::fabs(del - 1.0) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - lg) * hh;
}

struct Chi2Result {
    double chi2 = 0, pValue = 0;
    int dof = 0;
};

// Pearson's test; cells expecting fewer than 5 samples are pooled into one (merged into the
// smallest regular cell when the pool itself expects fewer than 5).
inline Chi2Result chiSquare(const std::vector<uint64_t>& observed,
                            const std::vector<double>& expected) {
    std::vector<double> obs, exp;
    double pooledObs = 0, pooledExp = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooledObs += double(observed[i]);
            pooledExp += expected[i];
        } else {
            obs.push_back(double(observed[i]));
            exp.push_back(expected[i]);
        }
    }
    if (pooledExp >= 5.0 || exp.empty()) {
        obs.push_back(pooledObs);
        exp.push_back(std::max(pooledExp, 1e-12));
    } else if (pooledObs > 0 || pooledExp > 0) {
        const auto it = std::min_element(exp.begin(), exp.end());
        obs[it - exp.begin()] += pooledObs;
        *it += pooledExp;
    }
    Chi2Result r;
    for (std::size_t i = 0; i < obs.size(); ++i)
        r.chi2 += (obs[i] - exp[i]) * (obs[i] - exp[i]) / exp[i];
    r.dof = int(obs.size()) - 1;
    r.pValue = r.dof > 0 ? gammaQ(0.5 * r.dof, 0.5 * r.chi2) : 1.0;
    return r;
}

}  // namespace ssrt::test
