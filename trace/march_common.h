// What the three marcher kernels share: loading a lane group of packed rays, projection,
// depth lookups and the scalar hit validation once a lane group is done. Included only by
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
constexpr int kW = int(ln::kWidth<Lane>);
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

// G-buffer depth at integer pixels (ix, iy) in the frame; background as +infinity.
SSRT_INLINE Lane sceneDepth(const MarchKernelArgs& a, Lane ix, Lane iy) {
    const ILane idx = ln::toIntTrunc(iy) * ILane(int32_t(a.zStride)) + ln::toIntTrunc(ix);
    const Lane z = ln::gather(a.viewZ, idx);
    return ln::select(z > Lane(0.0f), z, Lane(__builtin_inff()));
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
    return {ln::select(real, Lane(kMarching), endCode(MarchEnd::NoRay)), zero, zero, zero, zero,
            zero};
}

// Scalar validation and write-out of lanes [base, min(base + kW, count)): a candidate hit
// whose surface normal faces along the ray (world space) becomes BackFace; a ray that was
// rejected for thickness on the way and then left the screen or ran out of steps ends as
// Thickness; misses write zero positions.
inline void finishRays(MarchKernelArgs& a, int base, const LaneEnds& e) {
    alignas(64) float cause[kW], hx[kW], hy[kW], hz[kW], steps[kW], thick[kW];
    ln::store(cause, e.cause);
    ln::store(hx, e.hitX);
    ln::store(hy, e.hitY);
    ln::store(hz, e.hitZ);
    ln::store(steps, e.steps);
    ln::store(thick, e.thick);
    const float* R = a.viewToWorld;
    for (int l = 0; l < kW && base + l < a.count; ++l) {
        const int i = base + l;
        MarchEnd c = MarchEnd(int(cause[l]));
        if (c == MarchEnd::Hit) {
            const int ix = clampIndex(int(hx[l]), 0, a.width - 1);
            const int iy = clampIndex(int(hy[l]), 0, a.height - 1);
            const std::size_t n = std::size_t(iy) * a.nStride + std::size_t(ix);
            const float dx = a.dx[i], dy = a.dy[i], dz = a.dz[i];
            const float wx = (R[0] * dx + R[3] * dy) + R[6] * dz;
            const float wy = (R[1] * dx + R[4] * dy) + R[7] * dz;
            const float wz = (R[2] * dx + R[5] * dy) + R[8] * dz;
            const float facing = (a.normal[0][n] * wx + a.normal[1][n] * wy) + a.normal[2][n] * wz;
            if (facing > 0.0f) c = MarchEnd::BackFace;
        } else if ((c == MarchEnd::LeftScreen || c == MarchEnd::StepCap) && thick[l] != 0.0f) {
            c = MarchEnd::Thickness;
        }
        const bool isHit = c == MarchEnd::Hit;
        a.hit[i] = isHit ? 1.0f : 0.0f;
        a.hitX[i] = isHit ? hx[l] : 0.0f;
        a.hitY[i] = isHit ? hy[l] : 0.0f;
        a.hitZ[i] = isHit ? hz[l] : 0.0f;
        a.steps[i] = steps[l];
        a.cause[i] = float(int(c));
    }
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
