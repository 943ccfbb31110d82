#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "denoise/reblur_lanes.h"

// REBLUR's temporal accumulation, one copy per ISA (denoise/reblur_lanes.h has what the passes
// share).

namespace ssrt::SSRT_ISA_NS {

namespace {

using namespace reblur_lanes;

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
SSRT_INLINE V3 prevPointInThisFrame(const ReblurPassArgs& a, Lane tx, Lane ty, Lane zp) {
    const ReblurFrame& v = a.frame;
    const V3 pv = screen::viewPoint(tx, ty, zp, v.width, v.height, a.frame.prevTanHalfX,
                                    a.frame.prevTanHalfY);
    const V3 w = screen::viewToWorld(a.frame.prevViewToWorld, pv);
    return {w.x - Lane(a.frame.cameraDelta[0]), w.y - Lane(a.frame.cameraDelta[1]),
            w.z - Lane(a.frame.cameraDelta[2])};
}

// The 4x4 footprint of a history read at previous-frame position (qx, qy): each tap's pixel
// and whether it passes the occlusion test (only the inner 2x2 for a virtual read).
struct Footprint {
    Lane fx, fy;  // the position's fraction within the inner 2x2
    Mask ok[4][4];
    ILane index[4][4];
    ln::Run run[4][4];
    bool pair[4][3];       // taps (j, i) and (j, i + 1) read by one pair gather (pairable)
    V3 innerNormal[2][2];  // the inner taps' normals, gathered once for the test and the mean
    Mask allOk;
};

// Plane values at footprint taps (j, i) and (j, i + 1) (a signal's four: Lane[4] each).
template <class P, class Out>
SSRT_INLINE void gatherTwoAt(const P& plane, const Footprint& f, int j, int i, Out& a, Out& b) {
    gatherTwo(plane, f.pair[j][i], f.index[j][i], f.run[j][i], f.index[j][i + 1], f.run[j][i + 1],
              a, b);
}

// `surface`: the footprint is the surface's own (occlusion by the expected depth zExpected);
// otherwise a virtual-motion read (occlusion by the plane of the centre, whose point in this
// camera's world frame is xw). Neighbouring taps of a row are read in pairs (gatherTwo). `spec`:
// a.specular.
SSRT_INLINE Footprint testFootprint(const ReblurPassArgs& a, const Centre& p, Mask valid, Lane qx,
                                    Lane qy, bool surface, bool spec, Lane zExpected, V3 xw,
                                    Lane threshold) {
    const ReblurFrame& v = a.frame;
    const Lane zero(0.0f);
    const Lane sx = qx - Lane(0.5f), sy = qy - Lane(0.5f);
    const Lane x0 = ln::floor(sx), y0 = ln::floor(sy);
    Footprint f;
    f.fx = sx - x0;
    f.fy = sy - y0;
    f.allOk = valid;
    for (int j = 0; j < 4; ++j) {
        const bool innerRow = j == 1 || j == 2;
        for (int i = 0; i < 4; ++i) {
            f.ok[j][i] = Mask(false);
            f.index[j][i] = ILane(0);
            f.run[j][i] = ln::Run{false, 0};
        }
        for (int i = 0; i < 3; ++i) f.pair[j][i] = false;
        if (!surface && !innerRow) continue;
        // The row's taps: all 4 (surface), or the inner 2.
        const int i0 = surface ? 0 : 1, i1 = surface ? 4 : 3;
        Lane tx[4], ty[4];
        Mask inside[4];
        for (int i = i0; i < i1; ++i) {
            const Tap t = tapAt(v, x0 + Lane(float(i - 1) + 0.5f), y0 + Lane(float(j - 1) + 0.5f));
            f.index[j][i] = t.index;
            f.run[j][i] = t.run;
            tx[i] = t.x;
            ty[i] = t.y;
            inside[i] = t.inside;
        }
        for (int i = i0; i + 1 < i1; ++i)
            f.pair[j][i] = pairable(f.index[j][i], f.run[j][i], f.index[j][i + 1]);
        Lane zp[4];
        if (surface) {
            gatherTwoAt(a.frame.prev.viewZ, f, j, 0, zp[0], zp[1]);
            gatherTwoAt(a.frame.prev.viewZ, f, j, 2, zp[2], zp[3]);
        } else {
            gatherTwoAt(a.frame.prev.viewZ, f, j, 1, zp[1], zp[2]);
        }
        Lane nx[4], ny[4], nz[4], rp[4];
        if (innerRow) {
            gatherTwoAt(a.frame.prev.normal[0], f, j, 1, nx[1], nx[2]);
            gatherTwoAt(a.frame.prev.normal[1], f, j, 1, ny[1], ny[2]);
            gatherTwoAt(a.frame.prev.normal[2], f, j, 1, nz[1], nz[2]);
            if (spec) gatherTwoAt(a.frame.prev.roughness, f, j, 1, rp[1], rp[2]);
        }
        for (int i = i0; i < i1; ++i) {
            const bool inner = innerRow && (i == 1 || i == 2);
            Mask pass = valid & inside[i] & (zp[i] > zero);
            if (surface) {
                pass = pass & (ln::abs(zp[i] - zExpected) <= threshold);
            } else {
                const V3 q = prevPointInThisFrame(a, tx[i], ty[i], zp[i]);
                pass = pass & (ln::abs(ln::dot(p.n, q - xw)) <= threshold);
            }
            if (inner) {
                const V3 np{nx[i], ny[i], nz[i]};
                f.innerNormal[j - 1][i - 1] = np;
                // NRD rejects past ~89 degrees on averaged normals; per tap, stricter.
                pass = pass & (ln::dot(np, p.n) > Lane(surface ? 0.5f : 0.9f));
                if (spec) pass = pass & (ln::abs(rp[i] - p.r) < Lane(0.1f) + Lane(0.1f) * p.r);
            }
            f.ok[j][i] = pass;
            f.allOk = f.allOk & pass;
        }
    }
    return f;
}

// The signals of a row of the footprint (taps[i][ch]): an f16x4 history's a gather a tap; of a
// plane a channel, four neighbouring taps of an f16 plane in one row gather (ln::gatherF16Row4),
// else in two pairs (gatherTwo).
SSRT_INLINE void gatherRow(const ReblurPassArgs& a, const Footprint& f, int j, Lane taps[4][4]) {
    if (a.prevSignal.f16x4) {
        gatherTwoAt(a.prevSignal, f, j, 0, taps[0], taps[1]);
        return gatherTwoAt(a.prevSignal, f, j, 2, taps[2], taps[3]);
    }
    const bool row4 = f.pair[j][0] && f.pair[j][1] && f.pair[j][2];
    for (int ch = 0; ch < 4; ++ch) {
        if (row4 && a.prevSignal[ch].f16) {
            Lane t[4];
            ln::gatherF16Row4<Lane>(a.prevSignal[ch].f16, f.index[j][0], t);
            for (int i = 0; i < 4; ++i) taps[i][ch] = t[i];
        } else {
            gatherTwoAt(a.prevSignal[ch], f, j, 0, taps[0][ch], taps[1][ch]);
            gatherTwoAt(a.prevSignal[ch], f, j, 2, taps[2][ch], taps[3][ch]);
        }
    }
}

// The history bilinear over the inner 2x2 with the surviving weights (and, for a virtual
// read, the taps' mean normal). taps[j][i][ch]: the footprint's signals, the inner 2x2 read
// here unless `haveSignals` (the whole 4x4 read for the Catmull-Rom).
SSRT_INLINE History bilinearHistory(const ReblurPassArgs& a, const Footprint& f, bool surface,
                                    bool haveSignals, Lane taps[4][4][4]) {
    const Lane zero(0.0f), one(1.0f);
    const Lane fx = f.fx, fy = f.fy;
    const Lane bw[2][2] = {{(one - fx) * (one - fy), fx * (one - fy)}, {(one - fx) * fy, fx * fy}};
    Lane wsum = zero, frames = zero, fast = zero;
    Lane bil[4] = {zero, zero, zero, zero};
    V3 normal{zero, zero, zero};
    Lane w[2][2];
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            w[j][i] = ln::select(f.ok[j + 1][i + 1], bw[j][i], zero);
            wsum = wsum + w[j][i];
        }
    History h;
    h.found = wsum > Lane(1.0e-4f);
    const Lane inv = one / ln::select(h.found, wsum, one);
    // The inner taps' values, a row's two in one pair gather.
    Lane tapFrames[2][2], tapFast[2][2];
    for (int j = 0; j < 2; ++j) {
        gatherTwoAt(a.prevFrames, f, j + 1, 1, tapFrames[j][0], tapFrames[j][1]);
        gatherTwoAt(a.prevFast, f, j + 1, 1, tapFast[j][0], tapFast[j][1]);
        if (!haveSignals) gatherTwoAt(a.prevSignal, f, j + 1, 1, taps[j + 1][1], taps[j + 1][2]);
    }
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const Lane wn = w[j][i] * inv;
            frames = frames + wn * tapFrames[j][i];
            fast = fast + wn * tapFast[j][i];
            if (!surface)  // (only the virtual read's confidence asks for it)
                normal = normal + f.innerNormal[j][i] * wn;
            for (int ch = 0; ch < 4; ++ch) bil[ch] = bil[ch] + wn * taps[j + 1][i + 1][ch];
        }
    h.quality = ln::sqrt(ln::select(h.found, wsum, zero));
    h.frames = ln::select(h.found, frames, zero);
    h.fast = fast;
    h.normal = normal;
    for (int ch = 0; ch < 4; ++ch) h.signal[ch] = bil[ch];
    return h;
}

