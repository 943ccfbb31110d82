#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_math.h"
#include "core/rng.h"
#include "core/screen_lanes.h"
#include "core/tiles.h"
#include "denoise/reblur_kernel.h"

// REBLUR's passes over lanes across x (NRD's REBLUR_*.hlsl restated; denoise/denoise.h lists
// them). GPU constructs and their CPU rules, for bit-identical results on every ISA:
//   - texture filtering (hardware bilinear, Catmull-Rom from 5 bilinear fetches) becomes
//     explicit taps with float weights summed in a fixed order;
//   - a per-pixel branch becomes masks and select; a tap no lane needs is skipped, which
//     changes nothing (its weight would be 0 and every signal is finite);
//   - rcp / rsqrt / transcendental intrinsics become / and sqrt (correctly rounded) and the
//     project's own exp2, log2, atan (core/lane_math.h);
//   - per-thread hashes become the counter RNG (core/rng.h), per pixel.

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
namespace rb = ssrt::reblur;
using V3 = ln::V3<Lane>;
using ILane = ln::IntOf<Lane>;
using Mask = ln::MaskOf<Lane>;

namespace {

constexpr int kW = int(ln::kWidth<Lane>);
constexpr float kNormalUlp = 0.5f / 255.0f;  // NRD's normal-encoding floor on angles
constexpr float kMaxSignal = 65504.0f;       // the front end's clamp (NRD's fp16 range)

SSRT_INLINE Lane loadAt(const float* plane, std::size_t offset) {
    return ln::load<Lane>(plane + offset);
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

SSRT_INLINE Centre centreAt(const ReblurView& v, int x, int y, std::size_t o, bool specular) {
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
SSRT_INLINE Mask validAt(const ReblurView& v, std::size_t o, bool specular) {
    return loadAt(v.signalZ[specular ? 1 : 0], o) > Lane(0.0f);
}

// A tap's pixel (floored continuous position), whether it lies on the frame, and its index.
struct Tap {
    Lane x, y;  // pixel centre
    Mask inside;
    ILane index;
    ln::Run run;  // its lanes' pixels are consecutive: loads, not gathers
};

SSRT_INLINE Tap tapAt(const ReblurView& v, Lane fx, Lane fy) {
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

SSRT_INLINE Lane sanitize(Lane v) {
    const Mask finite = (v - v) == Lane(0.0f);  // false for NaN and both infinities
    return ln::select(finite, ln::clamp(v, Lane(0.0f), Lane(kMaxSignal)), Lane(0.0f));
}

// Normalised hit distance: 1 without a hit (a miss is as far as it gets).
SSRT_INLINE Lane normalisedHit(const ReblurView& v, Lane h, Lane z, Lane r) {
    const Lane d = sanitize(h);
    const Lane scale = rb::hitDistanceScale(v.hitScale, z, r);
    return ln::select(d > Lane(0.0f), ln::saturate(d / scale), Lane(1.0f));
}

// Copies a tile's rows of in[] to out[] (and copy[]): the passes on tiles without the signal.
void copyTile(const ReblurView& v, const float* const in[4], float* const out[4],
              float* const copy[4], int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    for (int y = y0; y < y1; ++y) {
        const std::size_t o = std::size_t(y) * v.stride;
        for (int ch = 0; ch < 4; ++ch) {
            std::copy(in[ch] + o + x0, in[ch] + o + x1, out[ch] + o + x0);
            if (copy[ch]) std::copy(in[ch] + o + x0, in[ch] + o + x1, copy[ch] + o + x0);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Front end (NRD's REBLUR_FrontEnd_PackRadianceAndNormHitDist with sanitize, and
// REBLUR_ClassifyTiles).

void frontEndChunk(const ReblurFrontEndArgs& a, int x, int y, uint8_t& flags) {
    const ReblurView& v = a.view;
    const std::size_t o = std::size_t(y) * v.stride + x;
    const Lane zero(0.0f), one(1.0f);
    const Lane z = loadAt(v.viewZ, o);
    const Mask surface = z > zero;
    // Lanes past the frame's right edge are not pixels.
    const Mask inFrame = (Lane(float(x)) + ln::laneIndex<Lane>()) < Lane(float(v.width));
    if (a.diffuse[0]) {
        const Lane colour = ln::max(ln::max(loadAt(a.albedo[0], o), loadAt(a.albedo[1], o)),
                                    loadAt(a.albedo[2], o)) *
                            (one - loadAt(a.metallic, o));
        const Mask has = surface & inFrame & (colour > zero);
        for (int ch = 0; ch < 3; ++ch)
            ln::store(a.noisyDiffuse[ch] + o, sanitize(loadAt(a.diffuse[ch], o)));
        ln::store(a.noisyDiffuse[3] + o, normalisedHit(v, loadAt(a.diffuseHit, o), z, one));
        ln::store(a.signalZ[0] + o, ln::select(has, z, zero));
        if (ln::any(has)) flags |= kTileDiffuse;
    }
    if (a.ssr[0]) {
        const Lane r = loadAt(v.roughness, o);
        const Mask has = surface & inFrame & (r < Lane(a.specularMaxRoughness));
        const Lane opacity = ln::saturate(sanitize(loadAt(a.ssrOpacity, o)));
        for (int ch = 0; ch < 3; ++ch) {
            const Lane ssr = sanitize(loadAt(a.ssr[ch], o));
            const Lane env = sanitize(loadAt(a.envSpecular[ch], o));
            ln::store(a.noisySpecular[ch] + o, opacity * ssr + (one - opacity) * env);
        }
        ln::store(a.noisySpecular[3] + o, normalisedHit(v, loadAt(a.specularHit, o), z, r));
        ln::store(a.signalZ[1] + o, ln::select(has, z, zero));
        if (ln::any(has)) flags |= kTileSpecular;
    }
}

// ---------------------------------------------------------------------------------------
// Pre-blur, blur and post-blur (REBLUR_PrePass, REBLUR_Blur, REBLUR_PostBlur): 8 taps of
// NRD's "special 8" set, rotated per group of pixels and frame, in a radius that follows the
// hit distance and shrinks as the history grows.
//
// The kernel is shared by kSpatialGroup pixels of a row: one rotation (per group and frame)
// and one radius (the mean of the group's own pixels' radii), so a tap is the same offset for
// every pixel of the group, a run of consecutive pixels: one vector load per plane instead of
// a gather (NRD rotates per pixel: on a GPU a tap is a texture fetch either way). The edge-
// stopping weights stay per pixel. 16 pixels is every ISA's lane count times a whole number,
// so the groups, and the bits, are the same on every ISA. (Measured on cornell 640x360 against
// the one-bounce reference, issue 27: relMSE at frames 1 and 30 and the flicker moved by less
// than 0.5 %; the post-blur took 0.6x the time.)

struct KernelTap {
    float x, y, gauss;  // offset in radii; exp(-0.66 rho^2)
};
constexpr float kRing = 0.5169302f, kInner = 0.8478937f;  // exp(-0.66), exp(-0.66 / 4)
constexpr KernelTap kSpecial8[8] = {{1.0f, 0.0f, kRing},
                                    {-1.0f, 0.0f, kRing},
                                    {0.0f, 1.0f, kRing},
                                    {0.0f, -1.0f, kRing},
                                    {0.35355339f, 0.35355339f, kInner},
                                    {-0.35355339f, 0.35355339f, kInner},
                                    {0.35355339f, -0.35355339f, kInner},
                                    {-0.35355339f, -0.35355339f, kInner}};

constexpr int kSpatialGroup = 16;
constexpr int kGroupChunks = kSpatialGroup / kW;
static_assert(kSpatialGroup % kW == 0 && kTileSize % kSpatialGroup == 0);

// One chunk's per-pixel terms, before the group's radius is known.
struct SpatialPixel {
    std::size_t o;
    Lane c[4];   // the pixel's own signal
    Mask valid;  // filtered (else copied)
    Centre p;
    Lane radius;  // the pixel's own, in pixels
    Lane hitWorld, invPlane, normalScale, roughScale, hitScale, minHit, contactFree;
};

void storeSpatial(const ReblurSpatialArgs& a, std::size_t o, const Lane s[4]) {
    for (int ch = 0; ch < 4; ++ch) {
        ln::store(a.out[ch] + o, s[ch]);
        if (a.copy[ch]) ln::store(a.copy[ch] + o, s[ch]);
    }
}

// The terms of pixels (x .. x + kW, y); false (and the chunk copied) where none is filtered.
bool spatialPixel(const ReblurSpatialArgs& a, int x, int y, SpatialPixel& q) {
    const ReblurView& v = a.view;
    q.o = std::size_t(y) * v.stride + x;
    const bool spec = a.specular;
    for (int ch = 0; ch < 4; ++ch) q.c[ch] = loadAt(a.in[ch], q.o);
    // The pre-blur's speed is NRD's fixed 1/11 (it runs before the history).
    const Lane frames = a.frames ? loadAt(a.frames, q.o) : Lane(10.0f);
    // A pixel with a long history leaves the blur as it came (the post-blur filters it).
    q.valid = validAt(v, q.o, spec) & (frames < Lane(a.maxFrames));
    if (!ln::any(q.valid)) {
        storeSpatial(a, q.o, q.c);
        return false;
    }
    const Centre& p = q.p = centreAt(v, x, y, q.o, spec);
    const Lane one(1.0f);
    const bool pre = a.pass == ReblurSpatial::PreBlur;
    const Lane alpha = one / (one + frames);
    const Lane hitWorld = q.hitWorld = q.c[3] * rb::hitDistanceScale(v.hitScale, p.z, p.r);
    const Lane hitFactor = ln::saturate(hitWorld / (Lane(v.frustum) * p.z));
    const Lane smc = spec ? rb::specMagicCurve(p.r) : one;
    Lane radius;
    if (pre) {
        radius = Lane(a.radius) * ln::sqrt(spec ? p.r * hitFactor : hitFactor);
    } else {
        const Lane oneMinusNoV = one - p.noV;
        const Lane grazing = oneMinusNoV * oneMinusNoV * oneMinusNoV * oneMinusNoV * oneMinusNoV;
        const Lane boost = (one - rb::linstep(2.0f, 4.0f, frames)) * (one - grazing) * smc;
        const Lane alphaBlur = one / (one + (one - boost) * frames);
        const Lane f = spec ? p.r * hitFactor : hitFactor;
        radius = Lane(a.radius) * ln::sqrt(ln::saturate(f * alphaBlur));
    }
    if (spec) {
        // No wider than the lobe's footprint on the surface, seen from the camera (NRD's
        // lobe radius; the dominant direction's N.D taken as N.V).
        const Lane dominant = rb::dominantFactor(p.noV, p.r);
        const Lane footprint = hitWorld * p.noV * rb::lobeTanHalfAngle(p.r, Lane(0.3f));
        const Lane pixel = Lane(2.0f * v.tanHalfY / float(v.height)) * (p.z + hitWorld * dominant);
        radius = ln::min(radius, footprint / pixel);
    }
    q.radius = ln::max(radius, Lane(a.minRadius) * smc);
    // Edge-stopping parameters.
    q.invPlane = one / (Lane(a.planeDistance * v.frustum) * p.z);
    q.normalScale =
        normalWeightScale(p.r, pre ? Lane(1.0f / 11.0f) : alpha, a.lobeFraction2, a.fractionScale);
    q.roughScale =
        one /
        rb::lerp(Lane(0.01f), one,
                 ln::saturate(p.r * Lane(std::min(1.0f, a.roughnessFraction * a.fractionScale))));
    q.hitScale = one / rb::lerp(Lane(0.0005f), one, ln::min(alpha, smc));
    q.minHit = Lane(a.minHitWeight * a.fractionScale) * smc;
    // Reflections stay sharp near their contacts (pre-blur, specular).
    q.contactFree = rb::linstep(0.5f, 1.0f, p.r);
    return true;
}

// The 8 taps at the group's offsets (ox[k], oy[k] in pixels) around pixels q.
void spatialFilter(const ReblurSpatialArgs& a, const SpatialPixel& q, const float* ox,
                   const float* oy) {
    const ReblurView& v = a.view;
    const bool spec = a.specular, pre = a.pass == ReblurSpatial::PreBlur;
    const Centre& p = q.p;
    const Lane zero(0.0f), one(1.0f);
    Lane sum[4] = {q.c[0], q.c[1], q.c[2], q.c[3]};
    Lane weightSum = one;
    for (int k = 0; k < 8; ++k) {
        const Tap t = tapAt(v, p.px + Lane(ox[k]), p.py + Lane(oy[k]));
        const Lane zs = ln::gather(v.signalZ[spec ? 1 : 0], t.index, t.run);  // 0: no signal
        const Mask ok = q.valid & t.inside & (zs > zero);
        if (!ln::any(ok)) continue;
        const V3 xs = screen::viewPoint(t.x, t.y, zs, v.width, v.height, v.tanHalfX, v.tanHalfY);
        const V3 ns{ln::gather(v.normal[0], t.index, t.run),
                    ln::gather(v.normal[1], t.index, t.run),
                    ln::gather(v.normal[2], t.index, t.run)};
        Lane w = geometryWeight(p, xs, q.invPlane) *
                 rb::weightNonExp(q.normalScale * rb::acosApprox(ln::dot(p.n, ns))) *
                 Lane(kSpecial8[k].gauss);
        if (spec) {
            const Lane rs = ln::gather(v.roughness, t.index, t.run);
            w = w * rb::weightNonExp(q.roughScale * (rs - p.r));
        }
        Lane s[4];
        for (int ch = 0; ch < 4; ++ch) s[ch] = ln::gather(a.in[ch], t.index, t.run);
        w = w * rb::lerp(q.minHit, one, rb::weightExp(q.hitScale * (s[3] - q.c[3])));
        if (spec && pre) {
            const V3 d = xs - p.x;
            const Lane dist = ln::sqrt(ln::dot(d, d));
            const Lane hs = s[3] * rb::hitDistanceScale(v.hitScale, zs, p.r);
            w = w * rb::lerp(ln::saturate(hs / (dist + q.hitWorld + Lane(rb::kEps))), one,
                             q.contactFree);
        }
        w = ln::select(ok, w, zero);
        for (int ch = 0; ch < 4; ++ch) sum[ch] = sum[ch] + w * s[ch];
        weightSum = weightSum + w;
    }
    Lane result[4];
    for (int ch = 0; ch < 4; ++ch) result[ch] = ln::select(q.valid, sum[ch] / weightSum, q.c[ch]);
    storeSpatial(a, q.o, result);
}

// Pixels (x .. x + kSpatialGroup, y): their terms, the group's radius (the mean over the
// pixels filtered, summed in pixel order) and rotation (a uniform angle in [0, pi/2) per
// group and frame: the set's 4-fold symmetry covers the rest), then the filter.
void spatialGroup(const ReblurSpatialArgs& a, int x, int y) {
    SpatialPixel q[kGroupChunks];
    bool any[kGroupChunks];
    alignas(64) float radius[kSpatialGroup];
    bool filtered[kSpatialGroup] = {};
    bool anyFiltered = false;
    for (int k = 0; k < kGroupChunks; ++k) {
        // (Chunks wholly past the frame's right edge are padding: left alone.)
        any[k] = x + k * kW < a.view.width && spatialPixel(a, x + k * kW, y, q[k]);
        if (!any[k]) continue;
        anyFiltered = true;
        ln::store(radius + k * kW, q[k].radius);
        const uint64_t bits = ln::maskBits(q[k].valid);
        for (int i = 0; i < kW; ++i) filtered[k * kW + i] = (bits >> i) & 1u;
    }
    if (!anyFiltered) return;
    float sum = 0.0f;
    int count = 0;
    for (int i = 0; i < kSpatialGroup; ++i)
        if (filtered[i]) sum += radius[i], ++count;
    const float r = sum / float(count);
    const uint32_t group = uint32_t(y) * uint32_t(a.view.width) + uint32_t(x);
    float cs, sn;
    ln::sincos(randomFloat(group, a.frameIndex, a.stream, 0) * ln::kHalfPi, sn, cs);
    float ox[8], oy[8];
    for (int k = 0; k < 8; ++k) {
        ox[k] = (kSpecial8[k].x * cs - kSpecial8[k].y * sn) * r;
        oy[k] = (kSpecial8[k].x * sn + kSpecial8[k].y * cs) * r;
    }
    for (int k = 0; k < kGroupChunks; ++k)
        if (any[k]) spatialFilter(a, q[k], ox, oy);
}

// ---------------------------------------------------------------------------------------
// Temporal accumulation (REBLUR_TemporalAccumulation).

// Catmull-Rom weights of the 4 taps around a fraction t (Keys' a = -0.5); they sum to 1.
SSRT_INLINE void catmullRom(Lane t, Lane w[4]) {
    const Lane half(0.5f), one(1.0f);
    w[0] = t * (Lane(-0.5f) + t * (one - half * t));
    w[1] = one + t * t * (Lane(-2.5f) + Lane(1.5f) * t);
    w[2] = t * (half + t * (Lane(2.0f) - Lane(1.5f) * t));
    w[3] = t * t * (Lane(-0.5f) + half * t);
}

// A reprojected history read: the 2x2 bilinear footprint (and with surface motion the 4x4
// Catmull-Rom one) at a previous-frame position, each tap tested for occlusion.
struct History {
    Lane signal[4];
    Lane frames;  // accumulation speed behind the read (0: none)
    Lane fast;
    Lane quality;  // sqrt of the bilinear weight that survived (REBLUR's footprint quality)
    Mask found;
    V3 normal;  // the surviving taps' mean normal (not normalised); virtual reads only
};

// The previous frame's view-space point of its pixel (tx, ty) at depth zp, in this camera's
// world frame (camera at the origin).
SSRT_INLINE V3 prevPointInThisFrame(const ReblurTemporalArgs& a, Lane tx, Lane ty, Lane zp) {
    const ReblurView& v = a.view;
    const V3 pv = screen::viewPoint(tx, ty, zp, v.width, v.height, a.prevTanHalfX, a.prevTanHalfY);
    const V3 w = screen::viewToWorld(a.prevViewToWorld, pv);
    return {w.x - Lane(a.cameraDelta[0]), w.y - Lane(a.cameraDelta[1]),
            w.z - Lane(a.cameraDelta[2])};
}

// Reads the history at previous-frame pixel position (qx, qy). `surface`: the footprint is
// the surface's own (occlusion by the expected depth zExpected, Catmull-Rom where all 16
// taps pass); otherwise a virtual-motion read (occlusion by the plane of the centre, whose
// point in this camera's world frame is xw, bilinear only).
History readHistory(const ReblurTemporalArgs& a, const Centre& p, Mask valid, Lane qx, Lane qy,
                    bool surface, Lane zExpected, V3 xw, Lane threshold) {
    const ReblurView& v = a.view;
    const Lane zero(0.0f), one(1.0f);
    const Lane sx = qx - Lane(0.5f), sy = qy - Lane(0.5f);
    const Lane x0 = ln::floor(sx), y0 = ln::floor(sy);
    const Lane fx = sx - x0, fy = sy - y0;
    History h;
    // Per tap of the 4x4 footprint (row j, column i): passes the occlusion test.
    Mask ok[4][4];
    ILane index[4][4];
    ln::Run run[4][4];
    V3 innerNormal[2][2];  // the inner taps' normals, gathered once for the test and the mean
    Mask allOk = valid;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const bool inner = (i == 1 || i == 2) && (j == 1 || j == 2);
            ok[j][i] = Mask(false);
            index[j][i] = ILane(0);
            run[j][i] = ln::Run{false, 0};
            if (!surface && !inner) continue;
            const Tap t = tapAt(v, x0 + Lane(float(i - 1) + 0.5f), y0 + Lane(float(j - 1) + 0.5f));
            index[j][i] = t.index;
            run[j][i] = t.run;
            const Lane zp = ln::gather(a.prevViewZ, t.index, t.run);
            Mask pass = valid & t.inside & (zp > zero);
            if (surface) {
                pass = pass & (ln::abs(zp - zExpected) <= threshold);
            } else {
                const V3 q = prevPointInThisFrame(a, t.x, t.y, zp);
                pass = pass & (ln::abs(ln::dot(p.n, q - xw)) <= threshold);
            }
            if (inner) {
                const V3 np{ln::gather(a.prevNormal[0], t.index, t.run),
                            ln::gather(a.prevNormal[1], t.index, t.run),
                            ln::gather(a.prevNormal[2], t.index, t.run)};
                innerNormal[j - 1][i - 1] = np;
                // NRD rejects past ~89 degrees on averaged normals; per tap, stricter.
                pass = pass & (ln::dot(np, p.n) > Lane(surface ? 0.5f : 0.9f));
                if (a.specular) {
                    const Lane rp = ln::gather(a.prevRoughness, t.index, t.run);
                    pass = pass & (ln::abs(rp - p.r) < Lane(0.1f) + Lane(0.1f) * p.r);
                }
            }
            ok[j][i] = pass;
            allOk = allOk & pass;
        }
    // Bilinear over the inner 2x2 with the surviving weights.
    const Lane bw[2][2] = {{(one - fx) * (one - fy), fx * (one - fy)}, {(one - fx) * fy, fx * fy}};
    Lane wsum = zero, frames = zero, fast = zero;
    Lane bil[4] = {zero, zero, zero, zero};
    V3 normal{zero, zero, zero};
    Lane w[2][2];
    Lane inner[2][2][4];  // the inner taps' signals, gathered once for both filters
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            w[j][i] = ln::select(ok[j + 1][i + 1], bw[j][i], zero);
            wsum = wsum + w[j][i];
        }
    h.found = wsum > Lane(1.0e-4f);
    const Lane inv = one / ln::select(h.found, wsum, one);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const ILane idx = index[j + 1][i + 1];
            const ln::Run r = run[j + 1][i + 1];
            const Lane wn = w[j][i] * inv;
            frames = frames + wn * ln::gather(a.prevFrames, idx, r);
            fast = fast + wn * ln::gather(a.prevFast, idx, r);
            if (!surface)  // (only the virtual read's confidence asks for it)
                normal = normal + innerNormal[j][i] * wn;
            for (int ch = 0; ch < 4; ++ch) {
                inner[j][i][ch] = ln::gather(a.prevSignal[ch], idx, r);
                bil[ch] = bil[ch] + wn * inner[j][i][ch];
            }
        }
    h.quality = ln::sqrt(ln::select(h.found, wsum, zero));
    h.frames = ln::select(h.found, frames, zero);
    h.fast = fast;
    h.normal = normal;
    for (int ch = 0; ch < 4; ++ch) h.signal[ch] = bil[ch];
    if (surface && ln::any(allOk)) {
        // Catmull-Rom where every tap passed (sharper history: less blur over 30 frames).
        Lane wx[4], wy[4];
        catmullRom(fx, wx);
        catmullRom(fy, wy);
        Lane cr[4] = {zero, zero, zero, zero};
        for (int j = 0; j < 4; ++j) {
            Lane row[4] = {zero, zero, zero, zero};
            for (int i = 0; i < 4; ++i) {
                const bool isInner = (i == 1 || i == 2) && (j == 1 || j == 2);
                for (int ch = 0; ch < 4; ++ch) {
                    const Lane s = isInner ? inner[j - 1][i - 1][ch]
                                           : ln::gather(a.prevSignal[ch], index[j][i], run[j][i]);
                    row[ch] = row[ch] + wx[i] * s;
                }
            }
            for (int ch = 0; ch < 4; ++ch) cr[ch] = cr[ch] + wy[j] * row[ch];
        }
        // Its negative lobes may undershoot: radiance stays >= 0, hit distances in [0, 1].
        for (int ch = 0; ch < 3; ++ch) cr[ch] = ln::max(cr[ch], zero);
        cr[3] = ln::saturate(cr[3]);
        for (int ch = 0; ch < 4; ++ch) h.signal[ch] = ln::select(allOk, cr[ch], h.signal[ch]);
    }
    // The accumulation speed drops with the footprint's quality (REBLUR: a *= lerp(Q, 1, alpha)).
    h.frames = h.frames * rb::lerp(h.quality, one, one / (one + h.frames));
    return h;
}

// The surface's curvature at the centre from its right (or left) and lower (or upper)
// neighbour: dot(n' - n, x' - x) / |x' - x|^2, 1 / radius on a sphere, averaged over the two;
// 0 across a depth edge.
SSRT_INLINE Lane curvature(const ReblurView& v, const Centre& p, int y) {
    const Lane zero(0.0f);
    Lane sum = zero;
    for (int axis = 0; axis < 2; ++axis) {
        Lane tx = p.px, ty = p.py;
        if (axis == 0)
            tx = ln::select(tx + Lane(1.0f) < Lane(float(v.width)), tx + Lane(1.0f),
                            tx - Lane(1.0f));
        else ty = Lane(float(y + 1 < v.height ? y + 1 : y - 1) + 0.5f);
        const Tap t = tapAt(v, tx, ty);
        const Lane zs = ln::gather(v.viewZ, t.index, t.run);
        const V3 xs = screen::viewPoint(t.x, t.y, zs, v.width, v.height, v.tanHalfX, v.tanHalfY);
        const V3 ns =
            screen::worldToView(v.viewToWorld, V3{ln::gather(v.normal[0], t.index, t.run),
                                                  ln::gather(v.normal[1], t.index, t.run),
                                                  ln::gather(v.normal[2], t.index, t.run)});
        const V3 d = xs - p.x;
        const Lane d2 = ln::dot(d, d);
        const Mask same = (zs > zero) & (ln::abs(zs - p.z) < Lane(0.05f) * p.z) & (d2 > zero);
        const Lane k = ln::dot(ns - p.nv, d) / ln::select(same, d2, Lane(1.0f));
        sum = sum + ln::select(same, k, zero);
    }
    return sum * Lane(0.5f);
}

void temporalChunk(const ReblurTemporalArgs& a, int x, int y) {
    const ReblurView& v = a.view;
    const std::size_t o = std::size_t(y) * v.stride + x;
    const bool spec = a.specular;
    const Lane zero(0.0f), one(1.0f);
    Lane c[4];
    for (int ch = 0; ch < 4; ++ch) c[ch] = loadAt(a.in[ch], o);
    const Centre p = centreAt(v, x, y, o, spec);
    const Mask valid = validAt(v, o, spec);
    const auto store = [&](const Lane s[4], Lane frames, Lane fast) {
        for (int ch = 0; ch < 4; ++ch) ln::store(a.out[ch] + o, s[ch]);
        ln::store(a.outFrames + o, frames);
        ln::store(a.outFast + o, fast);
    };
    const Lane lumaNow = rb::luma(c[0], c[1], c[2]);
    if (!a.prevViewZ || !ln::any(valid)) return store(c, zero, lumaNow);

    // Surface motion: where the pixel was, and the depth the previous camera saw it at (the
    // world assumed still, as NRD with 2D motion vectors; a moving object's history then
    // fails the test and restarts, which never ghosts).
    const Lane qx = p.px + loadAt(a.motion[0], o), qy = p.py + loadAt(a.motion[1], o);
    const V3 xw = screen::viewToWorld(v.viewToWorld, p.x);
    const V3 xprev = screen::worldToView(
        a.prevViewToWorld, V3{xw.x + Lane(a.cameraDelta[0]), xw.y + Lane(a.cameraDelta[1]),
                              xw.z + Lane(a.cameraDelta[2])});
    const Lane zExpected = zero - xprev.z;
    // Disocclusion threshold: a fraction of the frustum at that depth, wider at grazing angles.
    const Lane threshold =
        Lane(v.frustum) * p.z *
        ln::saturate(Lane(a.disocclusion + 1.0f / float(v.height)) / ln::max(Lane(0.01f), p.noV));
    History h = readHistory(a, p, valid, qx, qy, true, zExpected, xw, threshold);

    // Specular history is only as good as the reflection it saw: the surface's history saw
    // it from a direction the parallax angle away, which a lobe narrower than that angle
    // cannot hide (REBLUR's surface-motion confidence: a mirror on a moving camera keeps
    // few frames).
    Lane lobe = one;
    if (spec) {
        lobe = ln::max(ln::atan(rb::lobeTanHalfAngle(p.r, Lane(0.75f))), Lane(kNormalUlp));
        const V3 from = ln::normalize(xw);
        const V3 fromBefore =
            ln::normalize(V3{xw.x + Lane(a.cameraDelta[0]), xw.y + Lane(a.cameraDelta[1]),
                             xw.z + Lane(a.cameraDelta[2])});
        const Lane parallax = rb::acosApprox(ln::dot(from, fromBefore));
        Lane conf = ln::saturate(one - parallax / lobe);
        conf = conf * conf;
        h.frames = ln::min(h.frames, Lane(a.maxFrames) * conf * conf);
    }

    if (spec && a.virtualMotion) {
        // Virtual motion: the reflection seen in a mirror sits the hit distance behind it,
        // along the view ray; reproject that point (NRD's virtual motion, flat-mirror form,
        // leaning to the surface as the lobe widens: the dominant factor).
        const Lane dominant = rb::dominantFactor(p.noV, p.r);
        const Lane hitWorld = c[3] * rb::hitDistanceScale(v.hitScale, p.z, p.r);
        // A convex mirror images the hit closer behind it: h / (1 + 2 kappa h) (the mirror
        // equation with focal length 1 / (2 kappa)); concave ones are taken as flat.
        const Lane kappa = ln::max(curvature(v, p, y), zero);
        const Lane virtualDistance = hitWorld / (one + Lane(2.0f) * kappa * hitWorld);
        const V3 dir = ln::normalize(xw);
        const V3 xv = xw + dir * (virtualDistance * dominant);
        const V3 pv = screen::worldToView(
            a.prevViewToWorld, V3{xv.x + Lane(a.cameraDelta[0]), xv.y + Lane(a.cameraDelta[1]),
                                  xv.z + Lane(a.cameraDelta[2])});
        const Lane depth = zero - pv.z;
        const Mask front = depth > Lane(1.0e-6f);
        const Lane safe = ln::select(front, depth, one);
        const Lane vx = ((pv.x / safe) / Lane(a.prevTanHalfX) + one) * Lane(0.5f * float(v.width));
        const Lane vy = (one - (pv.y / safe) / Lane(a.prevTanHalfY)) * Lane(0.5f * float(v.height));
        History hv = readHistory(a, p, valid & front, vx, vy, false, zero, xw, threshold);
        // The virtual point is exact for a flat mirror only: where the history's normal
        // turned, the reflection turned twice as far (REBLUR's normal confidence).
        const Lane turn = rb::acosApprox(ln::dot(p.n, ln::normalize(hv.normal)));
        Lane conf = ln::saturate(one - Lane(2.0f) * turn / lobe);
        conf = conf * conf;
        hv.frames = ln::min(hv.frames, Lane(a.maxFrames) * conf * conf);
        const Lane amount =
            ln::select(hv.found, rb::smoothstep(0.05f, 0.95f, dominant) * hv.quality, zero);
        for (int ch = 0; ch < 4; ++ch) h.signal[ch] = rb::lerp(h.signal[ch], hv.signal[ch], amount);
        h.frames = rb::lerp(h.frames, hv.frames, amount);
        h.fast = rb::lerp(h.fast, hv.fast, amount);
        h.found = h.found | hv.found;
    }

    const Lane frames = ln::select(h.found, ln::min(h.frames, Lane(a.maxFrames)), zero);
    const Lane alpha = one / (one + frames);
    // Firefly suppressor: a new sample may exceed the history's luma by a shrinking factor.
    const Lane lumaHistory = rb::luma(h.signal[0], h.signal[1], h.signal[2]);
    const Lane maxRelative = Lane(a.fireflyScale) + Lane(38.0f) / (frames + one);
    const Lane k = Lane(3.0f) * frames / (one + Lane(3.0f) * frames);
    const Lane lumaKept = rb::lerp(lumaNow, ln::min(lumaNow, lumaHistory * maxRelative), k);
    const Lane scale = (lumaKept + Lane(rb::kEps)) / (lumaNow + Lane(rb::kEps));
    const Lane smc = spec ? rb::specMagicCurve(p.r) : one;
    const Lane hitAlpha = ln::max(alpha, one / (one + Lane(15.0f) * smc));
    Lane out[4];
    for (int ch = 0; ch < 3; ++ch) out[ch] = rb::lerp(h.signal[ch], c[ch] * scale, alpha);
    out[3] = rb::lerp(h.signal[3], c[3], hitAlpha);
    const Lane fastFrames = ln::min(frames, Lane(a.maxFastFrames));
    const Lane fastPrev = ln::select(h.found, h.fast, lumaKept);
    const Lane fast = rb::lerp(fastPrev, lumaKept, one / (one + fastFrames));
    for (int ch = 0; ch < 4; ++ch) out[ch] = ln::select(valid, out[ch], c[ch]);
    store(out, ln::select(valid, frames, zero), ln::select(valid, fast, lumaNow));
}

// ---------------------------------------------------------------------------------------
// History fix (REBLUR_HistoryFix): young pixels get a wide reconstruction; the fast history
// clamps the slow one (anti-lag).

void historyFixChunk(const ReblurHistoryFixArgs& a, int x, int y) {
    const ReblurView& v = a.view;
    const std::size_t o = std::size_t(y) * v.stride + x;
    const bool spec = a.specular;
    const Lane zero(0.0f), one(1.0f);
    Lane c[4];
    for (int ch = 0; ch < 4; ++ch) c[ch] = loadAt(a.in[ch], o);
    const Centre p = centreAt(v, x, y, o, spec);
    const Mask valid = validAt(v, o, spec);
    const Lane frames = loadAt(a.frames, o);
    Lane result[4] = {c[0], c[1], c[2], c[3]};
    const Mask young = valid & (frames < Lane(a.fixFrames));
    if (ln::any(young)) {
        const Lane smc = spec ? rb::specMagicCurve(p.r) : one;
        const Lane stride = ln::max(one, ln::floor(Lane(a.stride) / (Lane(2.0f) + frames) *
                                                   rb::lerp(Lane(0.5f), one, smc)));
        const Lane alpha = one / (one + frames);
        const Lane invPlane = one / (Lane(a.planeDistance * v.frustum) * p.z);
        const Lane normalScale = normalWeightScale(p.r, alpha, a.lobeFraction2, 1.0f);
        Lane sum[4], weightSum = one + frames;
        for (int ch = 0; ch < 4; ++ch) sum[ch] = c[ch] * weightSum;
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i) {
                if ((i == 0 && j == 0) || (std::abs(i) == 2 && std::abs(j) == 2)) continue;
                const Tap t =
                    tapAt(v, p.px + Lane(float(i)) * stride, p.py + Lane(float(j)) * stride);
                const Lane zs =
                    ln::gather(v.signalZ[spec ? 1 : 0], t.index, t.run);  // 0: no signal
                const Mask ok = young & t.inside & (zs > zero);
                if (!ln::any(ok)) continue;
                const V3 xs =
                    screen::viewPoint(t.x, t.y, zs, v.width, v.height, v.tanHalfX, v.tanHalfY);
                const V3 ns{ln::gather(v.normal[0], t.index, t.run),
                            ln::gather(v.normal[1], t.index, t.run),
                            ln::gather(v.normal[2], t.index, t.run)};
                Lane w = geometryWeight(p, xs, invPlane) *
                         rb::weightExp(normalScale * rb::acosApprox(ln::dot(p.n, ns)));
                if (spec) {
                    const Lane rs = ln::gather(v.roughness, t.index, t.run);
                    w = w * rb::weightExp((rs - p.r) / (Lane(0.05f) + Lane(0.15f) * p.r));
                }
                w = w * (one + ln::gather(a.frames, t.index, t.run));
                w = ln::select(ok, w, zero);
                for (int ch = 0; ch < 4; ++ch)
                    sum[ch] = sum[ch] + w * ln::gather(a.in[ch], t.index, t.run);
                weightSum = weightSum + w;
            }
        for (int ch = 0; ch < 4; ++ch) result[ch] = ln::select(young, sum[ch] / weightSum, c[ch]);
    }
    if (a.fast && ln::any(valid)) {
        // The fast history's 5x5 moments bound the slow history's luma (REBLUR's "fast
        // history" clamp), more firmly the older the pixel.
        // (signalZ is 0 off surfaces, so it alone says which taps count. Where the whole
        // window lies in the frame for every lane, its rows are plain loads.)
        const bool interior = x >= 2 && x + kW + 2 <= v.width && y >= 2 && y + 2 < v.height;
        const float* mask = v.signalZ[spec ? 1 : 0];
        Lane m1 = zero, m2 = zero, count = zero;
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i) {
                Lane ms, f;
                Mask inside;
                if (interior) {
                    const std::size_t at =
                        std::size_t(std::ptrdiff_t(o) + j * std::ptrdiff_t(v.stride) + i);
                    ms = loadAt(mask, at);
                    f = loadAt(a.fast, at);
                    inside = valid;
                } else {
                    const Tap t = tapAt(v, p.px + Lane(float(i)), p.py + Lane(float(j)));
                    ms = ln::gather(mask, t.index, t.run);
                    f = ln::gather(a.fast, t.index, t.run);
                    inside = valid & t.inside;
                }
                const Mask ok = inside & (ms > zero);
                f = ln::select(ok, f, zero);
                m1 = m1 + f;
                m2 = m2 + f * f;
                count = count + ln::select(ok, one, zero);
            }
        const Lane n = ln::max(count, one);
        m1 = m1 / n;
        const Lane sigma = ln::sqrt(ln::max(m2 / n - m1 * m1, zero));
        const Lane y0 = rb::luma(result[0], result[1], result[2]);
        const Lane clamped = ln::clamp(y0, m1 - Lane(2.0f) * sigma, m1 + Lane(2.0f) * sigma);
        const Lane y1 = rb::lerp(clamped, y0, one / (one + Lane(2.0f) * frames));
        const Lane scale = (y1 + Lane(rb::kEps)) / (y0 + Lane(rb::kEps));
        for (int ch = 0; ch < 3; ++ch)
            result[ch] = ln::select(valid, result[ch] * scale, result[ch]);
    }
    for (int ch = 0; ch < 4; ++ch) ln::store(a.out[ch] + o, result[ch]);
}

}  // namespace

void reblurFrontEndTile(const ReblurFrontEndArgs& a, int tile) {
    const ReblurView& v = a.view;
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    uint8_t flags = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) frontEndChunk(a, x, y, flags);
    a.tiles[tile] = flags;
}

void reblurSpatialTile(const ReblurSpatialArgs& a, int tile) {
    const ReblurView& v = a.view;
    if (!(v.tiles[tile] & (a.specular ? kTileSpecular : kTileDiffuse)))
        return copyTile(v, a.in, a.out, a.copy, tile);
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kSpatialGroup) spatialGroup(a, x, y);
}

void reblurTemporalTile(const ReblurTemporalArgs& a, int tile) {
    const ReblurView& v = a.view;
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) temporalChunk(a, x, y);
}

void reblurHistoryFixTile(const ReblurHistoryFixArgs& a, int tile) {
    const ReblurView& v = a.view;
    if (!(v.tiles[tile] & (a.specular ? kTileSpecular : kTileDiffuse))) {
        float* const none[4] = {};
        return copyTile(v, a.in, a.out, none, tile);
    }
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) historyFixChunk(a, x, y);
}

}  // namespace ssrt::SSRT_ISA_NS
