// REBLUR's shared formulas (NRD's REBLUR_Common.hlsli and Common.hlsli, restated), written once
// over the lane type like core/lane_math.h: only + - * /, sqrt, floor, select and the
// project's own exp2/log2/atan, so the scalar copy and every SIMD width give the same bits.
// r is perceptual roughness (NRD's "linear roughness"), z positive view depth.
#pragma once

#include "core/lane_math.h"
#include "core/lane_vec.h"

namespace ssrt::reblur {

namespace ln = ssrt::lanes;

inline constexpr float kEps = 1.0e-6f;

template <class L>
SSRT_INLINE L lerp(L a, L b, L t) {
    return a + (b - a) * t;
}

// (x - e0) / (e1 - e0) clamped to [0, 1]; e1 < e0 runs downward.
template <class L>
SSRT_INLINE L linstep(float e0, float e1, L x) {
    return ln::saturate((x - L(e0)) * L(1.0f / (e1 - e0)));
}

template <class L>
SSRT_INLINE L smoothstep01(L x) {
    const L s = ln::saturate(x);
    return s * s * (L(3.0f) - L(2.0f) * s);
}

// Hermite step from e0 to e1.
template <class L>
SSRT_INLINE L smoothstep(float e0, float e1, L x) {
    return smoothstep01((x - L(e0)) * L(1.0f / (e1 - e0)));
}

// Luma of linear RGB: Y of YCoCg, as REBLUR (0.25 R + 0.5 G + 0.25 B).
template <class L>
SSRT_INLINE L luma(L r, L g, L b) {
    return (L(0.25f) * r + L(0.5f) * g) + L(0.25f) * b;
}

// The non-exponential edge-stopping shape: 1 at 0, falling smoothly to 0 at |t| = 1.
template <class L>
SSRT_INLINE L weightNonExp(L t) {
    return L(1.0f) - smoothstep01(ln::abs(t));
}

// The exponential shape, NRD's ExpApprox(-3|t|): an exact rational, no exp().
template <class L>
SSRT_INLINE L weightExp(L t) {
    const L a = ln::abs(t);
    return L(1.0f) / ((L(9.0f) * a * a + L(3.0f) * a) + L(1.0f));
}

// acos(c) ~ sqrt(2 (1 - c)), for angles between normals.
template <class L>
SSRT_INLINE L acosApprox(L c) {
    return L(1.41421356f) * ln::sqrt(ln::saturate(L(1.0f) - c));
}

// REBLUR's specular "magic curve": how much a roughness behaves like a rough one.
template <class L>
SSRT_INLINE L specMagicCurve(L r) {
    const L s = L(1.0f) - ln::exp2(L(-200.0f) * r * r);
    return s * ln::sqrt(ln::sqrt(r));
}

// Tangent of the half angle of the GGX lobe holding `percent` of its volume (Frostbite).
template <class L>
SSRT_INLINE L lobeTanHalfAngle(L r, L percent) {
    return ln::saturate(r) * ln::sqrt(percent / ((L(1.0f) - percent) + L(kEps)));
}

// How far the GGX dominant direction leans from the normal to the mirror direction
// (the fit of Frostbite's G2 term NRD uses): 1 for a mirror head-on, toward 0 when rough.
template <class L>
SSRT_INLINE L dominantFactor(L noV, L r) {
    const L q = L(0.298475f) * ln::log(ln::max(L(39.4115f) - L(39.0029f) * r, L(kEps)));
    const L oneMinus = ln::max(L(1.0f) - ln::saturate(noV), L(kEps));
    return ln::saturate(ln::pow(oneMinus, L(10.8649f)) * (L(1.0f) - q) + q);
}

// The hit-distance normalisation f(z, r) = (A + B z) lerp(1, C, 2^(D r^2)); the signals carry
// hit distance / f, saturated.
struct HitDistanceScale {
    float a, b, c, d;  // a already in scene units (DenoiseSettings::hitDistanceA x diagonal)
};
// Its roughness factor lerp(1, C, 2^(D r^2)), and f from it: a loop over taps of one centre's
// roughness computes the factor once (the same operations, so the same bits).
template <class L>
SSRT_INLINE L hitDistanceRoughness(const HitDistanceScale& p, L r) {
    const L smooth = ln::saturate(ln::exp2(L(p.d) * r * r));
    return lerp(L(1.0f), L(p.c), smooth);
}
template <class L>
SSRT_INLINE L hitDistanceScaleWith(const HitDistanceScale& p, L z, L roughness) {
    return (L(p.a) + L(p.b) * z) * roughness;
}
template <class L>
SSRT_INLINE L hitDistanceScale(const HitDistanceScale& p, L z, L r) {
    return hitDistanceScaleWith(p, z, hitDistanceRoughness(p, r));
}

}  // namespace ssrt::reblur