// Catmull-Rom over the whole 4x4 where every tap passed (sharper history: less blur over 30
// frames), in place of the bilinear signal.
SSRT_INLINE void catmullRomHistory(const Footprint& f, const Lane taps[4][4][4], History& h) {
    const Lane zero(0.0f);
    Lane wx[4], wy[4];
    catmullRom(f.fx, wx);
    catmullRom(f.fy, wy);
    Lane cr[4] = {zero, zero, zero, zero};
    for (int j = 0; j < 4; ++j) {
        Lane row[4] = {zero, zero, zero, zero};
        for (int i = 0; i < 4; ++i)
            for (int ch = 0; ch < 4; ++ch) row[ch] = row[ch] + wx[i] * taps[j][i][ch];
        for (int ch = 0; ch < 4; ++ch) cr[ch] = cr[ch] + wy[j] * row[ch];
    }
    // Its negative lobes may undershoot: radiance stays >= 0, hit distances in [0, 1].
    for (int ch = 0; ch < 3; ++ch) cr[ch] = ln::max(cr[ch], zero);
    cr[3] = ln::saturate(cr[3]);
    for (int ch = 0; ch < 4; ++ch) h.signal[ch] = ln::select(f.allOk, cr[ch], h.signal[ch]);
}

// A read whose signal, speed or fast history is not finite is no history: the caller owns the
// history and may hand in a corrupt one, and a NaN tap would spread through the accumulation
// (a rejected tap's weight 0 times NaN is NaN) and the blur to the whole surface until a cut.
// The pixel restarts as at a disocclusion; a finite read keeps every bit.
SSRT_INLINE History finiteHistory(History h) {
    const Lane zero(0.0f);
    Mask finite = ((h.frames - h.frames) == zero) & ((h.fast - h.fast) == zero);
    for (int ch = 0; ch < 4; ++ch) finite = finite & ((h.signal[ch] - h.signal[ch]) == zero);
    h.found = h.found & finite;
    h.frames = ln::select(finite, h.frames, zero);
    h.fast = ln::select(finite, h.fast, zero);
    for (int ch = 0; ch < 4; ++ch) h.signal[ch] = ln::select(finite, h.signal[ch], zero);
    return h;
}

