#include "trace/hit_stats.h"

#include <stdexcept>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "trace/hit_stats_kernel.h"

namespace ssrt {

void accumulateHitStats(Isa isa, const TraceCamera& camera, const RayBatch& rays,
                        const MarchResult& march, const HitStatsPlanes& out, int sample,
                        int sampleCount, int threads) {
    const int w = camera.width, h = camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("accumulateHitStats: empty camera");
    if (sampleCount < 1 || sample < 0 || sample >= sampleCount)
        throw std::invalid_argument("accumulateHitStats: sample must be in [0, sampleCount)");
    if (!out.hit) throw std::invalid_argument("accumulateHitStats: hit plane needed");
    out.hit->ensureSize(w, h);
    if (out.steps) out.steps->ensureSize(w, h);
    if (out.distance) out.distance->ensureSize(w, h);
    const TileGrid grid(w, h);
    HitStatsArgs a{};
    a.width = w;
    a.height = h;
    a.tilesX = grid.tilesX;
    a.tanHalfX = camera.tanHalfX;
    a.tanHalfY = camera.tanHalfY;
    PlaneCheck need("accumulateHitStats", w, h);
    a.hit = need(march.hit, "march hit");
    if (out.steps) {
        a.steps = need(march.steps, "march steps");
        a.outSteps = need.output(*out.steps, "steps");
    }
    if (out.distance) {
        a.hitPos[0] = need(march.hitX, "march hitX");
        a.hitPos[1] = need(march.hitY, "march hitY");
        a.hitPos[2] = need(march.hitZ, "march hitZ");
        a.origin[0] = need(rays.ox, "ray origin");
        a.origin[1] = need(rays.oy, "ray origin");
        a.origin[2] = need(rays.oz, "ray origin");
        a.outDistance = need.output(*out.distance, "distance");
    }
    a.outHit = need.output(*out.hit, "hit");
    a.stride = need.stride();
    a.first = sample == 0;
    a.last = sample == sampleCount - 1;
    a.invCount = 1.0f / float(sampleCount);
    const auto tileFn = SSRT_DISPATCH(isa, hitStatsTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { tileFn(a, tile); });
}

}  // namespace ssrt
