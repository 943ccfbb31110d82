// Precomputed GGX tables over (cos theta_v, perceptual roughness): the directional albedo E
// and its cosine-weighted average E_avg of Kulla-Conty energy compensation, and the DFG
// table of the split-sum image-based light. Computed deterministically (double precision, a
// fixed point set, no threads), stored in shading/energy_tables_data.h, used in float.
#pragma once

#include <array>

namespace ssrt {

inline constexpr int kEnergyTableSize = 32;  // nodes per axis

// Nodes: mu_i = (i / (N - 1))^2 (dense at grazing angles, where E changes fastest; mu_0 is
// evaluated at 1e-4), roughness_j = j / (N - 1) with alpha = max(roughness^2, 1e-3) as
// brdf::roughnessToAlpha. Row-major: [j * N + i]. Look up with x = sqrt(mu).
struct EnergyTables {
    // E(mu, r) = int f_ss(mu, wo) cos(theta_o) dwo with F = 1.
    std::array<float, kEnergyTableSize * kEnergyTableSize> e{};
    // E_avg(r) = 2 int_0^1 E(mu, r) mu dmu (of the interpolated table, so lookups stay consistent).
    std::array<float, kEnergyTableSize> eAvg{};
    // Split-sum DFG: int f/F cos (1 - Fc) and int f/F cos Fc, Fc = (1 - wo.h)^5, so that the
    // specular albedo with Schlick's F is f0 * dfgA + f90 * dfgB (and dfgA + dfgB = E).
    std::array<float, kEnergyTableSize * kEnergyTableSize> dfgA{}, dfgB{};
};

// The stored tables (shading/energy_tables_data.h; copied out on first call, thread-safe).
const EnergyTables& energyTables();

// The tables computed afresh (about 0.5 s): what the stored ones were made from
// (shading/gen_energy_tables.cpp writes them; a test checks that they still agree).
EnergyTables computeEnergyTables();

// The estimator behind the tables, for tests: E, dfgA, dfgB at one (mu, alpha) with n^2
// stratified points (VNDF importance sampling, weight G2 / G1).
struct DfgSample {
    double e, a, b;
};
DfgSample integrateGgxAlbedo(double mu, double alpha, int n);

}  // namespace ssrt
