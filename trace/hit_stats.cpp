#include "trace/hit_stats.h"

#include <stdexcept>
#include <string_view>

#include "core/plane_view.h"
#include "core/tiles.h"
#include "trace/hit_stats_kernel.h"

namespace ssrt {

namespace {

constexpr std::string_view kHitStatsPass = "accumulateHitStats";

// Takes the batches' planes that the outputs need into `a`, checked to one size; their stride.
std::size_t takeBatches(HitStatsArgs& a, const RayBatch& rays, const MarchResult& m) {
    const int w = m.hit.width(), h = m.hit.height();
    const ViewF hit = viewOf(m.hit, "march.hit");
    const std::size_t stride = requireViews(kHitStatsPass, w, h, {hit});
    a.marchHit = hit.data;
    if (a.steps) {
        const ViewF steps = viewOf(m.steps, "march.steps");
        requireViews(kHitStatsPass, w, h, {steps});
        a.marchSteps = steps.data;
    }
    if (a.distance) {
        const ViewF hitX = viewOf(m.hitX, "march.hitX"), hitY = viewOf(m.hitY, "march.hitY"),
                    hitZ = viewOf(m.hitZ, "march.hitZ"), ox = viewOf(rays.ox, "ray.ox"),
                    oy = viewOf(rays.oy, "ray.oy"), oz = viewOf(rays.oz, "ray.oz");
        requireViews(kHitStatsPass, w, h, {hitX, hitY, hitZ, ox, oy, oz});
        a.hitPos[0] = hitX.data, a.hitPos[1] = hitY.data, a.hitPos[2] = hitZ.data;
        a.origin[0] = ox.data, a.origin[1] = oy.data, a.origin[2] = oz.data;
    }
    return stride;
}

}  // namespace

HitStatsAccumulator::HitStatsAccumulator(Isa isa, const TraceCamera& camera,
                                         const HitStatsArgs& out, int sample, int sampleCount)
    : args_(out), grid_(camera.width, camera.height) {
    const int w = camera.width, h = camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("accumulateHitStats: empty camera");
    if (sampleCount < 1 || sample < 0 || sample >= sampleCount)
        throw std::invalid_argument("accumulateHitStats: sample must be in [0, sampleCount)");
    HitStatsArgs& a = args_;
    a.stride = requireViews(kHitStatsPass, w, h, {a.hit});
    // (steps and distance are optional: checked where given)
    for (const OutF& v : {a.steps, a.distance})
        if (v) requireViews(kHitStatsPass, w, h, {v});
    a.width = w;
    a.height = h;
    a.tilesX = grid_.tilesX;
    a.tanHalfX = camera.tanHalfX;
    a.tanHalfY = camera.tanHalfY;
    a.first = sample == 0;
    a.last = sample == sampleCount - 1;
    a.invCount = 1.0f / float(sampleCount);
    kernel_ = SSRT_DISPATCH(isa, hitStatsTile);
}

void HitStatsAccumulator::tile(int tile, const RayBatch& rays, const MarchResult& march) const {
    const TileRect r = grid_.rect(tile);
    const BatchCorner c = march.corner;
    if (!sameCornerHolds(rays, march, r))
        throw std::invalid_argument("accumulateHitStats: the batches do not hold the tile");
    HitStatsArgs a = args_;
    a.inStride = takeBatches(a, rays, march);
    a.inX0 = c.x0;
    a.inY0 = c.y0;
    kernel_(a, tile);
}

void accumulateHitStats(Isa isa, const TraceCamera& camera, const RayBatch& rays,
                        const MarchResult& march, const HitStatsArgs& out, int sample,
                        int sampleCount, int threads) {
    const HitStatsAccumulator acc(isa, camera, out, sample, sampleCount);
    // The frame's batches, of the frame's size.
    requireViews(kHitStatsPass, camera.width, camera.height, {viewOf(march.hit, "march.hit")});
    if (out.distance)
        requireViews(kHitStatsPass, camera.width, camera.height, {viewOf(rays.ox, "ray.ox")});
    parallelForTiles(acc.grid().count(), threads, [&](int t) { acc.tile(t, rays, march); });
}

}  // namespace ssrt
