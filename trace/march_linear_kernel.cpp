// The linear marcher: fixed view-space steps along the ray (a length per ray: a fraction of
// its origin's depth, or absolute; MarchLengths), each sample projected to its pixel and
// compared with the depth buffer. A sample behind the surface and before its back face (or by
// at most thickness(z) where the back face is unknown), with step |dir.z| (the ray's depth
// change over one step) of slack, is a hit; one behind by more is a thickness rejection and
// the march goes on behind the surface.
#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "trace/march_common.h"

namespace ssrt::SSRT_ISA_NS {

namespace {

// One lane group of rays in flight.
struct LinearGroup {
    RayLanes r;
    Lane depth0, depthRate, stepLength, stepDepth;
    LaneEnds e;
    int base;

    SSRT_INLINE void init(const MarchKernelArgs& a, int groupBase) {
        const Lane zero(0.0f);
        base = groupBase;
        // Set-up (per ray, outside the loop).
        r = loadRays(a, base);
        depth0 = zero - r.o.z;
        depthRate = zero - r.d.z;
        stepLength = depth0 * Lane(a.stepScale) + Lane(a.stepBias);
        stepDepth = stepLength * ln::abs(r.d.z);
        e = startEnds(a, base);
    }

    // One step for the lanes still marching; false when none is.
    SSRT_INLINE bool step(MarchKernelArgs& a) {
        const Lane zero(0.0f), one(1.0f), nearZ(a.nearZ);
        const Mask active = e.cause < zero;
        if (!ln::any(active)) return false;
        countLanes(a, active);
        e.steps = ln::select(active, e.steps + one, e.steps);
        const Lane t = e.steps * stepLength;
        // The sample and its pixel.
        const Lane depth = depth0 + depthRate * t;
        const Lane k = one / ln::max(depth, nearZ);
        const Lane px = projectX(a, r.o.x + r.d.x * t, k);
        const Lane py = projectY(a, r.o.y + r.d.y * t, k);
        const Lane ix = pixelOf(px, a.width), iy = pixelOf(py, a.height);
        const ILane idx = depthIndex(a, ix, iy);
        const Lane sceneZ = sceneDepthAt(a, idx);
        const Mask own = (ix == r.pixelX) & (iy == r.pixelY);
        const Mask behind = (depth > sceneZ) & !own;
        const Lane diff = depth - sceneZ;
        const Lane thresh = thicknessAt(a, sceneZ) + stepDepth;
        const Mask accept =
            behind & withinSurface(a, idx, behind & active, depth, stepDepth, diff <= thresh);
        // Ends, first match wins: distance cap, near plane, off screen, hit, step cap.
        const Mask past = t > Lane(a.maxDistance);
        const Mask left = (depth < nearZ) | !onScreen(a, px, py);
        Lane c = ln::select(e.steps >= Lane(float(a.maxSteps)), endCode(MarchEnd::StepCap),
                            Lane(kMarching));
        c = ln::select(accept, endCode(MarchEnd::Hit), c);
        c = ln::select(left, endCode(MarchEnd::LeftScreen), c);
        c = ln::select(past, endCode(MarchEnd::StepCap), c);
        const Mask sampleUsed = active & !past & !left;
        const Mask hitNow = sampleUsed & accept;
        e.hitX = ln::select(hitNow, px, e.hitX);
        e.hitY = ln::select(hitNow, py, e.hitY);
        e.hitZ = ln::select(hitNow, sceneZ, e.hitZ);
        e.thick = ln::select(sampleUsed & behind & !accept, one, e.thick);
        e.cause = ln::select(active, c, e.cause);
        return true;
    }

    SSRT_INLINE void finish(MarchKernelArgs& a) { finishRays(a, base, e); }
};

}  // namespace

void marchLinearKernel(MarchKernelArgs& a) { marchGroups<LinearGroup>(a); }

}  // namespace ssrt::SSRT_ISA_NS
