// The DDA marcher: McGuire and Mara 2014, "Efficient GPU Screen-Space Ray Tracing" (JCGT
// 3(4)). The ray is clipped to the near plane and to maxDistance; its end points are
// projected to pixels and k = 1/depth is interpolated linearly in screen space (perspective
// correct). Steps of ddaStride pixels along the major axis, the first offset by the jitter;
// at each the ray's depth interval over the step, [1/k at the previous half step, 1/k at the
// next], is tested against [z, z + thickness] of the depth buffer. A short binary search
// between the last two samples refines the hit.
//
// Deviation: positions are evaluated from the step index (P0 + dP u) rather than
// accumulated, so long rays do not drift; the step count does not include refinement.
#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "trace/march_common.h"

namespace ssrt::SSRT_ISA_NS {

namespace {

// The screen-space segment of one lane group, in permuted coordinates (major axis first).
struct Segment {
    Mask permute;      // major axis is y
    Lane M0, m0, k0;   // start: major, minor, 1/depth
    Lane dM, dm, dk;   // per step (one stride along the major axis)
    Lane M1, stepDir;  // end along the major axis, its direction (+-1)
    Lane kLo, kHi;     // range of k over the segment
    Mask nearClipped;  // the segment ends on the near plane
};

SSRT_INLINE Segment setUp(const MarchKernelArgs& a, const RayLanes& r) {
    const Lane zero(0.0f), one(1.0f);
    Segment s;
    const ScreenSegment seg = projectSegment(a, r);
    s.nearClipped = seg.nearClipped;
    const Lane x0 = seg.x0, y0 = seg.y0, k0 = seg.k0, y1 = seg.y1, k1 = seg.k1;
    Lane x1 = seg.x1;
    // A degenerate segment gets a hundredth of a pixel (as in the paper).
    const Lane dx0 = x1 - x0, dy0 = y1 - y0;
    x1 = ln::select(dx0 * dx0 + dy0 * dy0 < Lane(0.0001f), x1 + Lane(0.01f), x1);
    const Lane ddx = x1 - x0, ddy = y1 - y0;
    // Step along the major axis.
    s.permute = ln::abs(ddx) < ln::abs(ddy);
    const Lane major = ln::select(s.permute, ddy, ddx), minor = ln::select(s.permute, ddx, ddy);
    s.stepDir = ln::select(major >= zero, one, Lane(-1.0f));
    const Lane invMajor = s.stepDir / major;
    const Lane stride(a.ddaStride);
    s.M0 = ln::select(s.permute, y0, x0);
    s.m0 = ln::select(s.permute, x0, y0);
    s.M1 = ln::select(s.permute, y1, x1);
    s.k0 = k0;
    s.dM = s.stepDir * stride;
    s.dm = minor * invMajor * stride;
    s.dk = (k1 - k0) * invMajor * stride;
    s.kLo = ln::min(k0, k1);
    s.kHi = ln::max(k0, k1);
    return s;
}

// Pixel position and k at step parameter u.
SSRT_INLINE void at(const Segment& s, Lane u, Lane& px, Lane& py, Lane& k) {
    const Lane M = s.M0 + s.dM * u, m = s.m0 + s.dm * u;
    px = ln::select(s.permute, m, M);
    py = ln::select(s.permute, M, m);
    k = ln::clamp(s.k0 + s.dk * u, s.kLo, s.kHi);
}

// One lane group of rays in flight.
struct DdaGroup {
    RayLanes r;
    Segment s;
    Lane jitter, uHit, prevZ;
    LaneEnds e;
    int base;

    SSRT_INLINE void init(const MarchKernelArgs& a, int groupBase) {
        const Lane zero(0.0f), one(1.0f), half(0.5f);
        base = groupBase;
        r = loadRays(a, base);
        s = setUp(a, r);
        jitter = ln::load<Lane>(a.jitter + base);
        e = startEnds(a, base);
        uHit = zero;  // step parameter of the hit sample
        // Ray depth half a step before the first sample (interval [u - 1/2, u + 1/2]).
        Lane px, py, k;
        at(s, jitter + half, px, py, k);
        prevZ = one / k;
    }

