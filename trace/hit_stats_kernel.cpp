#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_vec.h"
#include "core/tiles.h"
#include "trace/hit_stats_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;

namespace {

void hitStatsChunk(const HitStatsArgs& a, int x, int y) {
    const std::size_t o = std::size_t(y) * a.stride + x;
    const std::size_t i = std::size_t(y - a.inY0) * a.inStride + std::size_t(x - a.inX0);
    const Lane zero(0.0f);
    const Lane hit = loadAt(a.marchHit, i);
    Lane hitSum = hit;
    if (!a.first) hitSum = loadAt(a.hit.data, o) + hit;
    if (a.distance.data) {
        Lane d = zero;
        const auto hits = hit > zero;
        if (ln::any(hits)) {
            // The hit's view-space point from its pixel position and depth, minus the origin
            // (the scalar loop's expressions, in its order).
            const Lane z = loadAt(a.hitPos[2], i);
            const Lane px =
                ((Lane(2.0f) * loadAt(a.hitPos[0], i)) / Lane(float(a.width)) - Lane(1.0f)) *
                Lane(a.tanHalfX) * z;
            const Lane py =
                (Lane(1.0f) - (Lane(2.0f) * loadAt(a.hitPos[1], i)) / Lane(float(a.height))) *
                Lane(a.tanHalfY) * z;
            const Lane dx = px - loadAt(a.origin[0], i), dy = py - loadAt(a.origin[1], i),
                       dz = -z - loadAt(a.origin[2], i);
            d = ln::select(hits, ln::sqrt(dx * dx + dy * dy + dz * dz), zero);
        }
        Lane distSum = d;
        if (!a.first) distSum = loadAt(a.distance.data, o) + d;
        if (a.last) {
            const auto any = hitSum > zero;
            distSum = ln::select(any, distSum / ln::select(any, hitSum, Lane(1.0f)), zero);
        }
        ln::store(a.distance.data + o, distSum);
    }
    if (a.last) hitSum = hitSum * Lane(a.invCount);
    ln::store(a.hit.data + o, hitSum);
    if (a.steps.data) {
        Lane stepSum = loadAt(a.marchSteps, i);
        if (!a.first) stepSum = loadAt(a.steps.data, o) + stepSum;
        if (a.last) stepSum = stepSum * Lane(a.invCount);
        ln::store(a.steps.data + o, stepSum);
    }
}

}  // namespace

void hitStatsTile(const HitStatsArgs& args, int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, args.tilesX, args.width, args.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) hitStatsChunk(args, x, y);
}

}  // namespace ssrt::SSRT_ISA_NS
