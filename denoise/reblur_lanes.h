// What REBLUR's per-ISA kernels share (denoise/*_kernel.cpp, one pass each): included by
// each copy after core/isa_target.h, inside its ISA's namespace, so every helper is that
// ISA's own (tests/check_kernel_objects.sh).
//
// REBLUR's passes over lanes across x (NRD's REBLUR_*.hlsl restated; denoise/denoise.h lists
// them). GPU constructs and their CPU rules, for bit-identical results on every ISA:
//   - texture filtering (hardware bilinear, Catmull-Rom from 5 bilinear fetches) becomes
//     explicit taps with float weights summed in a fixed order;
//   - a per-pixel branch becomes masks and select; a tap no lane needs is skipped, which
//     changes nothing (its weight would be 0 and every signal is finite);
//   - rcp / rsqrt / transcendental intrinsics become / and sqrt (correctly rounded) and the
//     project's own exp2, log2, atan (core/lane_math.h);
//   - per-thread hashes become the counter RNG (core/rng.h), per pixel.
#pragma once

#include <algorithm>

#include "core/lane_math.h"
#include "core/pixel_formats_lanes.h"
#include "core/rng.h"
#include "core/screen_lanes.h"
#include "core/signal_lanes.h"
#include "core/tiles.h"
#include "denoise/reblur_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
namespace rb = ssrt::reblur;
using V3 = ln::V3<Lane>;
using ILane = ln::IntOf<Lane>;
using Mask = ln::MaskOf<Lane>;

