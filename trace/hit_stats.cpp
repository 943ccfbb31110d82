#include "trace/hit_stats.h"

#include <stdexcept>
#include <string>

#include "core/tiles.h"
#include "trace/hit_stats_kernel.h"

namespace ssrt {

namespace {

const float* need(const PlaneF* p, int w, int h, const char* what) {
    if (!p || p->width() != w || p->height() != h)
        throw std::invalid_argument(std::string("accumulateHitStats: ") + what +
                                    " missing or not of the frame's size");
    return p->row(0);
}

}  // namespace

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
    a.stride = out.hit->stride();
    a.tanHalfX = camera.tanHalfX;
    a.tanHalfY = camera.tanHalfY;
    a.hit = need(&march.hit, w, h, "march hit");
    if (out.steps) {
        a.steps = need(&march.steps, w, h, "march steps");
        a.outSteps = out.steps->row(0);
    }
    if (out.distance) {
        a.hitPos[0] = need(&march.hitX, w, h, "march hitX");
        a.hitPos[1] = need(&march.hitY, w, h, "march hitY");
        a.hitPos[2] = need(&march.hitZ, w, h, "march hitZ");
        a.origin[0] = need(&rays.ox, w, h, "ray origin");
        a.origin[1] = need(&rays.oy, w, h, "ray origin");
        a.origin[2] = need(&rays.oz, w, h, "ray origin");
        a.outDistance = out.distance->row(0);
    }
    a.outHit = out.hit->row(0);
    a.first = sample == 0;
    a.last = sample == sampleCount - 1;
    a.invCount = 1.0f / float(sampleCount);
    const auto tileFn = SSRT_DISPATCH(isa, hitStatsTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { tileFn(a, tile); });
}

}  // namespace ssrt
