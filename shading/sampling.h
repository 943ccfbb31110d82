// Direction samplers and their exact PDFs, written once over the lane type.
//
// Local frame: normal on +z. wi is the view direction (pointing away from the surface), wm
// a microfacet normal (half vector), wo the sampled direction (reflection of wi about wm).
// Every sampler takes its two uniform numbers u1, u2 in [0, 1) explicitly and comes with a
// PDF function over the same domain (solid angle): `sampleX(..., u1, u2)` / `xPdf(..., w)`.
// The PDFs are exact over the whole sphere (0 where the sampler never lands), so a histogram
// of the samples can be held against them (tests/shading/sampling_chi2_test.cpp).
//
// Alphas are clamped to [kMinAlpha, 1] here: below 1e-4 D no longer fits in a float.
#pragma once

#include "core/lane_math.h"
#include "core/lane_vec.h"
#include "shading/brdf.h"

namespace ssrt::sampling {

namespace ln = ssrt::lanes;
using ln::V3;

inline constexpr float kMinAlpha = 1.0e-4f;
inline constexpr float kTwoPi = 6.28318530717958647692f;
inline constexpr float kInvTwoPi = 0.159154943091895335769f;

template <class L>
SSRT_INLINE L clampAlpha(L a) {
    return ln::clamp(a, L(kMinAlpha), L(1.0f));
}

// Mirror reflection of wi about the unit vector wm: 2 (wi.wm) wm - wi.
template <class L>
SSRT_INLINE V3<L> reflect(V3<L> wi, V3<L> wm) {
    const L d = ln::dot(wi, wm);
    return wm * (d + d) - wi;
}

// ---- Cosine and uniform hemisphere ------------------------------------------------------

// Malley's method: a uniform point on the disk (polar map) lifted to the hemisphere.
template <class L>
SSRT_INLINE V3<L> sampleCosineHemisphere(L u1, L u2) {
    L s, c;
    ln::sincos(L(kTwoPi) * u2, s, c);
    const L r = ln::sqrt(u1);
    return {r * c, r * s, ln::sqrt(ln::max(L(1.0f) - u1, L(0.0f)))};
}
template <class L>
SSRT_INLINE L cosineHemispherePdf(V3<L> wo) {
    return ln::select(wo.z > L(0.0f), wo.z * L(ln::kInvPi), L(0.0f));
}

// z uniform in (0, 1] (Archimedes: equal heights cut equal areas of the sphere).
template <class L>
SSRT_INLINE V3<L> sampleUniformHemisphere(L u1, L u2) {
    L s, c;
    ln::sincos(L(kTwoPi) * u2, s, c);
    const L z = L(1.0f) - u1;
    const L r = ln::sqrt(ln::max(L(1.0f) - z * z, L(0.0f)));
    return {r * c, r * s, z};
}
template <class L>
SSRT_INLINE L uniformHemispherePdf(V3<L> wo) {
    return ln::select(wo.z > L(0.0f), L(kInvTwoPi), L(0.0f));
}

// ---- GGX NDF sampling (of D(m) cos(theta_m)) --------------------------------------------
// Walter et al. 2007, eq. 35-36: theta = acos(sqrt((1 - u) / (u (a^2 - 1) + 1))), phi = 2 pi v.
// Written as the normalisation of (ax sqrt(u) cos phi, ay sqrt(u) sin phi, sqrt(1 - u)): its
// squared length is u (a^2 - 1) + 1, so for ax = ay its cosine is exactly the formula above,
// while sin(theta) comes out without the cancellation of sqrt(1 - cos^2). The anisotropic
// case is the same slope-space stretch (Heitz 2014, sec. 5.3).
template <class L>
SSRT_INLINE V3<L> sampleGgxNdf(L ax, L ay, L u1, L u2) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    L s, c;
    ln::sincos(L(kTwoPi) * u2, s, c);
    const L r = ln::sqrt(u1);
    return ln::normalize(V3<L>{ax * r * c, ay * r * s, ln::sqrt(ln::max(L(1.0f) - u1, L(0.0f)))});
}
// PDF over the half vector: D(m) m.z.
template <class L>
SSRT_INLINE L ggxNdfPdf(V3<L> wm, L ax, L ay) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    return brdf::D_GGXAniso(wm.x, wm.y, wm.z, ax, ay) * ln::max(wm.z, L(0.0f));
}

