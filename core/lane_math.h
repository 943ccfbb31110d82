// The project's own transcendentals, written once over the lane type.
//
// Built only from + - * /, sqrt, floor, select and exact integer/bit operations, so the
// scalar copy and every SIMD width return the same bits (libm and xsimd's own versions
// differ between paths). Polynomials are the single-precision minimax fits of Cephes
// (S. Moshier, "Methods and Programs for Mathematical Functions", 1989) with its range
// reductions; accuracy is a few ulp over the stated domains (tests/core/lane_math_test.cpp).
#pragma once

#include "core/lanes.h"

namespace ssrt::lanes {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kHalfPi = 1.57079632679489661923f;
inline constexpr float kInvPi = 0.318309886183790671538f;

// Horner evaluation, highest coefficient first.
template <class L, std::size_t N>
SSRT_INLINE L polynomial(L x, const float (&c)[N]) {
    L r(c[0]);
    for (std::size_t i = 1; i < N; ++i) r = r * x + L(c[i]);
    return r;
}

// 2^x for x in [-126, 128); clamped outside (no denormals, no infinities).
template <class L>
SSRT_INLINE L exp2(L x) {
    x = lanes::clamp(x, L(-126.0f), L(127.99f));
    // x = n + f with f in [-0.5, 0.5]
    const L n = lanes::floor(x + L(0.5f));
    const L f = x - n;
    constexpr float c[] = {1.535336188319500e-4f, 1.339887440266574e-3f, 9.618437357674640e-3f,
                           5.550332471162809e-2f, 2.402264791363012e-1f, 6.931472028550421e-1f};
    const L p = f * lanes::polynomial(f, c) + L(1.0f);
    // Scale by 2^n through the exponent field; n + 127 is in [1, 255) here.
    const auto e = (lanes::toIntTrunc(n) + IntOf<L>(127)) << 23;
    return p * lanes::floatFromBits(e);
}

// log2(x) for finite x > 0; log2(0) = -126 (the clamp of exp2), negative x gives -126 too.
template <class L>
SSRT_INLINE L log2(L x) {
    using I = IntOf<L>;
    const auto valid = x >= L(1.1754944e-38f);
    x = lanes::select(valid, x, L(1.0f));
    // x = m * 2^e with m in [sqrt(1/2), sqrt(2))
    const I bits = lanes::bitsOf(x);
    I e = ((bits >> 23) & I(0xff)) - I(126);
    L m = lanes::floatFromBits((bits & I(0x007fffff)) | I(0x3f000000));  // m in [0.5, 1)
    const auto small = m < L(0.70710678f);
    m = lanes::select(small, m + m, m);
    e = e - lanes::select(lanes::toIntMask(small), I(1), I(0));
    const L ef = lanes::toFloat(e);
    // ln(1 + t) = t - t^2/2 + t^3 P(t)
    const L t = m - L(1.0f);
    const L z = t * t;
    constexpr float c[] = {7.0376836292e-2f,  -1.1514610310e-1f, 1.1676998740e-1f,
                           -1.2420140846e-1f, 1.4249322787e-1f,  -1.6668057665e-1f,
                           2.0000714765e-1f,  -2.4999993993e-1f, 3.3333331174e-1f};
    const L lnm = t - L(0.5f) * z + t * z * lanes::polynomial(t, c);
    const L r = lnm * L(1.44269504088896341f) + ef;
    return lanes::select(valid, r, L(-126.0f));
}

template <class L>
SSRT_INLINE L exp(L x) {
    return lanes::exp2(x * L(1.44269504088896341f));
}

template <class L>
SSRT_INLINE L log(L x) {
    return lanes::log2(x) * L(0.693147180559945309f);
}

// x^y for x >= 0 (0^y = 0 for y > 0); negative x is treated as 0.
template <class L>
SSRT_INLINE L pow(L x, L y) {
    const L r = lanes::exp2(y * lanes::log2(x));
    return lanes::select(x > L(0.0f), r, L(0.0f));
}

// Sine and cosine together. Octant reduction with a three-part pi/4 (Cody-Waite), exact
// for |x| < 8192; beyond that accuracy falls off gracefully (no NaN).
template <class L>
SSRT_INLINE void sincos(L x, L& s, L& c) {
    const L ax = lanes::abs(x);
    // j = octant index rounded up to even; y = x - j pi/4 lies in [-pi/4, pi/4]
    L j = lanes::floor(ax * L(1.27323954473516f));
    j = j + (j - L(2.0f) * lanes::floor(j * L(0.5f)));  // odd -> next even
    const L y = ((ax - j * L(0.78515625f)) - j * L(2.4187564849853515625e-4f)) -
                j * L(3.77489497744594108e-8f);
    const L z = y * y;
    constexpr float sc[] = {-1.9515295891e-4f, 8.3321608736e-3f, -1.6666654611e-1f};
    constexpr float cc[] = {2.443315711809948e-5f, -1.388731625493765e-3f, 4.166664568298827e-2f};
    const L sy = y + y * z * lanes::polynomial(z, sc);
    const L cy = L(1.0f) - L(0.5f) * z + z * z * lanes::polynomial(z, cc);
    // quadrant q = (j / 2) mod 4
    const L h = j * L(0.5f);
    const L q = h - L(4.0f) * lanes::floor(h * L(0.25f));
    const auto swap = (q == L(1.0f)) | (q == L(3.0f));
    const L sBase = lanes::select(swap, cy, sy);
    const L cBase = lanes::select(swap, sy, cy);
    const auto sNeg = lanes::maskXor(q >= L(2.0f), x < L(0.0f));
    const auto cNeg = (q == L(1.0f)) | (q == L(2.0f));
    s = lanes::select(sNeg, L(0.0f) - sBase, sBase);
    c = lanes::select(cNeg, L(0.0f) - cBase, cBase);
}

template <class L>
SSRT_INLINE L sin(L x) {
    L s, c;
    lanes::sincos(x, s, c);
    return s;
}

template <class L>
SSRT_INLINE L cos(L x) {
    L s, c;
    lanes::sincos(x, s, c);
    return c;
}

// asin on [-1, 1] (clamped): asin(x) = x + x z P(z), z = x^2, for |x| <= 1/2; above,
// asin(x) = pi/2 - 2 asin(sqrt((1 - x) / 2)).
template <class L>
SSRT_INLINE L asin(L x) {
    const L ax = lanes::min(lanes::abs(x), L(1.0f));
    const auto big = ax > L(0.5f);
    const L z = lanes::select(big, L(0.5f) * (L(1.0f) - ax), ax * ax);
    const L r = lanes::select(big, lanes::sqrt(z), ax);
    constexpr float c[] = {4.2163199048e-2f, 2.4181311049e-2f, 4.5470025998e-2f, 7.4953002686e-2f,
                           1.6666752422e-1f};
    const L p = r + r * z * lanes::polynomial(z, c);
    const L a = lanes::select(big, L(kHalfPi) - (p + p), p);
    return lanes::select(x < L(0.0f), L(0.0f) - a, a);
}

// acos on [-1, 1] (clamped), accurate near +-1 where pi/2 - asin(x) would cancel.
template <class L>
SSRT_INLINE L acos(L x) {
    x = lanes::clamp(x, L(-1.0f), L(1.0f));
    const L ax = lanes::abs(x);
    const L z = L(0.5f) * (L(1.0f) - ax);
    const L s = lanes::sqrt(z);
    constexpr float c[] = {4.2163199048e-2f, 2.4181311049e-2f, 4.5470025998e-2f, 7.4953002686e-2f,
                           1.6666752422e-1f};
    const L half = s + s * z * lanes::polynomial(z, c);  // lanes::asin(lanes::sqrt((1 - |x|) / 2))
    const L nearOne = lanes::select(x < L(0.0f), L(kPi) - (half + half), half + half);
    return lanes::select(ax > L(0.5f), nearOne, L(kHalfPi) - lanes::asin(x));
}

// atan with the reduction of Cephes atanf (three intervals).
template <class L>
SSRT_INLINE L atan(L x) {
    const L ax = lanes::abs(x);
    const auto far = ax > L(2.414213562373095f);
    const auto mid = (ax > L(0.4142135623730950f)) & !far;
    const L t = lanes::select(far, L(-1.0f) / lanes::select(far, ax, L(1.0f)),
                              lanes::select(mid, (ax - L(1.0f)) / (ax + L(1.0f)), ax));
    const L base = lanes::select(far, L(kHalfPi), lanes::select(mid, L(0.25f * kPi), L(0.0f)));
    const L z = t * t;
    constexpr float c[] = {8.05374449538e-2f, -1.38776856032e-1f, 1.99777106478e-1f,
                           -3.33329491539e-1f};
    const L r = base + (t + t * z * lanes::polynomial(z, c));
    return lanes::select(x < L(0.0f), L(0.0f) - r, r);
}

// atan2(y, x) in (-pi, pi]; atan2(y, -0) = atan2(y, +0): the sign of a zero x is ignored.
template <class L>
SSRT_INLINE L atan2(L y, L x) {
    const L ax = lanes::abs(x), ay = lanes::abs(y);
    const L num = lanes::min(ax, ay), den = lanes::max(ax, ay);
    const L a = lanes::atan(num / lanes::select(den > L(0.0f), den, L(1.0f)));
    L r = lanes::select(ay > ax, L(kHalfPi) - a, a);
    r = lanes::select(x < L(0.0f), L(kPi) - r, r);
    return lanes::select(y < L(0.0f), L(0.0f) - r, r);
}

}  // namespace ssrt::lanes
