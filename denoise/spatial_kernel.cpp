#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "denoise/reblur_lanes.h"

// REBLUR's spatial passes (pre-blur, blur, post-blur), one copy per ISA (denoise/reblur_lanes.h has
// what the passes share).

namespace ssrt::SSRT_ISA_NS {

namespace {

using namespace reblur_lanes;

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
    Lane hitRoughness;  // the hit-distance scale's roughness factor (rb::hitDistanceRoughness)
    Lane frames;        // the accumulation speed (the pre-blur's: 10)
};

void storeSpatial(const ReblurPassArgs& a, std::size_t o, const Lane s[4]) {
    storeAt(a.out, o, s);
    storeAt(a.copy, o, s);
}

// A pixel whose luma lies within this share of its fast history's (the last few frames'
// mean) has a signal that did not change: no lag for the post-blur to hide.
constexpr float kSteadyLuma = 0.25f;

Mask steady(Lane fast, const Lane c[4]) {
    const Lane luma = rb::luma(c[0], c[1], c[2]);
    return ln::abs(luma - fast) <= Lane(kSteadyLuma) * ln::max(luma, fast) + Lane(rb::kEps);
}

// The terms of pixels (x .. x + kW, y); false (and the chunk copied) where none is filtered.
bool spatialPixel(const ReblurPassArgs& a, int x, int y, SpatialPixel& q) {
    const ReblurFrame& v = a.frame;
    q.o = std::size_t(y) * v.stride + x;
    const bool spec = a.specular;
    loadAt(a.in, q.o, q.c);
    // The pre-blur's speed is NRD's fixed 1/11 (it runs before the history); a frame without
    // history has none.
    const Lane frames = q.frames = a.frames ? loadAt(a.frames, q.o) : Lane(a.noFrames);
    // A pixel with a long history leaves the blur as it came (the post-blur filters it), and
    // the post-blur too where its signal is steady.
    Mask old = frames >= Lane(a.maxFrames);
    if (a.steadyFast && ln::any(old)) old = old & steady(loadAt(a.steadyFast, q.o), q.c);
    q.valid = validAt(v, q.o, spec) & !old;
    if (!ln::any(q.valid)) {
        storeSpatial(a, q.o, q.c);
        return false;
    }
    const Centre& p = q.p = centreAt(v, x, y, q.o, spec);
    const Lane one(1.0f);
    const bool pre = a.pass == ReblurSpatial::PreBlur;
    const Lane alpha = one / (one + frames);
    q.hitRoughness = rb::hitDistanceRoughness(v.hitScale, p.r);
    const Lane hitWorld = q.hitWorld =
        q.c[3] * rb::hitDistanceScaleWith(v.hitScale, p.z, q.hitRoughness);
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
    // No wider than the reflection's lobe seen from the camera (NRD's lobe radius, with GGX's
    // lobe and the mirror's curvature: specularLobePixels).
    if (spec) radius = ln::min(radius, specularLobePixels(v, p, hitWorld, curvature(v, p, x, y)));
    q.radius = ln::max(radius, Lane(a.frame.minBlurRadius) * smc);
    // Edge-stopping parameters.
    q.invPlane = one / (Lane(a.frame.planeDistance * v.frustum) * p.z);
    q.normalScale = normalWeightScale(p.r, pre ? Lane(1.0f / 11.0f) : alpha, a.frame.lobeFraction2,
                                      a.fractionScale);
    q.roughScale = one / rb::lerp(Lane(0.01f), one,
                                  ln::saturate(p.r * Lane(std::min(1.0f, a.frame.roughnessFraction *
                                                                             a.fractionScale))));
    q.hitScale = one / rb::lerp(Lane(0.0005f), one, ln::min(alpha, smc));
    q.minHit = Lane(a.frame.minHitWeight * a.fractionScale) * smc;
    // Reflections stay sharp near their contacts (pre-blur, specular).
    q.contactFree = rb::linstep(0.5f, 1.0f, p.r);
    return true;
}

// A pixel whose taps gathered less than this weight (a quarter of one ring tap's) found no
// neighbour on its own surface: a face seen edge-on, a few pixels wide, under the group's
// screen-space kernel (NRD lays its kernel on the surface's plane, GetKernelBasis, which
// squashes it onto such a face; the group's shared offsets cannot). It gets a second ring of
// kLonelyRadius pixels, which stays on the face. Only while the history is young (fewer than
// kLonelyFrames frames): by then the accumulation has averaged the noise away, and a ring
// applied every frame to the recurrent history would widen into a blur (cornell 640x360,
// frame 30: diffuse relMSE 0.0269 with it on every frame, 0.0266 without).
constexpr float kLonelyWeight = 4.0f * kRing;
constexpr float kLonelyRadius = 2.0f;
constexpr float kLonelyFrames = 4.0f;

// The 8 taps at offsets (ox[k], oy[k] in pixels) around the lanes `lanes` of pixels q, added to
// sum and weightSum. (One copy per signal and per pre-blur or not, a.specular and a.pass: each
// leaves out the others' branches.)
template <bool spec, bool pre>
void addTapsOf(const ReblurPassArgs& a, const SpatialPixel& q, Mask lanes, const float* ox,
               const float* oy, Lane sum[4], Lane& weightSum) {
    const ReblurFrame& v = a.frame;
    const Centre& p = q.p;
    const Lane zero(0.0f), one(1.0f);
    const ViewRays rays(v);
    for (int k = 0; k < 8; ++k) {
        const Tap t = tapAt(v, p.px + Lane(ox[k]), p.py + Lane(oy[k]));
        const Lane zs = ln::gather(v.signalZ[spec ? 1 : 0], t.index, t.run);  // 0: no signal
        const Mask ok = lanes & t.inside & (zs > zero);
        if (!ln::any(ok)) continue;
        const V3 xs = rays.at(t.x, t.y, zs);
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
        gatherAt(a.in, t.index, t.run, s);
        w = w * rb::lerp(q.minHit, one, rb::weightExp(q.hitScale * (s[3] - q.c[3])));
        if (spec && pre) {
            const V3 d = xs - p.x;
            const Lane dist = ln::sqrt(ln::dot(d, d));
            const Lane hs = s[3] * rb::hitDistanceScaleWith(v.hitScale, zs, q.hitRoughness);
            w = w * rb::lerp(ln::saturate(hs / (dist + q.hitWorld + Lane(rb::kEps))), one,
                             q.contactFree);
        }
        w = ln::select(ok, w, zero);
        for (int ch = 0; ch < 4; ++ch) sum[ch] = sum[ch] + w * s[ch];
        weightSum = weightSum + w;
    }
}

using AddTaps = void (*)(const ReblurPassArgs&, const SpatialPixel&, Mask, const float*,
                         const float*, Lane*, Lane&);

// The 8 taps at the group's offsets (ox[k], oy[k] in pixels, of radius r) around pixels q,
// and the lonely pixels' second ring.
void spatialFilter(const ReblurPassArgs& a, const SpatialPixel& q, const float* ox, const float* oy,
                   float r) {
    const bool pre = a.pass == ReblurSpatial::PreBlur;
    const AddTaps addTaps = a.specular ? (pre ? addTapsOf<true, true> : addTapsOf<true, false>)
                                       : (pre ? addTapsOf<false, true> : addTapsOf<false, false>);
    const Lane one(1.0f);
    Lane sum[4] = {q.c[0], q.c[1], q.c[2], q.c[3]};
    Lane weightSum = one;
    addTaps(a, q, q.valid, ox, oy, sum, weightSum);
    // (Only pixels whose own radius reaches the second ring: a mirror keeps its sharpness.)
    const Mask lonely = q.valid & (weightSum < Lane(1.0f + kLonelyWeight)) &
                        (q.radius >= Lane(kLonelyRadius)) & (q.frames < Lane(kLonelyFrames));
    if (r > kLonelyRadius && ln::any(lonely)) {
        float lx[8], ly[8];
        for (int k = 0; k < 8; ++k) {
            lx[k] = ox[k] * (kLonelyRadius / r);
            ly[k] = oy[k] * (kLonelyRadius / r);
        }
        addTaps(a, q, lonely, lx, ly, sum, weightSum);
    }
    Lane result[4];
    for (int ch = 0; ch < 4; ++ch) result[ch] = ln::select(q.valid, sum[ch] / weightSum, q.c[ch]);
    storeSpatial(a, q.o, result);
}

// Pixels (x .. x + kSpatialGroup, y): their terms, the group's radius (the mean over the
// pixels filtered, summed in pixel order) and rotation (a uniform angle in [0, pi/2) per
// group and frame: the set's 4-fold symmetry covers the rest), then the filter.
void spatialGroup(const ReblurPassArgs& a, int x, int y) {
    SpatialPixel q[kGroupChunks];
    bool any[kGroupChunks];
    alignas(64) float radius[kSpatialGroup];
    bool filtered[kSpatialGroup] = {};
    bool anyFiltered = false;
    for (int k = 0; k < kGroupChunks; ++k) {
        // (Chunks wholly past the frame's right edge are padding: left alone.)
        any[k] = x + k * kW < a.frame.width && spatialPixel(a, x + k * kW, y, q[k]);
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
    const uint32_t group = uint32_t(y) * uint32_t(a.frame.width) + uint32_t(x);
    float cs, sn;
    ln::sincos(randomFloat(group, a.frame.frameIndex, a.stream, 0) * ln::kHalfPi, sn, cs);
    float ox[8], oy[8];
    for (int k = 0; k < 8; ++k) {
        ox[k] = (kSpecial8[k].x * cs - kSpecial8[k].y * sn) * r;
        oy[k] = (kSpecial8[k].x * sn + kSpecial8[k].y * cs) * r;
    }
    for (int k = 0; k < kGroupChunks; ++k)
        if (any[k]) spatialFilter(a, q[k], ox, oy, r);
}

}  // namespace

void reblurSpatialTile(const ReblurPassArgs& a, int tile) {
    const ReblurFrame& v = a.frame;
    if (!(v.tiles[tile] & (a.specular ? kTileSpecular : kTileDiffuse)))
        return copyTile(v, a.in, a.out, a.copy, tile);
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kSpatialGroup) spatialGroup(a, x, y);
}

}  // namespace ssrt::SSRT_ISA_NS
