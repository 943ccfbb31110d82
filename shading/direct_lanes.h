// Lane-generic pieces of the direct kernel (shading/direct_kernel.cpp) that other kernels
// share, written once over the lane type L (float or xsimd::batch<float, A>): the sky
// radiance along a direction (SSGI misses read it), the per-point shading model (the
// reference image shades its hits with it, L = float), and the tone map and sRGB encoding
// of `display` (the composite ends with them). Templates and always_inline only: every ISA copy
// compiles its own (see core/lanes.h), and the direct kernel keeps its bits.
#pragma once

#include "core/lane_math.h"
#include "core/lane_vec.h"
#include "shading/brdf.h"
#include "shading/direct_kernel.h"
#include "shading/environment.h"
#include "shading/irradiance_sh.h"
#include "shading/multiscatter.h"
#include "shading/shadow_bounds.h"

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

// The prefiltered sky LD(r, roughness): linear between the two levels around roughness *
// (levels - 1), bilinear in each. Lanes may need different levels, so each level that any
// lane needs is read for all lanes and weighted by zero where it is not needed (x + 0 * y is
// x for finite y: the same bits as reading only the two levels, as the scalar copy does).
template <class L>
SSRT_INLINE V3<L> envPrefiltered(const DirectArgs& a, V3<L> r, L roughness) {
    const int n = a.envLevelCount;
    const L f = ln::saturate(roughness) * L(float(n - 1));
    const L i0 = ln::min(ln::floor(f), L(float(n - 2)));
    const L t = f - i0;
    L u, v;
    env::directionToUv(r, u, v);
    V3<L> sum{L(0.0f), L(0.0f), L(0.0f)};
    for (int k = 0; k < n; ++k) {
        const L lk = L(float(k));
        const L w = ln::select(i0 == lk, L(1.0f) - t, ln::select(i0 + L(1.0f) == lk, t, L(0.0f)));
        if (!ln::any(w > L(0.0f))) continue;
        sum = sum + env::sampleBilinear(a.envLevel[k], u, v) * w;
    }
    return sum * L(a.envIntensity);
}

// The shadow map's answer at a surface point p with normal n, the fraction of its PCF taps
// that see the light (taps clamped to the map's edge; points outside the map are lit:
// nothing there casts a shadow).
//
// Receiver plane (Isidoro 2006, "Shadow Mapping: GPU-based Tips and Techniques"): each tap
// compares the map's depth at its texel centre with the receiver's plane extended to that
// centre, not with p's own depth, so a tilted receiver meets itself in every tap and needs
// no slope-scaled bias. The map is orthographic (raster/shadow_map.cpp), clip = A p + b with
// the rows a_i of A orthogonal (a rotation scaled per axis), so the plane's clip-space
// normal is A^-T n, n_c,i = (a_i . n) / |a_i|^2, and with texel coordinates
// fu = (cx + 1) s / 2, fv = (1 - cy) s / 2 and key = (1 - cz) / 2 the plane's key changes
// per texel by
//   dkey/dfu = n_c,x / (s n_c,z),   dkey/dfv = -n_c,y / (s n_c,z),
// n_c,z = (a_z . l)(n . l) / |a_z|^2 (a_z is parallel to the light), with n . l floored at
// kShadowMinCos so that the plane stays finite at grazing light.
//
// Each tap's gap = map - plane (positive: something nearer the light) is
//   receiver  |gap| <= tol: the map sees the receiver itself;
//   occluder  gap > tol: something nearer the light; `far` past creaseTol;
//   absent    gap < -tol: the map sees past the plane, so the receiver does not reach that
//             texel (its edge, or a surface curving away): the tap knows nothing of p.
// Where two surfaces meet (a crease: the green wall against the back wall and on the floor),
// the one the light sees lies nearer the other's extended plane on its own side of the
// crease, and plain PCF cannot tell a contact shadow from a lit corner: at the back wall's
// corner by the green wall, the taps past the corner see nothing (lit, before: the bright
// seam, and a slope-scaled bias let the green wall's own nearest taps pass as well); by the
// red wall, which the light sees, the taps past the corner see the red wall (shadow: a dark
// seam without that bias). Which side p is on, p's own texel (the centre tap) says, so
// occluder taps within the crease's reach (creaseTol: how far two planes of slopes up to the
// receiver's and kShadowCreaseTan part across the taps) and absent taps take p's answer:
//   p is shadowed when the centre is an occluder; or when the centre is absent, or is the
//   only tap that sees the receiver (a crease runs through it), and some tap is an occluder.
// A shadowed p counts only the taps that see its plane to within exactTol (rounding: a flat
// receiver's plane is exact) as lit, so a crease's neighbour is never light; a lit p counts
// every tap but the far occluders, so the edge of a shadow cast from afar is filtered as
// before. The counts are whole numbers of taps: every ISA adds them in the same bits.
inline constexpr float kShadowCreaseTan = 10.0f;
inline constexpr float kShadowMinCos = 1e-3f;                 // tan about 1000
inline constexpr int kShadowMaxTaps = 2 * kMaxPcfRadius + 1;  // per side

