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
#include "raster/hiz_layout.h"
#include "trace/march_common.h"

namespace ssrt::SSRT_ISA_NS {

namespace {

// Entry L (per lane, 0..15) of a 16-float level table: a register permute where the ISA has
// one (ln::pickFromOne with AVX-512's 16 lanes, pickFromTwo with AVX2's 8), else a gather.
// Same values either way.
SSRT_INLINE Lane levelTable(const float* table, ILane L) {
    static_assert(kMaxHiZLevels == 16);
    if constexpr (kW == 16) return ln::pickFromOne(table, L);
    else if constexpr (kW == 8) return ln::pickFromTwo(table, L);
    else return ln::gather(table, L);
}

// A cell's side in pixels at level L, 2^L, and its reciprocal, 2^-L: exact, from the
// exponent bits (L <= 15), on every ISA without a table.
SSRT_INLINE Lane levelCellSize(ILane L) { return ln::floatFromBits((L + ILane(127)) << 23); }
SSRT_INLINE Lane levelInvCellSize(ILane L) { return ln::floatFromBits((ILane(127) - L) << 23); }

// The first element of row of tiles ty of level L, relative to the level: ty x the pitch's
// 16-float tiles, a shift per lane where the ISA has one (the pitch is a power of two), else a
// multiply. The same integers either way.
SSRT_INLINE ILane tileRowStart(const MarchKernelArgs& a, ILane L, ILane ty) {
#if defined(SSRT_ISA_avx512)
    return ILane(_mm512_sllv_epi32(ty, ln::toIntTrunc(levelTable(a.hizRowShift, L))));
#elif defined(SSRT_ISA_avx2)
    return ILane(_mm256_sllv_epi32(ty, ln::toIntTrunc(levelTable(a.hizRowShift, L))));
#else
    return (ty * ln::toIntTrunc(levelTable(a.hizPitch, L))) << 4;
#endif
}

// 1/minZ of level L at cell (x, y) (background 0), per lane: levels differ between lanes.
// The cell is already clamped into its level (cellOf).
SSRT_INLINE Lane loadInvMinZ(const MarchKernelArgs& a, ILane L, ILane x, ILane y) {
    if (a.hizInvPacked) {
        // Packed pyramid in 4x4 tiles (raster/hiz.h, hiZPackedIndex): the level tables from
        // registers, one gather for the depth.
        static_assert(kHiZPackedTile == 4 && kHiZPackedTileSize == 16);
        const ILane index =
            (ln::toIntTrunc(levelTable(a.hizOffset, L)) + tileRowStart(a, L, y >> 2)) +
            (((x >> 2) << 4) + (((y & ILane(3)) << 2) + (x & ILane(3))));
        return ln::gather(a.hizInvPacked, index);
    }
    alignas(64) int32_t lv[kW], ix[kW], iy[kW];
    alignas(64) float out[kW];
    ln::store(lv, L);
    ln::store(ix, x);
    ln::store(iy, y);
    for (int l = 0; l < kW; ++l)
        out[l] =
            1.0f / a.hizMin[lv[l]][std::size_t(iy[l]) * a.hizStride[lv[l]] + std::size_t(ix[l])];
    return ln::load<Lane>(out);
}

// The cell of level L (cells of 1 / invSize pixels) under pixel position p, clamped into a
// level of `cells` cells. For a lane still marching p is on screen (>= 0), where the floor
// is the truncation; the clamp keeps every other lane (NaN included) inside the level.
SSRT_INLINE ILane cellOf(Lane p, Lane invSize, Lane cells) {
    return ln::toIntTrunc(ln::clamp(p * invSize, Lane(0.0f), cells - Lane(1.0f)));
}

// One lane group of rays in flight: set-up, one traversal iteration, validation.
struct Group {
    RayLanes r;
    ScreenSegment s;
    Lane dPx, dPy, dk, invDx, invDy, invDk, floorX, floorY, nudgeX, nudgeY;
    Mask deeper;
    Lane t, px, py, level;  // the cell size follows from the level (levelCellSize)
    LaneEnds e;
    int base;

