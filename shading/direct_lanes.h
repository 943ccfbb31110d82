// Lane-generic pieces of the direct kernel (shading/direct_kernel.cpp) that other kernels
// share, written once over the lane type L (float or xsimd::batch<float, A>): the sky
// radiance along a direction (SSGI misses read it), and the tone map and sRGB encoding of
// `display` (the composite ends with them). Templates and always_inline only: every ISA copy
// compiles its own (see core/lanes.h), and the direct kernel keeps its bits.
#pragma once

#include "core/lane_math.h"
#include "core/lane_vec.h"
#include "shading/direct_kernel.h"
#include "shading/environment.h"

namespace ssrt::shade {

namespace ln = ssrt::lanes;
using ln::V3;

template <class L>
SSRT_INLINE V3<L> splat3(const float* v) {
    return {L(v[0]), L(v[1]), L(v[2])};
}

template <class L>
SSRT_INLINE V3<L> mix3(V3<L> a, V3<L> b, L t) {
    return a + (b - a) * t;
}

// Bilinear lookup of level `level` of the equirect sky at direction d, times its intensity.
template <class L>
SSRT_INLINE V3<L> envRadiance(const DirectArgs& a, int level, V3<L> d) {
    L u, v;
    env::directionToUv(d, u, v);
    return env::sampleBilinear(a.envLevel[level], u, v) * L(a.envIntensity);
}

// The analytic sky: ground below the horizon, horizon to zenith above (scenes/scene.cpp);
// or the equirect image (level 0) when a.envLevelCount > 0. `dir` is a world direction
// (unit for the image; the gradient reads only dir.y of a unit vector).
template <class L>
SSRT_INLINE V3<L> skyRadiance(const DirectArgs& a, V3<L> dir) {
    if (a.envLevelCount > 0) return envRadiance(a, 0, dir);
    if (!a.skyGradient) return splat3<L>(a.skyZenith);
    const L y = dir.y;
    const L s = L(1.0f) - y;
    const V3<L> above = mix3(splat3<L>(a.skyHorizon), splat3<L>(a.skyZenith), L(1.0f) - s * s);
    return ln::select(y < L(0.0f), splat3<L>(a.skyGround), above);
}

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve"
template <class L>
SSRT_INLINE L tonemapAces(L x) {
    const L num = x * (L(2.51f) * x + L(0.03f));
    const L den = x * (L(2.43f) * x + L(0.59f)) + L(0.14f);
    return ln::saturate(num / den);
}

// IEC 61966-2-1 sRGB transfer function.
template <class L>
SSRT_INLINE L srgbEncode(L x) {
    const L hi = L(1.055f) * ln::pow(x, L(1.0f / 2.4f)) - L(0.055f);
    return ln::select(x <= L(0.0031308f), x * L(12.92f), hi);
}

// `display` from linear, exposed colour: ACES, then sRGB.
template <class L>
SSRT_INLINE L displayEncode(L x) {
    return srgbEncode(tonemapAces(x));
}

}  // namespace ssrt::shade