// Reflection version: wo = reflect(wi, wm). Each wo has the two half vectors +-h, h =
// normalize(wi + wo); exactly one lies above the surface, and |dwm/dwo| = 1 / (4 |wi.h|).
// For unit vectors 1 + wi.wo = |wi + wo|^2 / 2, so |wi.h| = |wi + wo| / 2: the PDF is
// D(h) h.z / (2 |wi + wo|). (Taking wi.h by a dot product instead loses all its digits where
// wo nears -wi, which grazing views reach with half vectors near the normal, and where this
// PDF peaks.)
template <class L>
SSRT_INLINE V3<L> sampleGgxNdfReflection(V3<L> wi, L ax, L ay, L u1, L u2) {
    return reflect(wi, sampleGgxNdf(ax, ay, u1, u2));
}
template <class L>
SSRT_INLINE L ggxNdfReflectionPdf(V3<L> wi, V3<L> wo, L ax, L ay) {
    const V3<L> v = wi + wo;
    const L len2 = ln::dot(v, v);
    const auto ok = len2 > L(0.0f);
    const L len = ln::sqrt(ln::select(ok, len2, L(1.0f)));
    V3<L> h = v * (L(1.0f) / len);
    h = ln::select(h.z < L(0.0f), V3<L>{L(0.0f) - h.x, L(0.0f) - h.y, L(0.0f) - h.z}, h);
    return ln::select(ok, ggxNdfPdf(h, ax, ay) / (len + len), L(0.0f));
}

// ---- VNDF: distribution of visible normals ----------------------------------------------
// D_wi(m) = G1(wi) max(0, wi.m) D(m) / wi.z  (Heitz 2014, eq. 16). With t = smithT(wi) and
// G1 = 2 wi.z / (wi.z + t) this is 2 D(m) max(0, wi.m) / (t + wi.z), which stays finite at
// the horizon. For wi.z < 0 the spherical-cap samplers below keep the part of the
// microsurface above the horizon that wi sees; its projected area is (t + wi.z) / 2 as well,
// written (t - wi.z) / (2 (t^2 - wi.z^2)) to avoid the cancellation (Eto and Tokuyoshi 2023).

// 1 / (t + b) for b in [-t, t], the stable form when b < 0: (t - b) / |wi.xy stretched|^2.
template <class L>
SSRT_INLINE L invTPlusB(V3<L> wi, L ax, L ay, L b) {
    const L px = ax * wi.x, py = ay * wi.y;
    const L len2 = px * px + py * py;
    const L t = ln::sqrt(len2 + wi.z * wi.z);
    const L pos = L(1.0f) / ln::max(t + b, L(1.0e-30f));
    const L neg = (t - b) / ln::max(len2, L(1.0e-30f));
    return ln::select(b >= L(0.0f), pos, neg);
}

// The standard VNDF PDF over the half vector (ellipsoid and spherical-cap samplers).
template <class L>
SSRT_INLINE L vndfPdf(V3<L> wi, V3<L> wm, L ax, L ay) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    const L d = brdf::D_GGXAniso(wm.x, wm.y, wm.z, ax, ay);
    const L im = ln::max(ln::dot(wi, wm), L(0.0f));
    return L(2.0f) * d * im * invTPlusB(wi, ax, ay, wi.z);
}
// Its reflection version: D_wi(h) / (4 wi.h) = D(h) / (2 (t + wi.z)), h = normalize(wi + wo).
template <class L>
SSRT_INLINE L vndfReflectionPdf(V3<L> wi, V3<L> wo, L ax, L ay) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    const V3<L> h = ln::normalize(wi + wo);
    const L d = brdf::D_GGXAniso(h.x, h.y, h.z, ax, ay);
    return ln::select(ln::dot(wi, h) > L(0.0f), L(0.5f) * d * invTPlusB(wi, ax, ay, wi.z), L(0.0f));
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1: stretch the
// view to the hemisphere configuration, sample the projected area of the hemisphere (a disk
// whose far half is squashed by (1 + Vh.z) / 2), lift to the hemisphere, un-stretch.
// Defined for wi.z >= 0 (below the horizon the view is clamped onto it).
template <class L>
SSRT_INLINE V3<L> sampleVndfEllipsoid(V3<L> wi, L ax, L ay, L u1, L u2) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    // Transform the view direction to the hemisphere configuration
    const V3<L> vh = ln::normalize(V3<L>{ax * wi.x, ay * wi.y, ln::max(wi.z, L(0.0f))});
    // Orthonormal basis (with special case if cross product is zero)
    const L lensq = vh.x * vh.x + vh.y * vh.y;
    const auto flat = lensq > L(0.0f);
    const L inv = L(1.0f) / ln::sqrt(ln::select(flat, lensq, L(1.0f)));
    const V3<L> t1 = {ln::select(flat, (L(0.0f) - vh.y) * inv, L(1.0f)),
                      ln::select(flat, vh.x * inv, L(0.0f)), L(0.0f)};
    const V3<L> t2 = ln::cross(vh, t1);
    // Parameterization of the projected area
    L s, c;
    ln::sincos(L(kTwoPi) * u2, s, c);
    const L r = ln::sqrt(u1);
    const L p1 = r * c;
    const L sh = L(0.5f) * (L(1.0f) + vh.z);
    const L p2 = (L(1.0f) - sh) * ln::sqrt(ln::max(L(1.0f) - p1 * p1, L(0.0f))) + sh * (r * s);
    // Reprojection onto the hemisphere
    const L pz = ln::sqrt(ln::max(L(1.0f) - p1 * p1 - p2 * p2, L(0.0f)));
    const V3<L> nh = t1 * p1 + t2 * p2 + vh * pz;
    // Transforming the normal back to the ellipsoid configuration
    return ln::normalize(V3<L>{ax * nh.x, ay * nh.y, ln::max(nh.z, L(0.0f))});
}
template <class L>
SSRT_INLINE V3<L> sampleVndfEllipsoidReflection(V3<L> wi, L ax, L ay, L u1, L u2) {
    return reflect(wi, sampleVndfEllipsoid(wi, ax, ay, u1, u2));
}

