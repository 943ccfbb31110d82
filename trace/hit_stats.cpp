#include "trace/hit_stats.h"

#include <stdexcept>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "trace/hit_stats_kernel.h"

namespace ssrt {

HitStatsAccumulator::HitStatsAccumulator(Isa isa, const TraceCamera& camera,
                                         const HitStatsPlanes& out, int sample, int sampleCount)
    : grid_(camera.width, camera.height) {
    const int w = camera.width, h = camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("accumulateHitStats: empty camera");
    if (sampleCount < 1 || sample < 0 || sample >= sampleCount)
        throw std::invalid_argument("accumulateHitStats: sample must be in [0, sampleCount)");
    if (!out.hit) throw std::invalid_argument("accumulateHitStats: hit plane needed");
    out.hit->ensureSize(w, h);
    if (out.steps) out.steps->ensureSize(w, h);
    if (out.distance) out.distance->ensureSize(w, h);
    HitStatsArgs& a = args_;
    a.width = w;
    a.height = h;
    a.tilesX = grid_.tilesX;
    a.tanHalfX = camera.tanHalfX;
    a.tanHalfY = camera.tanHalfY;
    PlaneCheck need("accumulateHitStats", w, h);
    if (out.steps) a.outSteps = need.output(*out.steps, "steps");
    if (out.distance) a.outDistance = need.output(*out.distance, "distance");
    a.outHit = need.output(*out.hit, "hit");
    a.stride = need.stride();
    a.first = sample == 0;
    a.last = sample == sampleCount - 1;
    a.invCount = 1.0f / float(sampleCount);
    kernel_ = SSRT_DISPATCH(isa, hitStatsTile);
}

void HitStatsAccumulator::tile(int tile, const RayBatch& rays, const MarchResult& march) const {
    const TileRect r = grid_.rect(tile);
    const BatchCorner c = march.corner;
    const int w = march.hit.width(), h = march.hit.height();
    if (!sameCornerHolds(rays, march, r))
        throw std::invalid_argument("accumulateHitStats: the batches do not hold the tile");
    HitStatsArgs a = args_;
    PlaneCheck need("accumulateHitStats", w, h);
    a.hit = need(march.hit, "march hit");
    if (a.outSteps) a.steps = need(march.steps, "march steps");
    if (a.outDistance) {
        a.hitPos[0] = need(march.hitX, "march hitX");
        a.hitPos[1] = need(march.hitY, "march hitY");
        a.hitPos[2] = need(march.hitZ, "march hitZ");
        a.origin[0] = need(rays.ox, "ray origin");
        a.origin[1] = need(rays.oy, "ray origin");
        a.origin[2] = need(rays.oz, "ray origin");
    }
    a.inStride = need.stride();
    a.inX0 = c.x0;
    a.inY0 = c.y0;
    kernel_(a, tile);
}

void accumulateHitStats(Isa isa, const TraceCamera& camera, const RayBatch& rays,
                        const MarchResult& march, const HitStatsPlanes& out, int sample,
                        int sampleCount, int threads) {
    const HitStatsAccumulator acc(isa, camera, out, sample, sampleCount);
    const int w = camera.width, h = camera.height;
    PlaneCheck need("accumulateHitStats", w, h);  // the frame's batches, of the frame's size
    need(march.hit, "march hit");
    if (out.distance) need(rays.ox, "ray origin");
    parallelForTiles(acc.grid().count(), threads, [&](int t) { acc.tile(t, rays, march); });
}

}  // namespace ssrt