    SSRT_INLINE void init(const MarchKernelArgs& a, int groupBase) {
        const Lane zero(0.0f), one(1.0f), big(1e30f);
        const float detailedSize = float(1 << a.mostDetailedLevel);
        base = groupBase;
        // Set-up: the screen-space segment and its reciprocal slopes.
        r = loadRays(a, base);
        s = projectSegment(a, r);
        dPx = s.x1 - s.x0, dPy = s.y1 - s.y0, dk = s.k1 - s.k0;
        // A tiny slope counts as +0 (a huge positive reciprocal, boundaries to the right), so
        // the sign of the reciprocal and the side of the boundary always agree.
        const Mask flatX = ln::abs(dPx) <= Lane(1e-12f), flatY = ln::abs(dPy) <= Lane(1e-12f);
        invDx = ln::select(flatX, big, one / ln::select(flatX, one, dPx));
        invDy = ln::select(flatY, big, one / ln::select(flatY, one, dPy));
        deeper = dk < Lane(-1e-30f);
        invDk = ln::select(deeper, one / ln::select(deeper, dk, one), zero);
        const Mask posX = (dPx >= zero) | flatX, posY = (dPy >= zero) | flatY;
        floorX = ln::select(posX, one, zero);
        floorY = ln::select(posY, one, zero);
        // Nudge past the cell boundary (FidelityFX: 0.005 of a most detailed cell).
        nudgeX = ln::select(posX, Lane(0.005f * detailedSize), Lane(-0.005f * detailedSize));
        nudgeY = ln::select(posY, Lane(0.005f * detailedSize), Lane(-0.005f * detailedSize));
        // Leave the origin's own cell at the most detailed level.
        const Lane invD(1.0f / detailedSize), sizeD(detailedSize);
        const Lane planeX = (ln::floor(s.x0 * invD) + floorX) * sizeD + nudgeX;
        const Lane planeY = (ln::floor(s.y0 * invD) + floorY) * sizeD + nudgeY;
        t = ln::min((planeX - s.x0) * invDx, (planeY - s.y0) * invDy);
        level = Lane(float(a.startLevel));
        e = startEnds(a, base);
        px = s.x0 + dPx * t;
        py = s.y0 + dPy * t;
    }

    // One iteration for the lanes still marching; false when none is.
    SSRT_INLINE bool step(MarchKernelArgs& a) {
        const Lane zero(0.0f), one(1.0f), big(1e30f);
        Mask active = e.cause < zero;
        if (!ln::any(active)) return false;
        // Off screen, past the end of the segment or out of iterations: a miss. (Most steps
        // end no lane: the end codes are worked out only when one does.)
        const Mask left = !onScreen(a, px, py);
        const Mask past = t > one;
        const Mask capped = e.steps >= Lane(float(a.maxSteps));
        if (ln::any(active & (left | past | capped))) {
            Lane c = ln::select(past,
                                ln::select(s.nearClipped, endCode(MarchEnd::LeftScreen),
                                           endCode(MarchEnd::StepCap)),
                                Lane(kMarching));
            c = ln::select(left, endCode(MarchEnd::LeftScreen), c);
            c = ln::select(capped, endCode(MarchEnd::StepCap), c);
            e.cause = ln::select(active, c, e.cause);
            active = e.cause < zero;
            if (!ln::any(active)) return false;
        }
        countLanes(a, active);
        e.steps = ln::select(active, e.steps + one, e.steps);
        // The cell's minimum depth and the three planes.
        const ILane L = ln::toIntTrunc(level);
        const Lane size = levelCellSize(L), invSize = levelInvCellSize(L);
        const ILane ix = cellOf(px, invSize, levelTable(a.hizWidthF, L));
        const ILane iy = cellOf(py, invSize, levelTable(a.hizHeightF, L));
        const Lane kSurface = loadInvMinZ(a, L, ix, iy);  // background: 0
        const Lane cellX = ln::toFloat(ix), cellY = ln::toFloat(iy);
        const Lane tx = ((cellX + floorX) * size + nudgeX - s.x0) * invDx;
        const Lane ty = ((cellY + floorY) * size + nudgeY - s.y0) * invDy;
        const Lane tz = ln::select(deeper, (kSurface - s.k0) * invDk, big);
        const Lane tMin = ln::min(ln::min(tx, ty), tz);
        const Lane k = s.k0 + dk * t;
        const Mask above = k >= kSurface;  // ray depth <= surface
        const Mask skipped = above & (tMin != tz);
        t = ln::select(active & above, tMin, t);
        px = s.x0 + dPx * t;
        py = s.y0 + dPy * t;
        // Climb after leaving a cell in front of it, else descend.
        const Mask up = active & skipped & (level < Lane(float(a.hizLevels - 1)));
        const Mask down = active & !skipped;
        level = ln::select(up, level + one, ln::select(down, level - one, level));
        // Below the most detailed level: a candidate hit (keep the level loadable).
        const Lane mostDetailed(float(a.mostDetailedLevel));
        Mask candidate = active & (level < mostDetailed);
        if (a.mostDetailedLevel > 0 && ln::any(candidate)) {
            // A coarse cell's minimum may lie in front of the pixel the ray is over: where
            // the ray is still in front of that pixel's depth, step out of the cell at the
            // most detailed level and go on instead.
            const Lane sceneZ = sceneDepth(a, pixelOf(px, a.width), pixelOf(py, a.height));
            const Mask inFront = candidate & ((s.k0 + dk * t) * sceneZ > one);
            stepOutOfCell(a, inFront);
            candidate = candidate & !inFront;
        }
        if (ln::any(candidate)) candidate = candidate & !passBehind(a, candidate);
        e.cause = ln::select(candidate, endCode(MarchEnd::Hit), e.cause);
        level = ln::max(level, mostDetailed);
        return true;
    }