// Dupuy and Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps", listing 3:
// in the stretched configuration the visible normal is the halfway vector of the view and a
// uniform point on the spherical cap z in (-b, 1] (b = wi.z for the full VNDF; works for
// wi.z < 0 as well).
//
// Written in terms of the cap height w = 1 + b instead of b: z = 1 - u2 w and
// 1 - z^2 = u2 w (2 - u2 w), and the halfway vector's z = z + wi.z = (1 - u2) w + (wi.z - b).
// Seen from below a smooth surface (wi.z < 0, small alpha) the cap is tiny and 1 + wi.z,
// 1 - z^2 and z + wi.z would all cancel in float; w itself is computed without cancellation
// (capHeight below), which keeps the samples exact to a few ulp there too.
template <class L>
SSRT_INLINE V3<L> sampleVndfCapStd(V3<L> wiStd, L w, L zOffset, L u1, L u2) {
    // Sample a spherical cap of height w
    L s, c;
    ln::sincos(L(kTwoPi) * u1, s, c);
    const L uw = u2 * w;
    const L sinTheta = ln::sqrt(ln::max(uw * (L(2.0f) - uw), L(0.0f)));
    // Compute the halfway direction (unnormalised)
    return {sinTheta * c + wiStd.x, sinTheta * s + wiStd.y, (L(1.0f) - u2) * w + zOffset};
}

// 1 + wiStd.z with wiStd = normalize(ax wi.x, ay wi.y, wi.z) = (..., wi.z / t): for wi.z < 0
// it is (t + wi.z) / t = len2 / (t (t - wi.z)), len2 = (ax wi.x)^2 + (ay wi.y)^2.
template <class L>
SSRT_INLINE L capHeight(V3<L> wi, L ax, L ay) {
    const L px = ax * wi.x, py = ay * wi.y;
    const L len2 = px * px + py * py;
    const L t = ln::sqrt(len2 + wi.z * wi.z);
    const L tSafe = ln::max(t, L(1.0e-30f));
    const L above = L(1.0f) + wi.z / tSafe;
    const L below = len2 / (tSafe * ln::max(t - wi.z, L(1.0e-30f)));
    return ln::select(wi.z >= L(0.0f), above, below);
}

template <class L>
SSRT_INLINE V3<L> sampleVndfSphericalCaps(V3<L> wi, L ax, L ay, L u1, L u2) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    // Warp to the hemisphere configuration
    const V3<L> wiStd = ln::normalize(V3<L>{ax * wi.x, ay * wi.y, wi.z});
    const V3<L> wmStd = sampleVndfCapStd(wiStd, capHeight(wi, ax, ay), L(0.0f), u1, u2);
    // Warp back to the ellipsoid configuration
    return ln::normalize(V3<L>{ax * wmStd.x, ay * wmStd.y, wmStd.z});
}
template <class L>
SSRT_INLINE V3<L> sampleVndfSphericalCapsReflection(V3<L> wi, L ax, L ay, L u1, L u2) {
    return reflect(wi, sampleVndfSphericalCaps(wi, ax, ay, u1, u2));
}

