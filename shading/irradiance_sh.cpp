#include "shading/irradiance_sh.h"

#include <cmath>
#include <vector>

namespace ssrt {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// Basis constants of the real Y_lm as the polynomials of the header, in its term order
// (1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2), and the band of each term.
struct ShBasis {
    double scale[kShTerms];
    int band[kShTerms];
};

ShBasis shBasis() {
    const double y0 = 0.5 / std::sqrt(kPiD);             // 1 / (2 sqrt(pi))
    const double y1 = std::sqrt(3.0 / (4.0 * kPiD));     // sqrt(3 / (4 pi))
    const double y2 = std::sqrt(15.0 / (4.0 * kPiD));    // sqrt(15 / (4 pi))
    const double y20 = std::sqrt(5.0 / (16.0 * kPiD));   // sqrt(5 / (16 pi))
    const double y22 = std::sqrt(15.0 / (16.0 * kPiD));  // sqrt(15 / (16 pi))
    return {{y0, y1, y1, y1, y2, y2, y20, y2, y22}, {0, 1, 1, 1, 2, 2, 2, 2, 2}};
}

void basisTerms(double x, double y, double z, double (&p)[kShTerms]) {
    p[0] = 1.0;
    p[1] = y;
    p[2] = z;
    p[3] = x;
    p[4] = x * y;
    p[5] = y * z;
    p[6] = 3.0 * z * z - 1.0;
    p[7] = x * z;
    p[8] = x * x - y * y;
}

}  // namespace

ShIrradiance projectIrradianceSh(const EquirectView& img) {
    const ShBasis basis = shBasis();
    const int w = img.width, h = img.height;
    // Per column: the direction's azimuthal part (sin phi, -cos phi), once.
    std::vector<float> sinPhi(w), cosPhi(w);
    for (int x = 0; x < w; ++x) {
        const float u = (float(x) + 0.5f) / float(w);
        lanes::sincos((u - 0.5f) * (2.0f * lanes::kPi), sinPhi[x], cosPhi[x]);
    }
    // Row boundaries: cos(pi y / h), y = 0 .. h (exactly 1 and -1 at the poles).
    std::vector<double> cosEdge(h + 1);
    for (int y = 0; y <= h; ++y)
        cosEdge[y] = y == 0   ? 1.0
                     : y == h ? -1.0
                              : double(lanes::cos(lanes::kPi * float(y) / float(h)));
    double sum[3][kShTerms] = {};
    for (int y = 0; y < h; ++y) {
        float st, ct;
        lanes::sincos(lanes::kPi * (float(y) + 0.5f) / float(h), st, ct);
        const double dOmega = 2.0 * kPiD / w * (cosEdge[y] - cosEdge[y + 1]);
        double row[3][kShTerms] = {};
        for (int x = 0; x < w; ++x) {
            // The direction of uvToDirection: (sin t sin p, cos t, -sin t cos p)
            double p[kShTerms];
            basisTerms(double(st) * sinPhi[x], double(ct), -double(st) * cosPhi[x], p);
            const float* texel = img.rgb + (std::size_t(y) * w + x) * 3;
            for (int c = 0; c < 3; ++c)
                for (int j = 0; j < kShTerms; ++j) row[c][j] += double(texel[c]) * p[j];
        }
        for (int c = 0; c < 3; ++c)
            for (int j = 0; j < kShTerms; ++j) sum[c][j] += row[c][j] * dOmega;
    }
    // k_j = (A_l / pi) L_lm Y-constant, with L_lm = Y-constant * sum.
    const double aOverPi[3] = {1.0, 2.0 / 3.0, 0.25};
    ShIrradiance out;
    for (int c = 0; c < 3; ++c)
        for (int j = 0; j < kShTerms; ++j) {
            const double s = basis.scale[j];
            out.coeffs[c * kShTerms + j] = float(aOverPi[basis.band[j]] * s * s * sum[c][j]);
        }
    return out;
}

Rgb irradianceSh(const ShIrradiance& sh, lanes::V3<float> n) {
    const lanes::V3<float> e = env::irradianceSh(sh.coeffs, n);
    return {e.x, e.y, e.z};
}

}  // namespace ssrt
