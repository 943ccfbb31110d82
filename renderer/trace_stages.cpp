#include "renderer/trace_stages.h"

namespace ssrt::trace_stages {

// One sample's march of the frame's batch `rays` into `result`, shown to the observer.
void marchSample(const TraceContext& c, const MarchFrame& on, TracePass pass, int sample,
                 const RayBatch& rays, MarchResult& result, TraceStats& stats, StageTimes& times) {
    addTime(times.march, [&] {
        stats.march.add(marchRays(c.args.isa, c.ts.marcher, c.ts.march,
                                  {c.args.frameIndex, uint32_t(sample)}, on.camera, on.gbuffer,
                                  on.hiz, rays, result, c.threads()));
    });
    if (c.args.observer && *c.args.observer)
        (*c.args.observer)(pass, sample, rays, result, on.half);
}

// The frame's batches where the passes read them: every plane for the observer's stage-by-stage
// path; for the tile chain only the pdf (and the hits: `hits`) that what runs after the chain
// reads around each pixel.
void takeBatches(const TraceContext& c, Frame& frame, bool hits) {
    Frame::Scratch& sc = frame.scratch;
    const int w = frame.width, h = frame.height;
    if (!tiled(c)) {
        sc.pool.take(sc.rays, w, h);
        sc.pool.take(sc.march, w, h);
        return;
    }
    sc.pool.take(sc.rays.pdf, w, h);
    if (hits) sc.pool.take(sc.march.hit, w, h);
}

}  // namespace ssrt::trace_stages