namespace reblur_lanes {

constexpr float kNormalUlp = 0.5f / 255.0f;  // NRD's normal-encoding floor on angles
constexpr float kMaxSignal = 65504.0f;       // the front end's clamp (NRD's fp16 range)

// Signal planes (reblur_kernel.h: f16 or f32), through the shared conversions
// (core/signal_lanes.h: the same bits on every ISA; stores clamp to 65504, so a Catmull-Rom
// overshoot never becomes infinity).
SSRT_INLINE Lane loadAt(SignalIn plane, std::size_t offset) {
    return ln::loadSignal<Lane>(plane, offset);
}
SSRT_INLINE Lane gatherAt(SignalIn plane, ILane index, ln::Run run) {
    return ln::gatherSignal<Lane>(plane, index, run);
}
SSRT_INLINE Lane gatherAt(const float* plane, ILane index, ln::Run run) {
    return ln::gather(plane, index, run);
}
// Two taps of one row side by side, i1 = i0 + 1 in every lane, read by one pair gather
// (ln::gatherPair, ln::gatherF16Pair: half the gathered elements): not where i0 is a run (two
// loads are cheaper), nor where tapAt's clamp at the frame's edge broke the neighbourhood in a
// lane (there i1 may equal i0). Either way the same values.
SSRT_INLINE bool pairable(ILane i0, ln::Run r0, ILane i1) {
    if constexpr (kW == 1) return false;
    else return !r0.consecutive && ln::all(i1 == i0 + ILane(1));
}
SSRT_INLINE void gatherTwo(const float* plane, bool pair, ILane i0, ln::Run r0, ILane i1,
                           ln::Run r1, Lane& a, Lane& b) {
    if (pair) return ln::gatherPair(plane, i0, a, b);
    a = ln::gather(plane, i0, r0);
    b = ln::gather(plane, i1, r1);
}
SSRT_INLINE void gatherTwo(SignalIn plane, bool pair, ILane i0, ln::Run r0, ILane i1, ln::Run r1,
                           Lane& a, Lane& b) {
    if (pair) {
        if (plane.f16) return ln::gatherF16Pair<Lane>(plane.f16, i0, a, b);
        return ln::gatherPair(plane.f32, i0, a, b);
    }
    a = gatherAt(plane, i0, r0);
    b = gatherAt(plane, i1, r1);
}
SSRT_INLINE void storeAt(SignalOut plane, std::size_t offset, Lane x) {
    ln::storeSignal(plane, offset, x);
}
// Radiance and hit distance (SignalIn4, SignalOut4: an f16x4 pixel in one load, gather or store).
SSRT_INLINE void loadAt(const SignalIn4& signal, std::size_t offset, Lane out[4]) {
    ln::loadSignal4<Lane>(signal, offset, out);
}
SSRT_INLINE void gatherAt(const SignalIn4& signal, ILane index, ln::Run run, Lane out[4]) {
    ln::gatherSignal4<Lane>(signal, index, run, out);
}
SSRT_INLINE void storeAt(const SignalOut4& signal, std::size_t offset, const Lane x[4]) {
    ln::storeSignal4<Lane>(signal, offset, x);
}
// Two taps as gatherTwo: an f16x4 pixel's four channels are one element, so no pair gather
// reads fewer (two gathers); a plane a channel, pairs as gatherTwo.
SSRT_INLINE void gatherTwo(const SignalIn4& signal, bool pair, ILane i0, ln::Run r0, ILane i1,
                           ln::Run r1, Lane a[4], Lane b[4]) {
    if (signal.f16x4) {
        gatherAt(signal, i0, r0, a);
        return gatherAt(signal, i1, r1, b);
    }
    for (int ch = 0; ch < 4; ++ch) gatherTwo(signal[ch], pair, i0, r0, i1, r1, a[ch], b[ch]);
}

// The centre pixel of a chunk: position, guides, and the view-space frame.
struct Centre {
    Lane px, py;  // pixel centre
    Lane z;
    V3 n, nv;  // world and view-space normal
    V3 x;      // view-space point
    Lane noV;
    Lane r;  // roughness (1 for the diffuse signal)
};

SSRT_INLINE Centre centreAt(const ReblurFrame& v, int x, int y, std::size_t o, bool specular) {
    Centre c;
    c.px = Lane(float(x) + 0.5f) + ln::laneIndex<Lane>();
    c.py = Lane(float(y) + 0.5f);
    c.z = loadAt(v.viewZ, o);
    c.n = {loadAt(v.normal[0], o), loadAt(v.normal[1], o), loadAt(v.normal[2], o)};
    c.nv = screen::worldToView(v.viewToWorld, c.n);
    c.x = screen::viewPoint(c.px, c.py, c.z, v.width, v.height, v.tanHalfX, v.tanHalfY);
    const V3 toEye = ln::normalize(V3{Lane(0.0f) - c.x.x, Lane(0.0f) - c.x.y, Lane(0.0f) - c.x.z});
    c.noV = ln::abs(ln::dot(c.nv, toEye));
    c.r = specular ? loadAt(v.roughness, o) : Lane(1.0f);
    return c;
}

// Signal present at the centre: a surface pixel with this signal.
SSRT_INLINE Mask validAt(const ReblurFrame& v, std::size_t o, bool specular) {
    return loadAt(v.signalZ[specular ? 1 : 0], o) > Lane(0.0f);
}

// A tap's pixel (floored continuous position), whether it lies on the frame, and its index.
struct Tap {
    Lane x, y;  // pixel centre
    Mask inside;
    ILane index;
    ln::Run run;  // its lanes' pixels are consecutive: loads, not gathers
};

SSRT_INLINE Tap tapAt(const ReblurFrame& v, Lane fx, Lane fy) {
    Tap t;
    const Lane ix = ln::floor(fx), iy = ln::floor(fy);
    t.inside = (ix >= Lane(0.0f)) & (ix < Lane(float(v.width))) & (iy >= Lane(0.0f)) &
               (iy < Lane(float(v.height)));
    t.x = ix + Lane(0.5f);
    t.y = iy + Lane(0.5f);
    t.index = screen::pixelIndex(ix, iy, v.width, v.height, v.stride);
    t.run = ln::runOf(t.index);
    return t;
}

// screen::viewPoint of this frame (x, y in pixels, z view depth), its factors computed once
// for a loop over taps: the same operations, so the same bits. (A division in a tap loop is
// not hoisted by the compiler where it follows a branch: it may trap, -ftrapping-math.)
struct ViewRays {
    float sx, sy, tanX, tanY;
    explicit ViewRays(const ReblurFrame& v)
        : sx(2.0f / float(v.width)),
          sy(2.0f / float(v.height)),
          tanX(v.tanHalfX),
          tanY(v.tanHalfY) {}
    SSRT_INLINE V3 at(Lane x, Lane y, Lane z) const {
        const Lane ndcX = x * Lane(sx) - Lane(1.0f);
        const Lane ndcY = Lane(1.0f) - y * Lane(sy);
        return {ndcX * Lane(tanX) * z, ndcY * Lane(tanY) * z, Lane(0.0f) - z};
    }
};

// Plane-distance weight of a point at view-space position xs (NRD's geometry weight).
SSRT_INLINE Lane geometryWeight(const Centre& c, V3 xs, Lane invDistance) {
    return rb::weightNonExp(ln::dot(c.nv, xs - c.x) * invDistance);
}

// Lobe-angle normal weight's scale: 1 / (the accepted angle x fraction scale).
SSRT_INLINE Lane normalWeightScale(Lane r, Lane alpha, float lobeFraction2, float fractionScale) {
    const Lane percent = Lane(0.75f) * rb::lerp(Lane(lobeFraction2), Lane(1.0f), alpha);
    const Lane angle = ln::max(ln::atan(rb::lobeTanHalfAngle(r, percent)), Lane(kNormalUlp));
    return Lane(1.0f) / (angle * Lane(fractionScale));
}

// The surface's curvature at the centre (pixels x .. x + kW of row y) from its right (or left)
// and lower (or upper) neighbour: dot(n' - n, x' - x) / |x' - x|^2, 1 / radius on a sphere,
// averaged over the two; 0 across a depth edge. A neighbour every lane has (not across the
// frame's edge) is read at its offset, a load, without tapAt's floor, clamp and run test: the
// same pixel and the same pixel centre (px + 1 and y +- 1 + 0.5 are exact), so the same bits.
SSRT_INLINE Lane curvature(const ReblurFrame& v, const Centre& p, int x, int y) {
    const Lane zero(0.0f);
    Lane sum = zero;
    const std::size_t o = std::size_t(y) * v.stride + std::size_t(x);
    for (int axis = 0; axis < 2; ++axis) {
        Lane tx = p.px, ty = p.py;
        const int ny = y + 1 < v.height ? y + 1 : y - 1;
        if (axis == 0)
            tx = ln::select(tx + Lane(1.0f) < Lane(float(v.width)), tx + Lane(1.0f),
                            tx - Lane(1.0f));
        else ty = Lane(float(ny) + 0.5f);
        Lane zs, nx, nyv, nz;
        Lane sx = tx, sy = ty;
        // (Lanes past the frame's right edge, a last chunk's padding, are clamped by tapAt.)
        if (axis == 0 ? x + kW < v.width : ny >= 0 && x + kW <= v.width) {
            const std::size_t n = axis == 0 ? o + 1 : std::size_t(ny) * v.stride + std::size_t(x);
            zs = loadAt(v.viewZ, n);
            nx = loadAt(v.normal[0], n);
            nyv = loadAt(v.normal[1], n);
            nz = loadAt(v.normal[2], n);
        } else {
            const Tap t = tapAt(v, tx, ty);
            sx = t.x;
            sy = t.y;
            zs = ln::gather(v.viewZ, t.index, t.run);
            nx = ln::gather(v.normal[0], t.index, t.run);
            nyv = ln::gather(v.normal[1], t.index, t.run);
            nz = ln::gather(v.normal[2], t.index, t.run);
        }
        const V3 xs = screen::viewPoint(sx, sy, zs, v.width, v.height, v.tanHalfX, v.tanHalfY);
        const V3 ns = screen::worldToView(v.viewToWorld, V3{nx, nyv, nz});
        const V3 d = xs - p.x;
        const Lane d2 = ln::dot(d, d);
        const Mask same = (zs > zero) & (ln::abs(zs - p.z) < Lane(0.05f) * p.z) & (d2 > zero);
        const Lane k = ln::dot(ns - p.nv, d) / ln::select(same, d2, Lane(1.0f));
        sum = sum + ln::select(same, k, zero);
    }
    return sum * Lane(0.5f);
}

// How many of this frame's pixels the reflection's lobe spans on a specular pixel: what a
// spatial filter may reach over without blurring the reflection more than the BRDF does.
//   - The lobe: the reflected directions holding 30 % of it lie within twice the microfacet
//     normal's angle theta_m, and a share P of GGX's microfacets lies within
//     tan theta_m = alpha sqrt(P / (1 - P)) (Walter et al. 2007, "Microfacet Models for
//     Refraction through Rough Surfaces", eq. 35; alpha as the BRDF's, brdf::roughnessToAlpha:
//     r^2, at least 1e-3). At its hit, hitWorld away, it covers hitWorld N.V 2 tan theta_m.
//   - Seen in the mirror: a convex mirror of curvature kappa images that patch smaller by
//     1 + 2 kappa hitWorld, that far behind it (the mirror equation, focal length
//     1 / (2 kappa); concave ones taken as flat), so from the camera it spans
//     patch / (z (1 + 2 kappa hitWorld) + hitWorld dominant) radians, the distance to the
//     reflection leaning to the surface's as the lobe widens (the dominant factor).
// NRD bounds its radius by the lobe of perceptual roughness (lobeTanHalfAngle, r in place of
// alpha), 1 / r times wider than GGX's below r = 0.5 and taken flat: on cornell's mirror sphere
// (r 0.02, alpha 1e-3) 5 pixels at 1280x720 where the reflection is sharper than one (issue 44).
SSRT_INLINE Lane specularLobePixels(const ReblurFrame& v, const Centre& p, Lane hitWorld,
                                    Lane kappa) {
    const Lane one(1.0f);
    const Lane alpha = ln::max(p.r * p.r, Lane(1.0e-3f));
    const Lane spread = Lane(2.0f * 0.65465367f) * alpha;  // 2 tan theta_m, sqrt(0.3 / 0.7)
    const Lane patch = hitWorld * p.noV * spread;
    const Lane minify = one + Lane(2.0f) * ln::max(kappa, Lane(0.0f)) * hitWorld;
    const Lane distance = p.z * minify + hitWorld * rb::dominantFactor(p.noV, p.r);
    return patch / (Lane(2.0f * v.tanHalfY / float(v.height)) * distance);
}

SSRT_INLINE Lane sanitize(Lane v) {
    const Mask finite = (v - v) == Lane(0.0f);  // false for NaN and both infinities
    return ln::select(finite, ln::clamp(v, Lane(0.0f), Lane(kMaxSignal)), Lane(0.0f));
}

// Normalised hit distance: 1 without a hit (a miss is as far as it gets). The distance is in
// scene units, so only non-finite and negative values go: sanitize's fp16 clamp would cut a
// scene in kilometres (a model scaled by 1000) short of its hits.
SSRT_INLINE Lane normalisedHit(const ReblurFrame& v, Lane h, Lane z, Lane r) {
    const Mask finite = (h - h) == Lane(0.0f);
    const Lane d = ln::select(finite, ln::max(h, Lane(0.0f)), Lane(0.0f));
    const Lane scale = rb::hitDistanceScale(v.hitScale, z, r);
    return ln::select(d > Lane(0.0f), ln::saturate(d / scale), Lane(1.0f));
}

// Copies a tile's rows of `in` to `out` (and `copy`, where not none): the passes on tiles
// without the signal. A lane group at a time through loadAt and storeAt, so a copy between
// formats converts as the passes do (f16 to f16 keeps the bits). Stores may run past the
// tile's last pixel into the row padding only (tiles are whole lane groups wide).
inline void copyTile(const ReblurFrame& v, const SignalIn4& in, const SignalOut4& out,
                     const SignalOut4& copy, int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    const bool copying = bool(copy);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) {
            const std::size_t o = std::size_t(y) * v.stride + x;
            Lane s[4];
            loadAt(in, o, s);
            storeAt(out, o, s);
            if (copying) storeAt(copy, o, s);
        }
}

}  // namespace reblur_lanes

}  // namespace ssrt::SSRT_ISA_NS