// The squared lengths of the rows a_x, a_y, a_z of the light's clip matrix (column-major m).
struct ShadowAxes {
    float ax2, ay2, az2;
};
SSRT_INLINE ShadowAxes shadowAxes(const float* m) {
    return {(m[0] * m[0] + m[4] * m[4]) + m[8] * m[8], (m[1] * m[1] + m[5] * m[5]) + m[9] * m[9],
            (m[2] * m[2] + m[6] * m[6]) + m[10] * m[10]};
}

// Where p falls in the shadow map and its receiver's plane there (shadowVisibility).
template <class L>
struct ShadowPlane {
    L u, v;      // p's texel (floored texel coordinates; in the map where inMap)
    L key;       // p's own depth key
    L gu, gv;    // the plane's key per texel in u and v
    L du0, dv0;  // from p to the centre tap's texel centre, in texels
    ln::MaskOf<L> inMap;
};

template <class L>
SSRT_INLINE ShadowPlane<L> shadowPlane(const DirectArgs& a, V3<L> p, V3<L> n, L cosL) {
    const float* m = a.lightViewProj;
    const L cx = ((L(m[0]) * p.x + L(m[4]) * p.y) + L(m[8]) * p.z) + L(m[12]);
    const L cy = ((L(m[1]) * p.x + L(m[5]) * p.y) + L(m[9]) * p.z) + L(m[13]);
    const L cz = ((L(m[2]) * p.x + L(m[6]) * p.y) + L(m[10]) * p.z) + L(m[14]);
    const L s(float(a.shadowSize));
    const L fu = (cx * L(0.5f) + L(0.5f)) * s;
    const L fv = (L(0.5f) - cy * L(0.5f)) * s;
    ShadowPlane<L> q;
    q.u = ln::floor(fu);
    q.v = ln::floor(fv);
    q.key = L(0.5f) - L(0.5f) * cz;
    q.inMap = (q.u >= L(0.0f)) & (q.v >= L(0.0f)) & (q.u < s) & (q.v < s);
    // The plane's key per texel (the derivation above).
    const auto [ax2, ay2, az2] = shadowAxes(m);
    const float* l = a.toLight;
    const float azl = ((m[2] * l[0] + m[6] * l[1]) + m[10] * l[2]) / az2;
    const L ncx = (((L(m[0]) * n.x + L(m[4]) * n.y) + L(m[8]) * n.z)) / L(ax2);
    const L ncy = (((L(m[1]) * n.x + L(m[5]) * n.y) + L(m[9]) * n.z)) / L(ay2);
    const L sncz = s * (L(azl) * cosL);
    q.gu = ncx / sncz;
    q.gv = (L(0.0f) - ncy) / sncz;
    q.du0 = (q.u + L(0.5f)) - fu;
    q.dv0 = (q.v + L(0.5f)) - fv;
    return q;
}

