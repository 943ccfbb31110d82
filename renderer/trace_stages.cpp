#include "renderer/trace_stages.h"

namespace ssrt::trace_stages {

// One sample's march of the frame's batch `rays` into `result`, shown to the observer.
void marchSample(const TraceContext& c, const MarchFrame& on, TracePass pass, int sample,
                 const RayBatch& rays, MarchResult& result, TraceStats& stats, StageTimes& times,
                 const std::function<void(MarchResult&)>& answer,
                 const std::vector<uint8_t>* skipTiles) {
    addTime(times.march, [&] {
        stats.march.add(marchRays(
            c.isa, c.ts().marcher, c.ts().march, {c.frameIndex, uint32_t(sample)}, on.camera, on.g,
            on.backZ, on.hiz, rays, result, c.threads(), skipsMarch(c, pass), skipTiles));
    });
    if (answer) answer(result);
    if (c.observer && *c.observer) (*c.observer)(pass, sample, rays, result, on.half);
}

void takeBatches(const TraceContext& c, Frame& frame) {
    Frame::Scratch& sc = frame.scratch;
    const int w = frame.width, h = frame.height;
    if (!tiled(c)) {
        sc.pool.take(sc.rays, w, h);
        sc.pool.take(sc.march, w, h);
        return;
    }
    sc.pool.take(sc.rays.pdf, w, h);
}

}  // namespace ssrt::trace_stages