// Reads the history at previous-frame pixel position (qx, qy): testFootprint's occlusion
// test, then bilinear, and Catmull-Rom where all 16 taps of a surface read pass. (One copy per
// kind of read and signal, a.specular: the others' branches and unused taps are left out of
// each.)
template <bool surface, bool spec>
History readHistory(const ReblurPassArgs& a, const Centre& p, Mask valid, Lane qx, Lane qy,
                    Lane zExpected, V3 xw, Lane threshold) {
    const Lane one(1.0f);
    const Footprint f = testFootprint(a, p, valid, qx, qy, surface, spec, zExpected, xw, threshold);
    // The footprint's signals, read once for both filters: the whole 4x4 where a lane takes
    // the Catmull-Rom, else the bilinear's inner 2x2.
    const bool whole = surface && ln::any(f.allOk);
    Lane taps[4][4][4];
    if (whole)
        for (int j = 0; j < 4; ++j) gatherRow(a, f, j, taps[j]);
    History h = bilinearHistory(a, f, surface, whole, taps);
    if (whole) catmullRomHistory(f, taps, h);
    // The accumulation speed drops with the footprint's quality (REBLUR: a *= lerp(Q, 1, alpha)).
    h.frames = h.frames * rb::lerp(h.quality, one, one / (one + h.frames));
    return finiteHistory(h);
}