// The taps' answer (shadowVisibility), lanes outside the map aside.
template <class L>
SSRT_INLINE L shadowTaps(const DirectArgs& a, const ShadowPlane<L>& q, L tol, L exactTol, L tanL) {
    using IL = ln::IntOf<L>;
    // One texel of depth in key units (the larger texel side), for the crease's reach.
    const auto [ax2, ay2, az2] = shadowAxes(a.lightViewProj);
    const float texelKey = ln::sqrt(az2) / (float(a.shadowSize) * ln::sqrt(ln::min(ax2, ay2)));
    const int r = a.pcfRadius;
    const L creaseTol = tol + (tanL + L(kShadowCreaseTan)) * L(float(2 * r + 2) * texelKey);
    const L last(float(a.shadowSize - 1));
    const L zero(0.0f), one(1.0f);
    // Counts of taps (whole numbers, exact in floats): occluders, the far ones among them (a far
    // tap is an occluder: creaseTol > tol), absent, and exact; the receivers are the rest.
    L occluder = zero, far = zero, absent = zero, exact = zero;
    L centreOccluder = zero, centreAbsent = zero;
    // Per column of taps, the same in every row: its texel and its term of the plane key.
    IL col[kShadowMaxTaps];
    L planeCol[kShadowMaxTaps];
    for (int dx = -r; dx <= r; ++dx) {
        col[dx + r] = ln::toIntTrunc(ln::clamp(q.u + L(float(dx)), zero, last));
        planeCol[dx + r] = q.gu * (q.du0 + L(float(dx)));
    }
    // Columns k and k + 1 side by side in every lane (neither clamped at the map's edge): a
    // row's two taps there are one pair gather (half the elements), the same values.
    const int n = 2 * r + 1;
    bool paired[kShadowMaxTaps] = {};
    for (int k = 0; k + 1 < n; k += 2) paired[k] = ln::all(col[k + 1] == col[k] + IL(1));
    for (int dy = -r; dy <= r; ++dy) {
        const IL row =
            ln::toIntTrunc(ln::clamp(q.v + L(float(dy)), zero, last)) * IL(int32_t(a.shadowStride));
        const L planeRow = q.gv * (q.dv0 + L(float(dy)));
        L depths[kShadowMaxTaps];
        for (int k = 0; k < n; ++k) {
            if (paired[k]) {
                ln::gatherPair(a.shadowMap, row + col[k], depths[k], depths[k + 1]);
                ++k;  // (its neighbour read with it)
            } else {
                depths[k] = ln::gather(a.shadowMap, row + col[k]);
            }
        }
        for (int dx = -r; dx <= r; ++dx) {
            const L depth = depths[dx + r];
            const L gap = depth - (q.key + (planeCol[dx + r] + planeRow));
            const auto isOccluder = gap > tol;
            const auto isAbsent = gap < L(0.0f) - tol;
            occluder = occluder + ln::select(isOccluder, one, zero);
            far = far + ln::select(gap > creaseTol, one, zero);
            absent = absent + ln::select(isAbsent, one, zero);
            exact = exact + ln::select(ln::abs(gap) <= exactTol, one, zero);
            if (dx == 0 && dy == 0) {
                centreOccluder = ln::select(isOccluder, one, zero);
                centreAbsent = ln::select(isAbsent, one, zero);
            }
        }
    }
    const L taps(float((2 * r + 1) * (2 * r + 1)));
    const L receiver = (taps - occluder) - absent;
    // p's own answer: its texel's; where that texel is past the receiver, or is the only one
    // that sees it (a crease through it), shadowed when any tap holds an occluder.
    const L centreReceiver = one - (centreOccluder + centreAbsent);
    const auto lone = (centreAbsent > zero) | ((centreReceiver > zero) & (receiver == one));
    const auto shadowed = (centreOccluder > zero) | (lone & (occluder > zero));
    // (receivers, near occluders and absent taps: every tap but the far ones)
    const L lit = ln::select(shadowed, exact, taps - far);
    return lit / taps;
}

