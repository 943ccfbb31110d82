// The Hi-Z marcher: stackless traversal of the min-depth pyramid (Uludag 2014, "Hi-Z
// Screen-Space Cone-Traced Reflections", GPU Pro 5; the loop follows AMD FidelityFX SSSR,
// ffx_sssr.h, FFX_SSSR_HierarchicalRaymarch).
//
// The ray is a screen-space segment P(t) = P0 + t (P1 - P0), k(t) = k0 + t (k1 - k0) with
// k = 1/depth, t in [0, 1] (clipped to the near plane and maxDistance). At level L the ray
// sits in a cell of 2^L pixels; if it is in front of the cell's minimum depth it advances to
// the nearer of the cell's exit and the depth plane of that minimum (the z plane only when
// the ray goes deeper). Leaving the cell while in front climbs a level; otherwise it
// descends. Descending below the most detailed level is a candidate hit, validated against
// the full-resolution depth with the thickness. The traversal treats the depth buffer as
// infinitely thick (FidelityFX does the same); the max pyramid is not used here.
#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "trace/march_common.h"

namespace ssrt::SSRT_ISA_NS {

namespace {

// minZ of level L at cell (cx, cy), per lane (levels differ between lanes: a scalar gather).
SSRT_INLINE Lane loadMinZ(const MarchKernelArgs& a, Lane level, Lane cx, Lane cy) {
    alignas(64) float lv[kW], x[kW], y[kW], out[kW];
    ln::store(lv, level);
    ln::store(x, cx);
    ln::store(y, cy);
    for (int l = 0; l < kW; ++l) {
        const int L = int(lv[l]);
        const int ix = std::clamp(int(x[l]), 0, a.hizWidth[L] - 1);
        const int iy = std::clamp(int(y[l]), 0, a.hizHeight[L] - 1);
        out[l] = a.hizMin[L][std::size_t(iy) * a.hizStride[L] + std::size_t(ix)];
    }
    return ln::load<Lane>(out);
}

}  // namespace

void marchHiZKernel(MarchKernelArgs& a) {
    const Lane zero(0.0f), one(1.0f), two(2.0f), half(0.5f);
    const Lane big(1e30f);
    const Lane maxSteps(float(a.maxSteps)), thickness(a.thickness);
    const float mostDetailed = float(a.mostDetailedLevel), top = float(a.hizLevels - 1);
    const float detailedSize = float(1 << a.mostDetailedLevel);
    for (int base = 0; base < a.count; base += kW) {
        // Set-up: the screen-space segment and its reciprocal slopes.
        const RayLanes r = loadRays(a, base);
        const ScreenSegment s = projectSegment(a, r);
        const Lane dPx = s.x1 - s.x0, dPy = s.y1 - s.y0, dk = s.k1 - s.k0;
        const Lane invDx = ln::select(ln::abs(dPx) > Lane(1e-12f), one / dPx, big);
        const Lane invDy = ln::select(ln::abs(dPy) > Lane(1e-12f), one / dPy, big);
        const Mask deeper = dk < Lane(-1e-30f);
        const Lane invDk = ln::select(deeper, one / dk, zero);
        const Lane floorX = ln::select(dPx >= zero, one, zero);
        const Lane floorY = ln::select(dPy >= zero, one, zero);
        // Nudge past the cell boundary (FidelityFX: 0.005 of a most detailed cell).
        const Lane nudgeX = ln::select(dPx >= zero, Lane(0.005f * detailedSize),
                                       Lane(-0.005f * detailedSize));
        const Lane nudgeY = ln::select(dPy >= zero, Lane(0.005f * detailedSize),
                                       Lane(-0.005f * detailedSize));
        // t where the ray crosses the next cell boundary of size `size` from (px, py).
        auto cellExit = [&](Lane px, Lane py, Lane size, Lane invSize) {
            const Lane planeX = (ln::floor(px * invSize) + floorX) * size + nudgeX;
            const Lane planeY = (ln::floor(py * invSize) + floorY) * size + nudgeY;
            return ln::min((planeX - s.x0) * invDx, (planeY - s.y0) * invDy);
        };
        // Leave the origin's own cell at the most detailed level.
        Lane t = cellExit(s.x0, s.y0, Lane(detailedSize), Lane(1.0f / detailedSize));
        Lane level(float(a.startLevel));
        Lane size(float(1 << a.startLevel)), invSize(1.0f / float(1 << a.startLevel));
        const Mask real = (ln::laneIndex<Lane>() + Lane(float(base))) < Lane(float(a.count));
        LaneEnds e{ln::select(real, Lane(kMarching), endCode(MarchEnd::NoRay)), zero, zero, zero,
                   zero, zero};
        Lane px = s.x0 + dPx * t, py = s.y0 + dPy * t;
        for (;;) {
            Mask active = e.cause < zero;
            // Off screen or past the end of the segment: a miss.
            const Mask left = !onScreen(a, px, py);
            const Mask past = t > one;
            Lane c = ln::select(past,
                                ln::select(s.nearClipped, endCode(MarchEnd::LeftScreen),
                                           endCode(MarchEnd::StepCap)),
                                Lane(kMarching));
            c = ln::select(left, endCode(MarchEnd::LeftScreen), c);
            c = ln::select(e.steps >= maxSteps, endCode(MarchEnd::StepCap), c);
            e.cause = ln::select(active, c, e.cause);
            active = e.cause < zero;
            if (!ln::any(active)) break;
            countLanes(a, active);
            e.steps = ln::select(active, e.steps + one, e.steps);
            // One iteration: the cell's minimum depth and the three planes.
            const Lane cellX = ln::floor(px * invSize), cellY = ln::floor(py * invSize);
            const Lane surface = loadMinZ(a, level, cellX, cellY);
            const Lane tx = ((cellX + floorX) * size + nudgeX - s.x0) * invDx;
            const Lane ty = ((cellY + floorY) * size + nudgeY - s.y0) * invDy;
            const Lane kSurface = one / surface;  // background: 0
            const Lane tz = ln::select(deeper, (kSurface - s.k0) * invDk, big);
            const Lane tMin = ln::min(ln::min(tx, ty), tz);
            const Lane k = s.k0 + dk * t;
            const Mask above = k * surface >= one;  // ray depth <= surface
            const Mask skipped = above & (tMin != tz);
            t = ln::select(active & above, tMin, t);
            px = s.x0 + dPx * t;
            py = s.y0 + dPy * t;
            // Climb after leaving a cell in front of it, else descend.
            const Mask up = skipped & (level < Lane(top));
            const Mask down = !skipped;
            level = ln::select(active & up, level + one, ln::select(active & down, level - one, level));
            size = ln::select(active & up, size * two, ln::select(active & down, size * half, size));
            invSize = ln::select(active & up, invSize * half,
                                 ln::select(active & down, invSize * two, invSize));
            const Mask candidate = active & (level < Lane(mostDetailed));
            // Keep the level loadable for lanes that stop here.
            level = ln::max(level, Lane(mostDetailed));
            e.cause = ln::select(candidate, endCode(MarchEnd::Hit), e.cause);
        }
        // Hit validation at full resolution: not the origin's pixel, not background, within
        // the thickness behind the surface.
        const Mask hit = e.cause == endCode(MarchEnd::Hit);
        if (ln::any(hit)) {
            const Lane ix = pixelOf(px, a.width), iy = pixelOf(py, a.height);
            const Lane sceneZ = sceneDepth(a, ix, iy);
            const Lane k = ln::clamp(s.k0 + dk * t, ln::min(s.k0, s.k1), ln::max(s.k0, s.k1));
            const Lane rayZ = one / k;
            const Mask own = (ix == r.pixelX) & (iy == r.pixelY);
            const Mask valid = (!own) & (rayZ <= sceneZ + thickness);
            e.cause = ln::select(hit & !valid, endCode(MarchEnd::Thickness), e.cause);
            const Mask ok = hit & valid;
            e.hitX = ln::select(ok, px, zero);
            e.hitY = ln::select(ok, py, zero);
            e.hitZ = ln::select(ok, sceneZ, zero);
        }
        finishRays(a, base, e);
    }
}

}  // namespace ssrt::SSRT_ISA_NS
