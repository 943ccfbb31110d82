// Kulla and Conty 2017, "Revisiting Physically Based Shading at Imageworks": the energy that
// single-scattering GGX loses to masking comes back as a second, diffuse-like lobe
//   f_ms(wi, wo) = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)),
// which integrates (cosine-weighted over wo) to exactly 1 - E(mu_i), so that with F = 1 the
// total albedo is one. With Fresnel the lobe is tinted by the average Fresnel F_avg (the
// cosine-weighted mean of F over the hemisphere, F_avg = 20/21 f0 + 1/21 f90 for Schlick):
//   f_ms * F_avg^2 E_avg / (1 - F_avg (1 - E_avg)).
// Lane-generic lookups into the tables of shading/energy_tables.h (pointers into them).
#pragma once

#include "core/lane_math.h"
#include "core/lanes.h"
#include "shading/energy_tables.h"

namespace ssrt::multiscatter {

namespace ln = ssrt::lanes;

// Bilinear lookup of an N x N table over (sqrt(mu), roughness) in [0, 1]^2, clamped.
template <class L>
SSRT_INLINE L lookup2d(const float* table, L mu, L roughness) {
    constexpr int N = kEnergyTableSize;
    const L x = ln::sqrt(ln::saturate(mu)) * L(float(N - 1));
    const L y = ln::saturate(roughness) * L(float(N - 1));
    const L x0 = ln::min(ln::floor(x), L(float(N - 2)));
    const L y0 = ln::min(ln::floor(y), L(float(N - 2)));
    const L fx = x - x0, fy = y - y0;
    using I = ln::IntOf<L>;
    const I i00 = ln::toIntTrunc(y0 * L(float(N)) + x0);
    // (Each row's two taps side by side: one pair gather, half the elements.)
    L a, b, c, d;
    ln::gatherPair(table, i00, a, b);
    ln::gatherPair(table, i00 + I(N), c, d);
    const L top = a + (b - a) * fx, bottom = c + (d - c) * fx;
    return top + (bottom - top) * fy;
}

// Linear lookup of an N table over roughness in [0, 1].
template <class L>
SSRT_INLINE L lookup1d(const float* table, L roughness) {
    constexpr int N = kEnergyTableSize;
    const L y = ln::saturate(roughness) * L(float(N - 1));
    const L y0 = ln::min(ln::floor(y), L(float(N - 2)));
    const L fy = y - y0;
    using I = ln::IntOf<L>;
    const I i0 = ln::toIntTrunc(y0);
    L a, b;
    ln::gatherPair(table, i0, a, b);
    return a + (b - a) * fy;
}

template <class L>
SSRT_INLINE L albedo(const EnergyTables& t, L mu, L roughness) {
    return lookup2d(t.e.data(), mu, roughness);
}
template <class L>
SSRT_INLINE L albedoAvg(const EnergyTables& t, L roughness) {
    return lookup1d(t.eAvg.data(), roughness);
}

// The multiple-scattering lobe with F = 1 (no cosine): 0 when `enabled` is false.
template <class L>
SSRT_INLINE L fMs(const EnergyTables& t, L muI, L muO, L roughness, bool enabled = true) {
    if (!enabled) return L(0.0f);
    const L ei = albedo(t, muI, roughness), eo = albedo(t, muO, roughness);
    const L denom = L(ln::kPi) * ln::max(L(1.0f) - albedoAvg(t, roughness), L(1.0e-6f));
    const L f = (L(1.0f) - ei) * (L(1.0f) - eo) / denom;
    return ln::select((muI > L(0.0f)) & (muO > L(0.0f)), f, L(0.0f));
}

// Cosine-weighted hemispherical average of Schlick's F: 2 int F(mu) mu dmu.
template <class L>
SSRT_INLINE L fresnelAvg(L f0, L f90) {
    return f0 * L(20.0f / 21.0f) + f90 * L(1.0f / 21.0f);
}

// Tint of the lobe for a coloured Fresnel (per channel): F_avg^2 E_avg / (1 - F_avg (1 - E_avg)).
template <class L>
SSRT_INLINE L fMsFresnelTint(L fAvg, L eAvg) {
    return fAvg * fAvg * eAvg / ln::max(L(1.0f) - fAvg * (L(1.0f) - eAvg), L(1.0e-6f));
}

}  // namespace ssrt::multiscatter