// What the map's depth bounds (DirectArgs::shadowBounds) prove of a lane's taps without
// reading them: `lit`, no tap is an occluder, so shadowVisibility's answer is taps / taps =
// 1 exactly; `dark`, every tap is an occluder off the plane by more than exactTol, so the
// centre is one, p is shadowed and no tap is exact: 0 / taps = +0.
//
// In exact arithmetic, with the tap (dx, dy) reading texel (u + dx, v + dy) and the block's
// depth(X, Y) = off + du X + dv Y, off in [lo, hi] (shading/shadow_bounds.h; X, Y from the
// block's reference texel, x, y p's texel's), the tap's gap is
//   depth - (key + gu (du0 + dx) + gv (dv0 + dy)) = off + c + (du - gu) dx + (dv - gv) dy,
//   c = (du x + dv y) - (gu du0 + gv dv0) - key,
// so every gap lies within spread = r (|du - gu| + |dv - gv|) of [lo + c, hi + c]: a receiver
// tilted as the map's surface (du = gu, dv = gv) is bounded as tightly as a flat one. Only
// lanes whose taps all lie inside the map are decided: clamped taps read other texels.
//
// Rounding: the taps' float gap differs from the exact one by at most 6 u (|gu| (|du0| + r) +
// |gv| (|dv0| + r) + |key| + |depth|) (u = 2^-24: 7 roundings, none of a value past that
// sum), and |depth| <= |lo| + |hi| + (kShadowBlock / 2 + r) (|du| + |dv|); the bound's own
// 14 roundings, and the test's, add under 16 u of `size` below, which holds both sums. So a
// margin of 2^-18 size (64 u, nearly three times the 22 u needed) makes both tests true of
// the taps' own gaps. NaN and infinities decide nothing: they make `size` NaN or infinite, which
// fails size < 2^20 (the bound under which no float of the taps overflows; the map's keys are in
// [0, 1]); 2^-100 in the margin covers the absolute rounding of subnormal results.
template <class L>
struct ShadowBound {
    ln::MaskOf<L> lit, dark;
};

template <class L>
SSRT_INLINE ShadowBound<L> shadowBound(const DirectArgs& a, const ShadowPlane<L>& q, L tol,
                                       L exactTol) {
    const L zero(0.0f), last(float(a.shadowSize - 1)), r(float(a.pcfRadius));
    // p's block, and p's texel from the block's reference texel (whole numbers: exact).
    const L side = L(float(kShadowBlock)), perBlock = L(1.0f / float(kShadowBlock));
    const L bu = ln::floor(ln::clamp(q.u, zero, last) * perBlock);
    const L bv = ln::floor(ln::clamp(q.v, zero, last) * perBlock);
    const L x = q.u - (bu * side + L(float(kShadowBlock / 2)));
    const L y = q.v - (bv * side + L(float(kShadowBlock / 2)));
    const auto index = ln::toIntTrunc((bv * L(float(a.shadowBlocks)) + bu) * L(4.0f));
    L lo, hi, du, dv;  // ShadowBlockBounds
    ln::gatherPair(a.shadowBounds, index, lo, hi);
    ln::gatherPair(a.shadowBounds + 2, index, du, dv);
    const L c = ((du * x + dv * y) - (q.gu * q.du0 + q.gv * q.dv0)) - q.key;
    const L spread = r * (ln::abs(du - q.gu) + ln::abs(dv - q.gv));
    const L size = (((ln::abs(lo) + ln::abs(hi)) +
                     (L(float(kShadowBlock / 2)) + r) * (ln::abs(du) + ln::abs(dv))) +
                    (ln::abs(q.gu) * (ln::abs(q.du0) + r) + ln::abs(q.gv) * (ln::abs(q.dv0) + r))) +
                   ln::abs(q.key);
    const L margin = (size + L(0x1p-100f)) * L(0x1p-18f);
    const auto sure =
        (size < L(0x1p20f)) & (q.u >= r) & (q.v >= r) & (q.u <= last - r) & (q.v <= last - r);
    const L highGap = ((hi + c) + spread) + margin;
    const L lowGap = ((lo + c) - spread) - margin;
    ShadowBound<L> b;
    b.lit = sure & (highGap <= tol);
    b.dark = sure & (lowGap > tol) & (lowGap > exactTol);
    return b;
}

template <class L>
SSRT_INLINE L shadowVisibility(const DirectArgs& a, V3<L> p, V3<L> n, L cosL, L tol, L exactTol,
                               L tanL) {
    const ShadowPlane<L> q = shadowPlane(a, p, n, cosL);
    if (!ln::any(q.inMap)) return L(1.0f);
    const L zero(0.0f), one(1.0f);
    if (a.shadowBounds) {
        // When the bounds decide every lane, the taps would give the same answers.
        const ShadowBound<L> b = shadowBound(a, q, tol, exactTol);
        if (ln::all((b.lit | b.dark) | !q.inMap)) return ln::select(q.inMap & b.dark, zero, one);
    }
    return ln::select(q.inMap, shadowTaps(a, q, tol, exactTol, tanL), one);
}