// ---- Bounded VNDF -----------------------------------------------------------------------
// Eto and Tokuyoshi 2023, "Bounded VNDF Sampling for Smith-GGX Reflections", listing 1.
// Part of the cap (-wi.z, -k wi.z] only ever yields reflections below the horizon; the
// tighter bound k (eq. 5, with a = min(ax, ay), eq. 6) cuts it off for wi.z > 0:
//   k = (1 - a^2) s^2 / (s^2 + a^2 wi.z^2),  s = 1 + |wi.xy|.
// Over the remaining cap the PDF is the VNDF renormalised: 2 D(m) (wi.m) / (t + k wi.z)
// over the half vector (eq. 8), D(h) / (2 (t + k wi.z)) over the reflection. For wi.z < 0
// the cap is (-wi.z, 1] as in Dupuy and Benyoub, with the stable form of the normaliser.
template <class L>
SSRT_INLINE L vndfBoundedK(V3<L> wi, L ax, L ay) {
    const L a = ln::saturate(ln::min(ax, ay));
    const L s = L(1.0f) + ln::sqrt(wi.x * wi.x + wi.y * wi.y);
    const L a2 = a * a, s2 = s * s;
    return (L(1.0f) - a2) * s2 / (s2 + a2 * wi.z * wi.z);
}
// The bound b of the world-space normaliser t + b: k wi.z above the horizon, wi.z below.
template <class L>
SSRT_INLINE L vndfBoundedB(V3<L> wi, L ax, L ay) {
    return ln::select(wi.z > L(0.0f), vndfBoundedK(wi, ax, ay) * wi.z, wi.z);
}

template <class L>
SSRT_INLINE V3<L> sampleVndfBounded(V3<L> wi, L ax, L ay, L u1, L u2) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    const V3<L> wiStd = ln::normalize(V3<L>{ax * wi.x, ay * wi.y, wi.z});
    // Above the horizon the cap is (-k wiStd.z, 1]: height 1 + k wiStd.z, and the halfway
    // vector's z gains (1 - k) wiStd.z; below it, the full cap of Dupuy and Benyoub.
    const auto above = wi.z > L(0.0f);
    const L k = vndfBoundedK(wi, ax, ay);
    const L w = ln::select(above, L(1.0f) + k * wiStd.z, capHeight(wi, ax, ay));
    const L zOffset = ln::select(above, (L(1.0f) - k) * wiStd.z, L(0.0f));
    const V3<L> wmStd = sampleVndfCapStd(wiStd, w, zOffset, u1, u2);
    return ln::normalize(V3<L>{ax * wmStd.x, ay * wmStd.y, wmStd.z});
}
template <class L>
SSRT_INLINE V3<L> sampleVndfBoundedReflection(V3<L> wi, L ax, L ay, L u1, L u2) {
    return reflect(wi, sampleVndfBounded(wi, ax, ay, u1, u2));
}

// True where the half vector wm lies in the sampled cap: its stretched direction d reflects
// the stretched view to o_std = 2 (d.wiStd) d - wiStd, which must have o_std.z > -b_std,
// i.e. 2 (d.wiStd) d.z + (b_std - wiStd.z) > 0 (the bracket is 0 below the horizon).
// (Always true when the reflection is above the horizon; the test suite checks that.)
template <class L>
SSRT_INLINE ln::MaskOf<L> vndfBoundedInCap(V3<L> wi, V3<L> wm, L ax, L ay) {
    const V3<L> wiStd = ln::normalize(V3<L>{ax * wi.x, ay * wi.y, wi.z});
    const L gap =
        ln::select(wi.z > L(0.0f), (vndfBoundedK(wi, ax, ay) - L(1.0f)) * wiStd.z, L(0.0f));
    const V3<L> d = ln::normalize(V3<L>{wm.x / ax, wm.y / ay, wm.z});
    const L di = ln::dot(d, wiStd);
    // (a rounding's worth of slack: samples drawn on the cap's rim must keep a positive PDF)
    return (di + di) * d.z + gap >= L(-1.0e-6f);
}

template <class L>
SSRT_INLINE L vndfBoundedPdf(V3<L> wi, V3<L> wm, L ax, L ay) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    const L d = brdf::D_GGXAniso(wm.x, wm.y, wm.z, ax, ay);
    const L im = ln::max(ln::dot(wi, wm), L(0.0f));
    const L pdf = L(2.0f) * d * im * invTPlusB(wi, ax, ay, vndfBoundedB(wi, ax, ay));
    return ln::select(vndfBoundedInCap(wi, wm, ax, ay), pdf, L(0.0f));
}
template <class L>
SSRT_INLINE L vndfBoundedReflectionPdf(V3<L> wi, V3<L> wo, L ax, L ay) {
    ax = clampAlpha(ax);
    ay = clampAlpha(ay);
    const V3<L> h = ln::normalize(wi + wo);
    const L d = brdf::D_GGXAniso(h.x, h.y, h.z, ax, ay);
    const L pdf = L(0.5f) * d * invTPlusB(wi, ax, ay, vndfBoundedB(wi, ax, ay));
    const auto ok = (ln::dot(wi, h) > L(0.0f)) & vndfBoundedInCap(wi, h, ax, ay);
    return ln::select(ok, pdf, L(0.0f));
}

}  // namespace ssrt::sampling
