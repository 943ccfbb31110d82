// What the three marcher kernels share: loading a lane group of packed rays, projection,
// depth lookups and the hit validation once a lane group is done. Included only by
// kernel sources (after core/isa_target.h), so everything here is per ISA.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/lane_vec.h"
#include "trace/march_kernel.h"
#include "trace/trace_types.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using ILane = ln::IntOf<Lane>;
using Mask = ln::MaskOf<Lane>;
static_assert(kMarchPad % kW == 0, "packed rays are padded to a multiple of every width");

// In-lane end codes: MarchEnd values, and kMarching while a lane is still going.
constexpr float kMarching = -1.0f;
SSRT_INLINE Lane endCode(MarchEnd e) { return Lane(float(int(e))); }

SSRT_INLINE int popcount(uint64_t bits) { return __builtin_popcountll(bits); }
// (Not std::clamp: an out-of-line copy of it would be a weak symbol shared across ISAs.)
SSRT_INLINE int clampIndex(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

// One lane group of packed rays, in view space.
struct RayLanes {
    ln::V3<Lane> o, d;
    Lane pixelX, pixelY;  // the ray's own pixel
};

SSRT_INLINE RayLanes loadRays(const MarchKernelArgs& a, int base) {
    RayLanes r;
    r.o = {ln::load<Lane>(a.ox + base), ln::load<Lane>(a.oy + base), ln::load<Lane>(a.oz + base)};
    r.d = {ln::load<Lane>(a.dx + base), ln::load<Lane>(a.dy + base), ln::load<Lane>(a.dz + base)};
    r.pixelX = ln::load<Lane>(a.pixelX + base);
    r.pixelY = ln::load<Lane>(a.pixelY + base);
    return r;
}

// Pixel coordinates (continuous, centres at +0.5) of view point (x, y) at depth 1/k.
SSRT_INLINE Lane projectX(const MarchKernelArgs& a, Lane x, Lane k) {
    return Lane(a.cx) + x * k * Lane(a.sx);
}
SSRT_INLINE Lane projectY(const MarchKernelArgs& a, Lane y, Lane k) {
    return Lane(a.cy) - y * k * Lane(a.sy);
}

// True where (px, py) lies inside the frame (false for NaN).
SSRT_INLINE Mask onScreen(const MarchKernelArgs& a, Lane px, Lane py) {
    return (px >= Lane(0.0f)) & (px < Lane(float(a.width))) & (py >= Lane(0.0f)) &
           (py < Lane(float(a.height)));
}

// Integer pixel of a continuous position, clamped into the frame (garbage lanes stay in
// bounds).
SSRT_INLINE Lane pixelOf(Lane p, int size) {
    return ln::clamp(ln::floor(p), Lane(0.0f), Lane(float(size - 1)));
}

// Index of integer pixels (ix, iy) in the frame's depth planes (viewZ, backZ).
SSRT_INLINE ILane depthIndex(const MarchKernelArgs& a, Lane ix, Lane iy) {
    return ln::toIntTrunc(iy) * ILane(int32_t(a.g.stride)) + ln::toIntTrunc(ix);
}

// G-buffer depth at a depthIndex; background as +infinity.
SSRT_INLINE Lane sceneDepthAt(const MarchKernelArgs& a, ILane idx) {
    const Lane z = ln::gather(a.g.viewZ, idx);
    return ln::select(z > Lane(0.0f), z, Lane(__builtin_inff()));
}

// G-buffer depth at integer pixels (ix, iy) in the frame; background as +infinity.
SSRT_INLINE Lane sceneDepth(const MarchKernelArgs& a, Lane ix, Lane iy) {
    return sceneDepthAt(a, depthIndex(a, ix, iy));
}

// How far behind the depth buffer's z a ray may pass and still hit it (MarchLengths). Only
// read where z is a surface (finite): the callers' masks rule the background out first.
SSRT_INLINE Lane thicknessAt(const MarchKernelArgs& a, Lane z) {
    return z * Lane(a.thicknessScale) + Lane(a.thicknessBias);
}

// Where a ray at depth rayZ, behind the surface at a depthIndex by the depth buffer, is still
// within it: `fallback` (the thickness test, as the caller words it) where the back-face
// layer knows no interval there, rayZ <= the back face + `slack` where it does. (Gathered
// only when some lane is behind: most steps have none.)
SSRT_INLINE Mask withinSurface(const MarchKernelArgs& a, ILane idx, Mask behind, Lane rayZ,
                               Lane slack, Mask fallback) {
    if (!a.backZ || !ln::any(behind)) return fallback;
    const Lane back = ln::gather(a.backZ, idx);
    const Mask known = back > Lane(0.0f);
    return (known & (rayZ <= back + slack)) | ((!known) & fallback);
}

// The ray clipped to the near plane and to maxDistance, its two ends projected: pixel
// positions and k = 1/depth, all three linear in screen space (perspective correct).
struct ScreenSegment {
    Lane x0, y0, k0, x1, y1, k1;
    Mask nearClipped;  // the segment ends on the near plane
};

SSRT_INLINE ScreenSegment projectSegment(const MarchKernelArgs& a, const RayLanes& r) {
    const Lane zero(0.0f), one(1.0f), nearZ(a.nearZ);
    ScreenSegment s;
    // Clip: depth(t) = depth0 + rate t stays >= near.
    const Lane depth0 = zero - r.o.z, rate = zero - r.d.z;
    Lane tEnd(a.maxDistance);
    const Lane safeRate = ln::select(rate < zero, rate, Lane(-1.0f));
    const Lane tNear = ln::max((nearZ - depth0) / safeRate, zero);
    s.nearClipped = (rate < zero) & (tNear < tEnd);
    tEnd = ln::select(s.nearClipped, tNear, tEnd);
    const Lane depth1 = ln::max(depth0 + rate * tEnd, nearZ);
    s.k0 = one / ln::max(depth0, nearZ);
    s.k1 = one / depth1;
    s.x0 = projectX(a, r.o.x, s.k0);
    s.y0 = projectY(a, r.o.y, s.k0);
    s.x1 = projectX(a, r.o.x + r.d.x * tEnd, s.k1);
    s.y1 = projectY(a, r.o.y + r.d.y * tEnd, s.k1);
    return s;
}

// A lane group's state once it is done.
struct LaneEnds {
    Lane cause;       // MarchEnd code (Hit = candidate, validated by finishRays)
    Lane hitX, hitY;  // pixel position of the candidate hit
    Lane hitZ;        // depth buffer there
    Lane steps;
    Lane thick;  // 1 where a thickness rejection happened on the way
};

// The ends of a lane group starting at ray `base`: lanes past the tile's last ray are NoRay
// from the start, the others are marching.
SSRT_INLINE LaneEnds startEnds(const MarchKernelArgs& a, int base) {
    const Lane zero(0.0f);
    const Mask real = (ln::laneIndex<Lane>() + Lane(float(base))) < Lane(float(a.count));
    return {
        ln::select(real, Lane(kMarching), endCode(MarchEnd::NoRay)), zero, zero, zero, zero, zero};
}

// Validation and write-out of lanes [base, base + kW) (the packed arrays are padded to whole
// lane groups; lanes past the tile's last ray write NoRay there, which nobody reads): a
// candidate hit whose surface normal faces along the ray (world space) becomes BackFace; a
// ray that was rejected for thickness on the way and then left the screen or ran out of
// steps ends as Thickness; misses write zero positions. (In lanes: the normals at the hits
// are scattered cache misses, which a gather overlaps and a scalar loop with a branch on
// each did not.)
inline void finishRays(MarchKernelArgs& a, int base, const LaneEnds& e) {
    const Lane zero(0.0f), one(1.0f);
    Lane c = e.cause;
    const Mask hit = c == endCode(MarchEnd::Hit);
    if (ln::any(hit)) {
        // Hit positions are on screen; misses (0, 0) read pixel 0, harmlessly.
        const ILane ix = ln::toIntTrunc(ln::clamp(e.hitX, zero, Lane(float(a.width - 1))));
        const ILane iy = ln::toIntTrunc(ln::clamp(e.hitY, zero, Lane(float(a.height - 1))));
        const ILane n = iy * ILane(int32_t(a.g.stride)) + ix;
        const Lane dx = ln::load<Lane>(a.dx + base), dy = ln::load<Lane>(a.dy + base),
                   dz = ln::load<Lane>(a.dz + base);
        const float* R = a.viewToWorld;
        const Lane wx = (Lane(R[0]) * dx + Lane(R[3]) * dy) + Lane(R[6]) * dz;
        const Lane wy = (Lane(R[1]) * dx + Lane(R[4]) * dy) + Lane(R[7]) * dz;
        const Lane wz = (Lane(R[2]) * dx + Lane(R[5]) * dy) + Lane(R[8]) * dz;
        const Lane facing =
            (ln::gather(a.g.normal[0], n) * wx + ln::gather(a.g.normal[1], n) * wy) +
            ln::gather(a.g.normal[2], n) * wz;
        c = ln::select(hit & (facing > zero), endCode(MarchEnd::BackFace), c);
    }
    const Mask gaveUp = (c == endCode(MarchEnd::LeftScreen)) | (c == endCode(MarchEnd::StepCap));
    c = ln::select(gaveUp & !(e.thick == zero), endCode(MarchEnd::Thickness), c);
    const Mask isHit = c == endCode(MarchEnd::Hit);
    ln::store(a.hit + base, ln::select(isHit, one, zero));
    ln::store(a.hitX + base, ln::select(isHit, e.hitX, zero));
    ln::store(a.hitY + base, ln::select(isHit, e.hitY, zero));
    ln::store(a.hitZ + base, ln::select(isHit, e.hitZ, zero));
    ln::store(a.steps + base, e.steps);
    ln::store(a.cause + base, c);
}

// Lane bookkeeping of one step: slots issued and lanes still marching.
SSRT_INLINE void countLanes(MarchKernelArgs& a, Mask active) {
    a.laneSlots += uint64_t(kW);
    a.laneActive += uint64_t(popcount(ln::maskBits(active)));
}

// Marches every packed ray with kInFlight lane groups in flight, their steps interleaved:
// each step waits on a gather, and the other groups' work hides part of that latency. Lanes
// never interact, so the grouping does not change a bit. G has init(args, base), step(args) ->
// bool (false once every lane has ended) and finish(args).
template <class G, int kInFlight = 2>
inline void marchGroups(MarchKernelArgs& a) {
    for (int base = 0; base < a.count; base += kInFlight * kW) {
        G g[kInFlight];
        bool more[kInFlight];
        int live = 0;
        for (int j = 0; j < kInFlight; ++j) {
            more[j] = base + j * kW < a.count;
            if (more[j]) g[j].init(a, base + j * kW), ++live;
        }
        const int started = live;
        while (live) {
            for (int j = 0; j < kInFlight; ++j)
                if (more[j] && !(more[j] = g[j].step(a))) --live;
        }
        for (int j = 0; j < started; ++j) g[j].finish(a);
    }
}

}  // namespace ssrt::SSRT_ISA_NS