// Kulla and Conty 2017, "Revisiting Physically Based Shading at Imageworks": the tint of the
// multiple-scattering lobe for one channel's F0 (Schlick, F90 = 1): F_avg^2 E_avg /
// (1 - F_avg (1 - E_avg)), F_avg = 20/21 F0 + 1/21 (shading/multiscatter.h).
template <class L>
SSRT_INLINE V3<L> multiScatterTint(V3<L> f0, L eAvg) {
    using namespace ssrt::multiscatter;
    const L one(1.0f);
    return {fMsFresnelTint(fresnelAvg(f0.x, one), eAvg),
            fMsFresnelTint(fresnelAvg(f0.y, one), eAvg),
            fMsFresnelTint(fresnelAvg(f0.z, one), eAvg)};
}

// A surface point to shade, world space.
template <class L>
struct Surface {
    V3<L> p, n, albedo, view;  // view: unit, from the surface towards the viewer
    L metallic, roughness;
};

// The parts of a surface's colour (DirectArgs::direct etc.), emission aside.
template <class L>
struct Parts {
    V3<L> sun, envDiffuse, specWeight, envSpecular;
};

// The sun's visibility at s by the shadow map (shadowVisibility, the receiver's plane from
// its normal): 0 facing away. The tolerance that tells the receiver from an occluder is
// biasConst plus biasSlope per unit of tan(angle to the light), for what the plane cannot
// know: a shading normal that is not the facet's, which tilts the plane the more the more
// grazing the light (the terminator of a smooth sphere). exactTol is biasConst alone.
template <class L>
SSRT_INLINE L shadowMapVisibility(const DirectArgs& a, const Surface<L>& s) {
    const L zero(0.0f), one(1.0f);
    const L NoLraw = ln::dot(s.n, splat3<L>(a.toLight));
    if (!ln::any(NoLraw > zero)) return zero;  // every lane faces away: no taps to read
    const L cosL = ln::max(NoLraw, L(kShadowMinCos));
    const L tanL = ln::sqrt(ln::max(one - cosL * cosL, zero)) / cosL;
    const L tol = L(a.biasConst) + L(a.biasSlope) * tanL;
    return ln::select(NoLraw > zero, shadowVisibility(a, s.p, s.n, cosL, tol, L(a.biasConst), tanL),
                      zero);
}

// The Lambert part of the sun light leaving a surface point, emission aside:
//   albedo (1 - metallic) / pi  lightRadiance  saturate(n.l)  shadow,
// what SSGI reads at its hits (trace/ssgi.h). One copy for the direct pass, which writes it
// per pixel (DirectArgs::hitLight), and SSGI's G-buffer path, so both give the same bits.
template <class L>
SSRT_INLINE V3<L> lambertSunLight(const DirectArgs& a, V3<L> n, V3<L> albedo, L metallic,
                                  L shadow) {
    const L NoL = ln::saturate(ln::dot(n, splat3<L>(a.toLight)));
    const V3<L> diffuse = albedo * ((L(1.0f) - metallic) * L(ln::kInvPi));
    return diffuse * splat3<L>(a.lightRadiance) * (NoL * shadow);
}

