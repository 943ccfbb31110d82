// What the screen-space passes share (renderer/trace_pass.cpp runs them; one file each:
// ssr_pass.cpp, ssgi_pass.cpp, denoise_pass.cpp, composite_pass.cpp): the frame's G-buffer as
// their stages read it, their stage times, the march of one sample, the tile chain.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/plane_view.h"
#include "renderer/frame_scheduler.h"
#include "renderer/pass_timer.h"
#include "renderer/trace_pass.h"
#include "trace/hit_stats.h"
#include "trace/reconstruct.h"
#include "trace/tile_chain.h"

namespace ssrt::trace_stages {

// The back-face depth layer when the frame has one (renderer.cpp, backDepthPass), else null.
inline const PlaneF* backZ(const PlaneF& p) { return p.empty() ? nullptr : &p; }

// The name `group`'s table gives its plane `p` (empty for a plane not its).
template <class Group, class T>
std::string_view planeName(const Group& group, const Plane<T>& p) {
    std::string_view name;
    group.forEachPlane([&](std::string_view n, const auto& q) {
        if (static_cast<const void*>(&q) == &p) name = n;
    });
    return name;
}

// The view of `p`, one of `group`'s planes, by its table's name.
template <class Group, class T>
PlaneView<const T> viewIn(const Group& group, const Plane<T>& p) {
    return viewOf(p, planeName(group, p));
}

// The same of a plane a stage writes every pixel of: sized to the camera first. Absent for a
// null plane (debugPlane's "not asked for").
template <class Group>
OutF stageOutput(Group& group, PlaneF* p, const TraceCamera& camera) {
    if (!p) return {};
    p->ensureSize(camera.width, camera.height);
    return outputOf(*p, planeName(group, *p));
}

// The same of one of the frame's outputs (OutputStore); absent unless `made`.
inline OutF stageOutput(Frame& frame, Res id, const TraceCamera& camera, bool made = true) {
    return made ? frame.outputs.output(id, 0, camera.width, camera.height) : OutF{};
}

// Times of one trace pass's stages, summed over its samples.
struct StageTimes {
    double rays = 0.0, march = 0.0, resolve = 0.0;
    double reconstruct = -1.0;  // reported when a layout other than full ran (>= 0)
    double world = 0.0;         // world rays (mixed, world tracing), reported when they ran
    bool worldRan = false;
    void report(FrameStats& stats, const char* pass) const {
        const std::string p(pass);
        stats.passes.push_back({p + " rays", rays});
        stats.passes.push_back({p + " march", march});
        stats.passes.push_back({p + " resolve", resolve});
        if (worldRan) stats.passes.push_back({p + " world", world});
        if (reconstruct >= 0.0) stats.passes.push_back({p + " reconstruct", reconstruct});
    }
};

// The frame a pass's rays are generated and marched on: the frame's own camera, G-buffer and
// pyramid, or the half frame's (`half`, TraceLayout::Half).
struct MarchFrame {
    const TraceCamera& camera;
    const GBufferView& g;
    const PlaneF* backZ;
    const HiZPyramid* hiz;
    const HalfFrame* half;
};

// Whether `pass` leaves its rays unmarched (RayMarcher::skipMarch): a signal traced in world
// space answers every ray there.
inline bool skipsMarch(const TraceContext& c, TracePass pass) {
    return traceMode(c, pass) == TraceMode::World;
}

// One sample's march of the frame's batch `rays` into `result` (none where skipsMarch, nor in
// the tiles `skipTiles` marks: MixedTileClassifier), then what `answer` (when given: world rays)
// answers in its place, shown to the observer.
void marchSample(const TraceContext& c, const MarchFrame& on, TracePass pass, int sample,
                 const RayBatch& rays, MarchResult& result, TraceStats& stats, StageTimes& times,
                 const std::function<void(MarchResult&)>& answer = {},
                 const std::vector<uint8_t>* skipTiles = nullptr);

// The half frame's traced signal's planes from the pool (tracedSignalsPooled; the denoiser
// gives them back once its front end has read them), its march steps aside: only looked at,
// not made then. (The frame's own signals are the frame memory's: renderer/frame_memory.h.)
template <class Group>
void takeSignal(PlanePool& pool, Group& g, int w, int h) {
    g.forEachPlane([&](std::string_view, PlaneF& p) {
        if (&p != &g.steps) pool.take(p, w, h);
    });
}

// Whether the trace runs tile by tile (trace/tile_chain.h): unless the observer (the truth's
// ray check) asks for the frame's rays and march results.
inline bool tiled(const TraceContext& c) { return !(c.observer && *c.observer); }

// The frame's batches where the passes read them: every plane for the observer's stage-by-stage
// path; for the tile chain only the pdf, which what runs after the chain reads around each
// pixel (the SSR resolve sizes the ring of hits its finish stage reads: trace/ssr_resolve.h).
void takeBatches(const TraceContext& c, Frame& frame);

// One sample's tile chain (trace/tile_chain.h): on each tile's batches the resolve's
// per-pixel pass, then the hit statistics; and the resolve's pass over a tile's neighbours
// (`finish`, when given) a tile row at a time behind it; `answer`, when given, between the
// march and the resolve (world rays: renderer/world_stage.h). Adds the march's counters and
// the stages' times; returns the rays' counters.
template <class Resolve>
RayGenStats traceTiles(const TraceContext& c, const RayGenerator& rays, const RayMarcher& march,
                       const Resolve& resolveTile, const HitStatsAccumulator& hitStats,
                       TraceStats& st, StageTimes& times, std::function<void(int tile)> finish = {},
                       std::function<void(int, const RayBatch&, MarchResult&)> answer = {}) {
    const bool answers = bool(answer);
    const TileChainStats r = runTileChain({rays, march,
                                           [&](int t, const RayBatch& b, const MarchResult& m) {
                                               resolveTile(t, b, m);
                                               hitStats.tile(t, b, m);
                                           },
                                           std::move(finish), std::move(answer)},
                                          c.threads());
    st.march.add(r.march);
    times.rays += r.raysMs;
    times.march += r.marchMs;
    times.resolve += r.consumeMs + r.finishMs;
    if (answers) times.world += r.answerMs, times.worldRan = true;
    return r.rays;
}

// The passes, in the order runTracePasses gives them to the frame scheduler: SSR's and SSGI's
// run over the whole frame; the denoiser's passes and the composite are tiled passes, which
// the scheduler runs in one loop where the frame graph chains them (denoise_pass.cpp,
// composite_pass.cpp). Each schedule function returns what to do once the scheduler has run
// into the stats given (the denoiser's check that the graph ran each of its passes; the
// composite's upsample's own line).
void ssrPass(const TraceContext& c, Frame& frame);
void ssgiPass(const TraceContext& c, Frame& frame);
std::function<void()> scheduleDenoiser(const TraceContext& c, Frame& frame, FrameScheduler& passes);
void scheduleUpsample(const TraceContext& c, Frame& frame, FrameScheduler& passes,
                      FrameStats& stats);
std::function<void(FrameStats&)> scheduleComposite(const TraceContext& c, Frame& frame,
                                                   FrameScheduler& passes);

}  // namespace ssrt::trace_stages