// Specular history is only as good as the reflection it saw: the surface's history saw it
// from a direction the parallax angle away, which a lobe narrower than that angle cannot hide
// (REBLUR's surface-motion confidence: a mirror on a moving camera keeps few frames). Returns
// the lobe's angle.
SSRT_INLINE Lane parallaxConfidence(const ReblurPassArgs& a, const Centre& p, V3 xw, History& h) {
    const Lane one(1.0f);
    const Lane lobe = ln::max(ln::atan(rb::lobeTanHalfAngle(p.r, Lane(0.75f))), Lane(kNormalUlp));
    const V3 from = ln::normalize(xw);
    const V3 fromBefore =
        ln::normalize(V3{xw.x + Lane(a.frame.cameraDelta[0]), xw.y + Lane(a.frame.cameraDelta[1]),
                         xw.z + Lane(a.frame.cameraDelta[2])});
    const Lane parallax = rb::acosApprox(ln::dot(from, fromBefore));
    Lane conf = ln::saturate(one - parallax / lobe);
    conf = conf * conf;
    h.frames = ln::min(h.frames, Lane(a.frame.maxAccumulatedFrames) * conf * conf);
    return lobe;
}

// Virtual motion: the reflection seen in a mirror sits the hit distance behind it, along the
// view ray; reproject that point (NRD's virtual motion, flat-mirror form, leaning to the
// surface as the lobe widens: the dominant factor) and blend its history into `h`.
SSRT_INLINE void virtualMotion(const ReblurPassArgs& a, const Centre& p, Mask valid, int x, int y,
                               Lane hit, V3 xw, Lane threshold, Lane lobe, History& h) {
    const ReblurFrame& v = a.frame;
    const Lane zero(0.0f), one(1.0f);
    const Lane dominant = rb::dominantFactor(p.noV, p.r);
    const Lane hitWorld = hit * rb::hitDistanceScale(v.hitScale, p.z, p.r);
    // A convex mirror images the hit closer behind it: h / (1 + 2 kappa h) (the mirror
    // equation with focal length 1 / (2 kappa)); concave ones are taken as flat.
    const Lane kappa = ln::max(curvature(v, p, x, y), zero);
    const Lane virtualDistance = hitWorld / (one + Lane(2.0f) * kappa * hitWorld);
    const V3 dir = ln::normalize(xw);
    const V3 xv = xw + dir * (virtualDistance * dominant);
    const V3 pv =
        screen::worldToView(a.frame.prevViewToWorld, V3{xv.x + Lane(a.frame.cameraDelta[0]),
                                                        xv.y + Lane(a.frame.cameraDelta[1]),
                                                        xv.z + Lane(a.frame.cameraDelta[2])});
    const Lane depth = zero - pv.z;
    const Mask front = depth > Lane(1.0e-6f);
    const Lane safe = ln::select(front, depth, one);
    const Lane vx =
        ((pv.x / safe) / Lane(a.frame.prevTanHalfX) + one) * Lane(0.5f * float(v.width));
    const Lane vy =
        (one - (pv.y / safe) / Lane(a.frame.prevTanHalfY)) * Lane(0.5f * float(v.height));
    History hv = readHistory<false, true>(a, p, valid & front, vx, vy, zero, xw, threshold);
    // The virtual point is exact for a flat mirror only: where the history's normal turned,
    // the reflection turned twice as far (REBLUR's normal confidence).
    const Lane turn = rb::acosApprox(ln::dot(p.n, ln::normalize(hv.normal)));
    Lane conf = ln::saturate(one - Lane(2.0f) * turn / lobe);
    conf = conf * conf;
    hv.frames = ln::min(hv.frames, Lane(a.frame.maxAccumulatedFrames) * conf * conf);
    const Lane amount =
        ln::select(hv.found, rb::smoothstep(0.05f, 0.95f, dominant) * hv.quality, zero);
    for (int ch = 0; ch < 4; ++ch) h.signal[ch] = rb::lerp(h.signal[ch], hv.signal[ch], amount);
    h.frames = rb::lerp(h.frames, hv.frames, amount);
    h.fast = rb::lerp(h.fast, hv.fast, amount);
    h.found = h.found | hv.found;
}