// The direct pass's model at one surface point seen along s.view, with the sun's
// `visibility` given (the shadow map's above, or a traced one: the reference image).
//
// Specular with multiple scattering, Kulla and Conty 2017, "Revisiting Physically Based
// Shading at Imageworks". E(mu) is the GGX directional albedo with F = 1 and E_avg its
// cosine-weighted average (shading/energy_tables.h, over perceptual roughness). The lobe
//   f_ms(wi, wo) = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg))
// integrates over wi, cosine-weighted, to 1 - E(mu_o), since 2 pi int (1 - E(mu)) mu dmu =
// pi (1 - E_avg); a coloured Fresnel tints it by T = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)).
// So, per channel,
//   sun:        (F D V + T f_ms(l, v)) E_sun n.l visibility
//   specWeight: (F0 A(n.v) + F90 B(n.v)) + T (1 - E(n.v)),
// specWeight being the sky's BRDF factor of the split sum (Karis 2013, shading/
// prefiltered_env.h): its single-scattering part the stored DFG table (F0 A + F90 B is the
// albedo of Schlick's F; F90 = 1 as F_Schlick is called here), its multiple-scattering part
// f_ms T integrated. White furnace: F0 = 1 gives F_avg = T = 1 and A + B = E, so specWeight
// = E + (1 - E) = 1 (tests/renderer/white_furnace_test.cpp).
template <class L>
SSRT_INLINE Parts<L> shadeSurface(const DirectArgs& a, const Surface<L>& s, L visibility) {
    using namespace ssrt::brdf;
    namespace ms = ssrt::multiscatter;
    const EnergyTables& tables = *a.energy;
    const L one(1.0f);
    const V3<L> l = splat3<L>(a.toLight);
    const L NoL = ln::saturate(ln::dot(s.n, l));
    const L NoV = ln::max(ln::dot(s.n, s.view), L(1e-4f));
    const V3<L> h = ln::normalize(s.view + l);
    const L NoH = ln::saturate(ln::dot(s.n, h));
    const L VoH = ln::saturate(ln::dot(s.view, h));
    const L alpha = roughnessToAlpha(s.roughness);
    // F0 = mix(0.04, baseColor, metallic)
    const V3<L> f0 = mix3(V3<L>{L(0.04f), L(0.04f), L(0.04f)}, s.albedo, s.metallic);
    // Multiple scattering: the tint T and, for the sun, f_ms(l, v) (0 where n.l = 0).
    const V3<L> tint = multiScatterTint(f0, ms::albedoAvg(tables, s.roughness));
    const L fMs = ms::fMs(tables, NoL, NoV, s.roughness);
    const L dv = D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha);
    const V3<L> spec{F_Schlick(VoH, f0.x, one) * dv + tint.x * fMs,
                     F_Schlick(VoH, f0.y, one) * dv + tint.y * fMs,
                     F_Schlick(VoH, f0.z, one) * dv + tint.z * fMs};
    const V3<L> diffuse = s.albedo * ((one - s.metallic) * Fd_Lambert<L>());
    const V3<L> direct = (diffuse + spec) * splat3<L>(a.lightRadiance) * (NoL * visibility);
    const V3<L> refl = s.n * (L(2.0f) * ln::dot(s.n, s.view)) - s.view;
    V3<L> irradiance, specSky;
    if (a.envLevelCount > 0) {
        // Equirect sky: irradiance / pi from the SH polynomial, the reflected sky from the
        // GGX-prefiltered levels (split sum, Karis 2013).
        irradiance = env::irradianceSh(a.envIrradiance, s.n) * L(a.envIntensity);
        specSky = envPrefiltered(a, refl, s.roughness);
    } else {
        // Analytic sky: irradiance blended by the normal's elevation, and the reflected sky
        // through the environment BRDF, blurred towards the sky's average as roughness grows.
        const V3<L> skyAvg =
            mix3(splat3<L>(a.skyGround),
                 mix3(splat3<L>(a.skyHorizon), splat3<L>(a.skyZenith), L(0.5f)), L(0.5f));
        const V3<L> up = mix3(splat3<L>(a.skyHorizon), splat3<L>(a.skyZenith), L(0.5f));
        irradiance = mix3(splat3<L>(a.skyGround), up, L(0.5f) + L(0.5f) * s.n.y);
        specSky = mix3(skyRadiance(a, refl), skyAvg, s.roughness);
    }
    // The sky's BRDF factor: the DFG split sum plus the multiple scattering, T (1 - E(n.v)).
    const L dfgA = ms::lookup2d(tables.dfgA.data(), NoV, s.roughness);
    const L dfgB = ms::lookup2d(tables.dfgB.data(), NoV, s.roughness);
    const L lost = one - ms::albedo(tables, NoV, s.roughness);
    const V3<L> specWeight = (f0 * dfgA + V3<L>{dfgB, dfgB, dfgB}) + tint * lost;
    // color = (sun + envDiffuse) + specWeight envSpecular, as shadeChunk sums it.
    return {direct, irradiance * diffuse * L(ln::kPi), specWeight, specSky};
}

// glTF 2.0 section 3.9.4: the occlusion texture "indicates areas that receive less indirect
// lighting". So it scales the sky's diffuse term and the specular factor (which weighs the
// sky's specular and SSR alike), never the sun; emission is not in Parts.
template <class L>
SSRT_INLINE void occludeIndirect(Parts<L>& p, L occlusion) {
    p.envDiffuse = p.envDiffuse * occlusion;
    p.specWeight = p.specWeight * occlusion;
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