    // Of the candidate lanes, those whose ray passes behind the surface there, past its back
    // face (raster/back_depth.h): they step out of the pixel at the most detailed level and go
    // on, as the linear and DDA marchers go on behind a surface, so that a ray behind a pole
    // still finds the wall (without the layer it ended as Thickness there). Where the back
    // face is unknown the candidate stands and finish() validates it against the thickness as
    // before: going on behind a surface of unknown depth turned rays whose truth is hidden
    // behind it into false hits (cornell's SSGI false hits 3.1 -> 6.9 %) and tripled the
    // corridor's SSR march (rays crawling a pixel at a time behind the walls). It goes on only
    // behind intervals thinner than the thickness guess: going on behind every known interval
    // lowered the colour error more on cornell, corridor and spheres (640x360 relMSE 0.0226,
    // 0.0171, 0.0123 against 0.0236, 0.0198, 0.0155) but found the wall behind the box where
    // the truth is the sphere it hides (`occluded` 0.0252 -> 0.0420, against 0.0245 here).
    // Own-pixel and background candidates are left to finish().
    SSRT_INLINE Mask passBehind(const MarchKernelArgs& a, Mask candidate) {
        const Lane zero(0.0f), one(1.0f);
        const Lane ix = pixelOf(px, a.width), iy = pixelOf(py, a.height);
        const ILane idx = depthIndex(a, ix, iy);
        const Lane sceneZ = sceneDepthAt(a, idx);
        const Lane k = ln::clamp(s.k0 + dk * t, ln::min(s.k0, s.k1), ln::max(s.k0, s.k1));
        const Lane rayZ = one / k;
        const Mask own = (ix == r.pixelX) & (iy == r.pixelY);
        const Mask surface = candidate & !own & (sceneZ < Lane(__builtin_inff()));
        if (!a.backZ || !ln::any(surface)) return surface & !surface;
        const Lane back = ln::gather(a.backZ, idx);
        const Mask thin = (back > zero) & (back <= sceneZ + thicknessAt(a, sceneZ));
        const Mask behind = surface & thin & (rayZ > back);
        if (!ln::any(behind)) return behind;
        stepOutOfCell(a, behind);
        e.thick = ln::select(behind, one, e.thick);
        return behind;
    }

    // The lanes of `m` move on to where the ray leaves its cell of the most detailed level,
    // and go on marching from that level.
    SSRT_INLINE void stepOutOfCell(const MarchKernelArgs& a, Mask m) {
        const Lane cellSize(float(1 << a.mostDetailedLevel));
        const Lane invCell(1.0f / float(1 << a.mostDetailedLevel));
        const Lane planeX = (ln::floor(px * invCell) + floorX) * cellSize + nudgeX;
        const Lane planeY = (ln::floor(py * invCell) + floorY) * cellSize + nudgeY;
        const Lane tExit = ln::min((planeX - s.x0) * invDx, (planeY - s.y0) * invDy);
        t = ln::select(m, tExit, t);
        px = s.x0 + dPx * t;
        py = s.y0 + dPy * t;
        level = ln::select(m, Lane(float(a.mostDetailedLevel)), level);
    }

    // Hit validation at full resolution (not the origin's pixel, not background, within the
    // thickness behind the surface), then the write-out.
    SSRT_INLINE void finish(MarchKernelArgs& a) {
        const Lane zero(0.0f), one(1.0f);
        const Mask hit = e.cause == endCode(MarchEnd::Hit);
        if (ln::any(hit)) {
            const Lane ix = pixelOf(px, a.width), iy = pixelOf(py, a.height);
            const ILane idx = depthIndex(a, ix, iy);
            const Lane sceneZ = sceneDepthAt(a, idx);
            const Lane k = ln::clamp(s.k0 + dk * t, ln::min(s.k0, s.k1), ln::max(s.k0, s.k1));
            const Lane rayZ = one / k;
            const Mask own = (ix == r.pixelX) & (iy == r.pixelY);
            // A candidate on a background pixel is a ray that ran out to (near) infinite
            // depth (k ~ 0, where k * inf is no test): no surface there, it reached the end of
            // its length (StepCap covers maxDistance).
            const Mask background = !(sceneZ < Lane(__builtin_inff()));
            const Mask surface = hit & !own & !background;
            const Mask valid = surface & withinSurface(a, idx, surface, rayZ, zero,
                                                       rayZ <= sceneZ + thicknessAt(a, sceneZ));
            e.cause = ln::select(hit & background, endCode(MarchEnd::StepCap), e.cause);
            e.cause = ln::select(hit & !background & !valid, endCode(MarchEnd::Thickness), e.cause);
            const Mask ok = hit & valid;
            e.hitX = ln::select(ok, px, zero);
            e.hitY = ln::select(ok, py, zero);
            e.hitZ = ln::select(ok, sceneZ, zero);
        }
        finishRays(a, base, e);
    }
};

}  // namespace

// Lane groups in flight: three with AVX-512 (32 vector registers; 8-18 % faster on incoherent
// rays than two, the same on mirror rays), two elsewhere (with AVX2 a third was no faster).
constexpr int kHiZInFlight = kW >= 16 ? 3 : 2;

void marchHiZKernel(MarchKernelArgs& a) { marchGroups<Group, kHiZInFlight>(a); }

}  // namespace ssrt::SSRT_ISA_NS
