// BRDF terms, written once over the lane type (float or xsimd::batch<float, A>).
// Names follow the literature as Filament does; each term opens with its source.
// Directions are unit vectors; dot products are clamped by the caller.
#pragma once

#include "core/lane_math.h"

namespace ssrt::brdf {

namespace ln = ssrt::lanes;

// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
// D(m) = alpha^2 / (pi ((n.m)^2 (alpha^2 - 1) + 1)^2)
template <class L>
SSRT_INLINE L D_GGX(L NoH, L alpha) {
    const L a2 = alpha * alpha;
    const L f = (NoH * NoH) * (a2 - L(1.0f)) + L(1.0f);
    return a2 / (L(ln::kPi) * f * f);
}

// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs"
// Height-correlated Smith G2 folded with the 1 / (4 NoV NoL) of the microfacet BRDF:
// V = 0.5 / (NoL sqrt(NoV^2 (1 - a2) + a2) + NoV sqrt(NoL^2 (1 - a2) + a2))
template <class L>
SSRT_INLINE L V_SmithGGXCorrelated(L NoV, L NoL, L alpha) {
    const L a2 = alpha * alpha;
    const L lv = NoL * ln::sqrt(NoV * NoV * (L(1.0f) - a2) + a2);
    const L ll = NoV * ln::sqrt(NoL * NoL * (L(1.0f) - a2) + a2);
    const L denom = lv + ll;
    return ln::select(denom > L(0.0f), L(0.5f) / ln::select(denom > L(0.0f), denom, L(1.0f)), L(0.0f));
}

// Schlick 1994, "An Inexpensive BRDF Model for Physically-Based Rendering"
// F = F0 + (F90 - F0) (1 - VoH)^5
template <class L>
SSRT_INLINE L F_Schlick(L VoH, L f0, L f90) {
    const L x = L(1.0f) - VoH;
    const L x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}

// Lambert 1760: a perfectly diffuse surface reflects albedo / pi.
template <class L>
SSRT_INLINE L Fd_Lambert() {
    return L(ln::kInvPi);
}

// Perceptual roughness to GGX alpha, kept away from 0 where D becomes a delta that float
// cannot hold (alpha^2 >= 1e-6 keeps D finite in single precision).
template <class L>
SSRT_INLINE L roughnessToAlpha(L perceptual) {
    const L r = ln::clamp(perceptual, L(0.0f), L(1.0f));
    return ln::max(r * r, L(1.0e-3f));
}

}  // namespace ssrt::brdf
