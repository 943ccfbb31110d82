// BRDF terms, written once over the lane type (float or xsimd::batch<float, A>).
// Names follow the literature as Filament does; each term opens with its source.
// Directions are unit vectors; dot products are clamped by the caller.
#pragma once

#include "core/lane_math.h"
#include "core/lane_vec.h"

namespace ssrt::brdf {

namespace ln = ssrt::lanes;
using ln::V3;

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
    return ln::select(denom > L(0.0f), L(0.5f) / ln::select(denom > L(0.0f), denom, L(1.0f)),
                      L(0.0f));
}

// D_GGX(NoH, alpha) x V_SmithGGXCorrelated(NoV, NoL, alpha) for one view and many light
// directions (the SSR resolve weighs 9 neighbours' rays by one pixel's lobe): the terms of
// alpha and NoV alone are computed once. Every product has the bits of the two functions
// above: the same expressions in the same order (tests/shading/sampling_test.cpp).
template <class L>
struct GgxDV {
    L a2, a2m1, oneMinusA2, NoV, viewRoot;

    SSRT_INLINE GgxDV(L NoV_, L alpha)
        : a2(alpha * alpha),
          a2m1(a2 - L(1.0f)),
          oneMinusA2(L(1.0f) - a2),
          NoV(NoV_),
          viewRoot(ln::sqrt(NoV_ * NoV_ * oneMinusA2 + a2)) {}

    SSRT_INLINE L operator()(L NoH, L NoL) const {
        const L f = (NoH * NoH) * a2m1 + L(1.0f);
        const L d = a2 / (L(ln::kPi) * f * f);
        const L lv = NoL * viewRoot;
        const L ll = NoV * ln::sqrt(NoL * NoL * oneMinusA2 + a2);
        const L denom = lv + ll;
        const L v = ln::select(denom > L(0.0f),
                               L(0.5f) / ln::select(denom > L(0.0f), denom, L(1.0f)), L(0.0f));
        return d * v;
    }
};

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

// ---- Anisotropic GGX and the Smith masking terms ----------------------------------------
// Local frame: normal on +z, tangent on +x. alpha_x, alpha_y are the GGX roughnesses along
// the tangent and bitangent; the isotropic functions above are the case alpha_x = alpha_y.

// Burley 2012, "Physically-Based Shading at Disney", appendix B (anisotropic GGX)
// D(m) = 1 / (pi ax ay ((mx/ax)^2 + (my/ay)^2 + mz^2)^2) for mz > 0, else 0.
template <class L>
SSRT_INLINE L D_GGXAniso(L mx, L my, L mz, L ax, L ay) {
    const L sx = mx / ax, sy = my / ay;
    const L f = (sx * sx + sy * sy) + mz * mz;
    const L d = L(1.0f) / (L(ln::kPi) * ax * ay * f * f);
    return ln::select(mz > L(0.0f), d, L(0.0f));
}

// Projected roughness term of Smith's Lambda: t = sqrt(wz^2 + ax^2 wx^2 + ay^2 wy^2), so that
// Lambda(w) = (t / |wz| - 1) / 2 and the division by wz (infinite at the horizon) is avoided.
template <class L>
SSRT_INLINE L smithT(L wx, L wy, L wz, L ax, L ay) {
    const L px = ax * wx, py = ay * wy;
    return ln::sqrt((px * px + py * py) + wz * wz);
}

// Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 86
// Lambda(w) = (-1 + sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2)) / 2; huge (not inf) at wz = 0.
template <class L>
SSRT_INLINE L Lambda_GGX(L wx, L wy, L wz, L ax, L ay) {
    const L t = smithT(wx, wy, wz, ax, ay);
    const L az = ln::max(ln::abs(wz), L(1.0e-30f));
    return L(0.5f) * (t / az - L(1.0f));
}

// Smith G1 = 1 / (1 + Lambda) = 2 |wz| / (|wz| + t): exact 0 at the horizon, 1 along +z.
template <class L>
SSRT_INLINE L G1_GGX(L wx, L wy, L wz, L ax, L ay) {
    const L az = ln::abs(wz);
    const L t = smithT(wx, wy, wz, ax, ay);
    const L den = az + t;
    return ln::select(den > L(0.0f), (az + az) / ln::select(den > L(0.0f), den, L(1.0f)), L(0.0f));
}

// Heitz 2014, eq. 99: height-correlated G2 = 1 / (1 + Lambda_i + Lambda_o)
//   = 2 |iz| |oz| / (t_i |oz| + t_o |iz|)   (both on the upper side; 0 otherwise).
template <class L>
SSRT_INLINE L G2_GGXCorrelated(V3<L> wi, V3<L> wo, L ax, L ay) {
    const L iz = wi.z, oz = wo.z;
    const L ti = smithT(wi.x, wi.y, iz, ax, ay), to = smithT(wo.x, wo.y, oz, ax, ay);
    const L den = ti * oz + to * iz;
    const auto ok = (iz > L(0.0f)) & (oz > L(0.0f)) & (den > L(0.0f));
    return ln::select(ok, L(2.0f) * iz * oz / ln::select(ok, den, L(1.0f)), L(0.0f));
}

// Visibility V = G2 / (4 iz oz) = 0.5 / (t_i oz + t_o iz), anisotropic form of
// V_SmithGGXCorrelated above (Heitz 2014; Filament's V_SmithGGXCorrelated_Anisotropic).
template <class L>
SSRT_INLINE L V_SmithGGXCorrelatedAniso(V3<L> wi, V3<L> wo, L ax, L ay) {
    const L iz = wi.z, oz = wo.z;
    const L ti = smithT(wi.x, wi.y, iz, ax, ay), to = smithT(wo.x, wo.y, oz, ax, ay);
    const L den = ti * oz + to * iz;
    const auto ok = (iz > L(0.0f)) & (oz > L(0.0f)) & (den > L(0.0f));
    return ln::select(ok, L(0.5f) / ln::select(ok, den, L(1.0f)), L(0.0f));
}

// Single-scattering GGX specular lobe with F = 1, cosine included: f(wi, wo) wo.z.
template <class L>
SSRT_INLINE L specularCos(V3<L> wi, V3<L> wo, L ax, L ay) {
    const V3<L> m = ln::normalize(wi + wo);
    return D_GGXAniso(m.x, m.y, m.z, ax, ay) * V_SmithGGXCorrelatedAniso(wi, wo, ax, ay) * wo.z;
}

// Schlick Fresnel with F90 = 1 (the common case of F_Schlick above).
template <class L>
SSRT_INLINE L F_Schlick(L VoH, L f0) {
    return F_Schlick(VoH, f0, L(1.0f));
}

// HDRP's screen-space reflection weight (Unity HDRP, ScreenSpaceReflections.compute): with
// o drawn from the VNDF of i and F = 1, f cos / pdf = G2 / G1(i)
//   = (1 + Lambda_i) / (1 + Lambda_i + Lambda_o) = oz (iz + t_i) / (t_i oz + t_o iz).
template <class L>
SSRT_INLINE L ssrSampleWeight(V3<L> wi, V3<L> wo, L ax, L ay) {
    const L iz = wi.z, oz = wo.z;
    const L ti = smithT(wi.x, wi.y, iz, ax, ay), to = smithT(wo.x, wo.y, oz, ax, ay);
    const L den = ti * oz + to * iz;
    const auto ok = (iz > L(0.0f)) & (oz > L(0.0f)) & (den > L(0.0f));
    return ln::select(ok, oz * (iz + ti) / ln::select(ok, den, L(1.0f)), L(0.0f));
}

}  // namespace ssrt::brdf
