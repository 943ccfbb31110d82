#include "shading/energy_tables.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "shading/energy_tables_data.h"

namespace ssrt {

namespace {

// Derivation (Karis 2013, "Real Shading in Unreal Engine 4"; Heitz 2018 for the estimator):
//   E(v) = int D G2 F / (4 v.z o.z) o.z do. Drawing o from the VNDF of v, the PDF over o is
//   D G1(v) / (4 v.z), so each sample weighs f cos / pdf = F G2(v, o) / G1(v); with Schlick,
//   F = f0 (1 - Fc) + f90 Fc and Fc = (1 - o.h)^5 splits the estimate into dfgA and dfgB.
// Samples: the spherical-cap VNDF sampler (Dupuy and Benyoub 2023) on an n x n stratified grid
// of cell centres (warped towards the rim), in double. Isotropic, so the view lies in the x-z
// plane.

double lambdaT(double x, double z, double a) { return std::sqrt(a * a * x * x + z * z); }

}  // namespace

DfgSample integrateGgxAlbedo(double mu, double alpha, int n) {
    const double vx = std::sqrt(std::max(0.0, 1.0 - mu * mu)), vz = mu;
    const double tv = lambdaT(vx, vz, alpha);
    const double sx = alpha * vx / tv, sz = vz / tv;  // stretched view
    double e = 0, a = 0, b = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            // u2 = 1 - (1 - v)^3 crowds the points towards the cap's rim, where the
            // reflections that leave below the horizon (the loss of smooth surfaces) come from.
            const double u1 = (i + 0.5) / n, v = (j + 0.5) / n,
                         u2 = 1.0 - (1.0 - v) * (1.0 - v) * (1.0 - v);
            const double jac = 3.0 * (1.0 - v) * (1.0 - v);
            const double phi = 2.0 * M_PI * u1;
            const double z = (1.0 - u2) * (1.0 + sz) - sz;
            const double st = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double hx = st * std::cos(phi) + sx, hy = st * std::sin(phi), hz = z + sz;
            double mx = alpha * hx, my = alpha * hy, mz = hz;
            const double ml = std::sqrt(mx * mx + my * my + mz * mz);
            mx /= ml, my /= ml, mz /= ml;
            const double vm = vx * mx + vz * mz;
            const double ox = 2 * vm * mx - vx, oy = 2 * vm * my, oz = 2 * vm * mz - vz;
            if (oz <= 0 || vm <= 0) continue;
            const double to = std::sqrt(alpha * alpha * (ox * ox + oy * oy) + oz * oz);
            // G2 / G1(v) = oz (vz + tv) / (tv oz + to vz)
            const double w = oz * (vz + tv) / (tv * oz + to * vz);
            const double fc = std::pow(1.0 - vm, 5.0);
            e += w * jac;
            a += w * jac * (1.0 - fc);
            b += w * jac * fc;
        }
    const double inv = 1.0 / (double(n) * n);
    return {e * inv, a * inv, b * inv};
}

EnergyTables computeEnergyTables() {
    EnergyTables t;
    constexpr int N = kEnergyTableSize;
    for (int j = 0; j < N; ++j) {
        const double r = double(j) / (N - 1);
        const double alpha = std::max(r * r, 1e-3);
        for (int i = 0; i < N; ++i) {
            const double x = double(i) / (N - 1);
            const DfgSample s = integrateGgxAlbedo(std::max(x * x, 1e-4), alpha, 96);
            t.e[j * N + i] = float(std::min(s.e, 1.0));
            t.dfgA[j * N + i] = float(s.a);
            t.dfgB[j * N + i] = float(s.b);
        }
        // E_avg = 2 int E mu dmu = 4 int E(x) x^3 dx over the table, linear in x = sqrt(mu)
        // (midpoint rule on 64 points per interval: error far below the float table's).
        double avg = 0;
        constexpr int kSub = 64;
        for (int i = 0; i + 1 < N; ++i)
            for (int k = 0; k < kSub; ++k) {
                const double f = (k + 0.5) / kSub, x = (i + f) / (N - 1);
                const double e = t.e[j * N + i] + (t.e[j * N + i + 1] - t.e[j * N + i]) * f;
                avg += 4.0 * e * x * x * x / (double(N - 1) * kSub);
            }
        t.eAvg[j] = float(std::min(avg, 1.0));
    }
    return t;
}

const EnergyTables& energyTables() {
    // The tables as computeEnergyTables() made them, stored (shading/energy_tables_data.h):
    // computing them costs half a second at start-up, and the stored bits do not depend on
    // the machine's libm (a test compares the two).
    namespace d = energy_data;
    static_assert(std::size(d::kE) == kEnergyTableSize * kEnergyTableSize &&
                      std::size(d::kDfgA) == std::size(d::kE) &&
                      std::size(d::kDfgB) == std::size(d::kE) &&
                      std::size(d::kEAvg) == kEnergyTableSize,
                  "shading/energy_tables_data.h is out of date: run ssrt_gen_energy_tables");
    static const EnergyTables tables = [] {
        EnergyTables t;
        std::copy(std::begin(energy_data::kE), std::end(energy_data::kE), t.e.begin());
        std::copy(std::begin(energy_data::kEAvg), std::end(energy_data::kEAvg), t.eAvg.begin());
        std::copy(std::begin(energy_data::kDfgA), std::end(energy_data::kDfgA), t.dfgA.begin());
        std::copy(std::begin(energy_data::kDfgB), std::end(energy_data::kDfgB), t.dfgB.begin());
        return t;
    }();
    return tables;
}

}  // namespace ssrt