// The new sample into the history read: the accumulation, the firefly suppressor and the
// fast history; stored.
SSRT_INLINE void accumulate(const ReblurPassArgs& a, const Centre& p, Mask valid, std::size_t o,
                            const Lane c[4], Lane lumaNow, const History& h) {
    const Lane zero(0.0f), one(1.0f);
    const Lane frames =
        ln::select(h.found, ln::min(h.frames, Lane(a.frame.maxAccumulatedFrames)), zero);
    const Lane alpha = one / (one + frames);
    // Firefly suppressor: a new sample may exceed the history's luma by a shrinking factor.
    const Lane lumaHistory = rb::luma(h.signal[0], h.signal[1], h.signal[2]);
    const Lane maxRelative = Lane(a.frame.fireflyScale) + Lane(38.0f) / (frames + one);
    const Lane k = Lane(3.0f) * frames / (one + Lane(3.0f) * frames);
    const Lane lumaKept = rb::lerp(lumaNow, ln::min(lumaNow, lumaHistory * maxRelative), k);
    const Lane scale = (lumaKept + Lane(rb::kEps)) / (lumaNow + Lane(rb::kEps));
    const Lane smc = a.specular ? rb::specMagicCurve(p.r) : one;
    const Lane hitAlpha = ln::max(alpha, one / (one + Lane(15.0f) * smc));
    Lane out[4];
    for (int ch = 0; ch < 3; ++ch) out[ch] = rb::lerp(h.signal[ch], c[ch] * scale, alpha);
    out[3] = rb::lerp(h.signal[3], c[3], hitAlpha);
    const Lane fastFrames = ln::min(frames, Lane(a.frame.maxFastAccumulatedFrames));
    const Lane fastPrev = ln::select(h.found, h.fast, lumaKept);
    const Lane fast = rb::lerp(fastPrev, lumaKept, one / (one + fastFrames));
    for (int ch = 0; ch < 4; ++ch) out[ch] = ln::select(valid, out[ch], c[ch]);
    storeAt(a.out, o, out);
    ln::store(a.outFrames + o, ln::select(valid, frames, zero));
    storeAt(a.outFast, o, ln::select(valid, fast, lumaNow));
}

// (One copy per signal, a.specular.)
template <bool spec>
void temporalChunk(const ReblurPassArgs& a, int x, int y) {
    const ReblurFrame& v = a.frame;
    const std::size_t o = std::size_t(y) * v.stride + x;
    const Lane zero(0.0f), one(1.0f);
    Lane c[4];
    loadAt(a.in, o, c);
    const Centre p = centreAt(v, x, y, o, spec);
    const Mask valid = validAt(v, o, spec);
    const Lane lumaNow = rb::luma(c[0], c[1], c[2]);
    if (!a.prevFrames || !ln::any(valid)) {
        storeAt(a.out, o, c);
        ln::store(a.outFrames + o, zero);
        storeAt(a.outFast, o, lumaNow);
        return;
    }
    // Surface motion: where the pixel was, and the depth the previous camera saw it at (the
    // world assumed still, as NRD with 2D motion vectors; a moving object's history then
    // fails the test and restarts, which never ghosts).
    const Lane qx = p.px + loadAt(a.frame.motion[0], o), qy = p.py + loadAt(a.frame.motion[1], o);
    const V3 xw = screen::viewToWorld(v.viewToWorld, p.x);
    const V3 xprev =
        screen::worldToView(a.frame.prevViewToWorld, V3{xw.x + Lane(a.frame.cameraDelta[0]),
                                                        xw.y + Lane(a.frame.cameraDelta[1]),
                                                        xw.z + Lane(a.frame.cameraDelta[2])});
    const Lane zExpected = zero - xprev.z;
    // Disocclusion threshold: a fraction of the frustum at that depth, wider at grazing angles.
    const Lane threshold = Lane(v.frustum) * p.z *
                           ln::saturate(Lane(a.frame.disocclusion + 1.0f / float(v.height)) /
                                        ln::max(Lane(0.01f), p.noV));
    History h = readHistory<true, spec>(a, p, valid, qx, qy, zExpected, xw, threshold);
    const Lane lobe = spec ? parallaxConfidence(a, p, xw, h) : one;
    if (spec && a.frame.virtualMotion)
        virtualMotion(a, p, valid, x, y, c[3], xw, threshold, lobe, h);
    accumulate(a, p, valid, o, c, lumaNow, h);
}

}  // namespace

void reblurTemporalTile(const ReblurPassArgs& a, int tile) {
    const ReblurFrame& v = a.frame;
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    const auto chunk = a.specular ? temporalChunk<true> : temporalChunk<false>;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) chunk(a, x, y);
}

}  // namespace ssrt::SSRT_ISA_NS