    // One step for the lanes still marching; false when none is.
    SSRT_INLINE bool step(MarchKernelArgs& a) {
        const Lane zero(0.0f), one(1.0f), half(0.5f);
        const Mask active = e.cause < zero;
        if (!ln::any(active)) return false;
        countLanes(a, active);
        e.steps = ln::select(active, e.steps + one, e.steps);
        const Lane u = e.steps + jitter;  // the first sample at 1 + jitter strides
        Lane px, py, k;
        at(s, u, px, py, k);
        // The ray's depth interval over this step.
        const Lane zA = prevZ;
        const Lane zB = one / ln::clamp(k + s.dk * half, s.kLo, s.kHi);
        prevZ = ln::select(active, zB, prevZ);
        const Lane zMin = ln::min(zA, zB), zMax = ln::max(zA, zB);
        const Lane ix = pixelOf(px, a.width), iy = pixelOf(py, a.height);
        const ILane idx = depthIndex(a, ix, iy);
        const Lane sceneZ = sceneDepthAt(a, idx);
        const Mask own = (ix == r.pixelX) & (iy == r.pixelY);
        const Mask cross = (zMax > sceneZ) & !own;
        const Mask accept = cross & withinSurface(a, idx, cross & active, zMin, zero,
                                                  zMin <= sceneZ + thicknessAt(a, sceneZ));
        // Ends, first match wins: end of the segment, off screen, hit, step cap.
        const Mask past = (s.M0 + s.dM * u - s.M1) * s.stepDir > zero;
        const Mask left = !onScreen(a, px, py);
        Lane c = ln::select(e.steps >= Lane(float(a.maxSteps)), endCode(MarchEnd::StepCap),
                            Lane(kMarching));
        c = ln::select(accept, endCode(MarchEnd::Hit), c);
        c = ln::select(left, endCode(MarchEnd::LeftScreen), c);
        c = ln::select(
            past,
            ln::select(s.nearClipped, endCode(MarchEnd::LeftScreen), endCode(MarchEnd::StepCap)),
            c);
        const Mask sampleUsed = active & !past & !left;
        uHit = ln::select(sampleUsed & accept, u, uHit);
        e.thick = ln::select(sampleUsed & cross & !accept, one, e.thick);
        e.cause = ln::select(active, c, e.cause);
        return true;
    }

    SSRT_INLINE void finish(MarchKernelArgs& a) {
        const Lane zero(0.0f), one(1.0f), half(0.5f);
        // Binary refinement between the previous sample and the hit sample: keep the
        // nearest parameter found behind the depth buffer.
        const Mask hit = e.cause == endCode(MarchEnd::Hit);
        if (ln::any(hit)) {
            Lane hi = uHit, lo = ln::max(uHit - one, zero);
            for (int i = 0; i < a.refineSteps; ++i) {
                const Lane mid = (lo + hi) * half;
                Lane px, py, k;
                at(s, mid, px, py, k);
                const Lane ix = pixelOf(px, a.width), iy = pixelOf(py, a.height);
                const Lane sceneZ = sceneDepth(a, ix, iy);
                const Mask own = (ix == r.pixelX) & (iy == r.pixelY);
                const Mask behind = (one / k > sceneZ) & !own;
                hi = ln::select(behind, mid, hi);
                lo = ln::select(behind, lo, mid);
            }
            Lane px, py, k;
            at(s, hi, px, py, k);
            e.hitX = ln::select(hit, px, zero);
            e.hitY = ln::select(hit, py, zero);
            e.hitZ =
                ln::select(hit, sceneDepth(a, pixelOf(px, a.width), pixelOf(py, a.height)), zero);
        }
        finishRays(a, base, e);
    }
};

}  // namespace

void marchDdaKernel(MarchKernelArgs& a) { marchGroups<DdaGroup>(a); }

}  // namespace ssrt::SSRT_ISA_NS
