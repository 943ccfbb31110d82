#include "renderer/trace_pass.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "renderer/pass_timer.h"
#include "renderer/trace_stages.h"

namespace ssrt {

using namespace trace_stages;

namespace {

// Hi-Z pyramid of the depth buffer, shared by both passes (half-resolution SSGI marches on
// its own pyramid).
void hiZPass(TraceContext& c, Frame& frame) {
    const ScopedPass timer(frame.stats, "hi-z");
    const PassReads depth(c.graph, frame, pass::kHiZ);  // (checks the depth it reads)
    buildHiZ(frame.gbuffer.viewZ, frame.scratch.hiz, c.threads());
    c.hiz = &frame.scratch.hiz;
}

// The pixels mixed SSR's proof looks at beside a ray's path (trace/hit_proof.h).
void thinFeaturesPass(const TraceContext& c, Frame& frame) {
    const ScopedPass timer(frame.stats, pass::kThinFeatures.data());
    const PassReads depth(c.graph, frame, pass::kThinFeatures);
    findThinFeatures(depth.view(Res::ViewZ), frame.scratch.thin, c.threads());
}

}  // namespace

bool tracedSignalsPooled(const RenderSettings& s) {
    return s.trace.denoise.enabled && !s.debugPlanes;
}

bool hitLightAtHalf(const RenderSettings& s) {
    const TraceSettings& t = s.trace;
    return t.ssgi && t.ssgiLayout == TraceLayout::Half && !t.ssgiFeedback && !s.debugPlanes;
}

bool diffuseUpsampledInComposite(const RenderSettings& s) {
    const TraceSettings& t = s.trace;
    return t.ssgi && t.denoise.enabled && t.ssgiLayout == TraceLayout::Half && !s.debugPlanes &&
           !t.ssgiFeedback;
}

// The screen-space passes on one frame scheduler, each whole pass and each chain one step of
// the frame's memory: SSR's and SSGI's passes over the whole frame, then the denoiser's passes
// and the composite, in one loop over the tiles where the graph chains them. Their times are
// collected apart and added after (the half frame's denoiser passes under the frame's names).
void runTracePasses(TraceContext c, Frame& frame) {
    c.camera = frame.camera;
    c.backZ = backZ(frame.scratch.backZ);
    FrameScheduler passes(c.graph, TileGrid(c.camera.width, c.camera.height), c.threads(), c.cancel,
                          &c.memory);
    FrameStats stats;
    passes.whole(pass::kHiZ, [&] { hiZPass(c, frame); });
    passes.whole(pass::kThinFeatures, [&] { thinFeaturesPass(c, frame); });
    passes.whole(
        pass::kSsr, [&] { ssrPass(c, frame); }, pass::kSsrReconstruct);
    // (On the half frame SSGI's first pass makes the half frame.)
    passes.whole(
        c.graph.runs(pass::kSsgi) ? pass::kSsgi : pass::kSsgiHalfFrame, [&] { ssgiPass(c, frame); },
        pass::kSsgiReconstruct);
    const std::function<void()> checkDenoiser = scheduleDenoiser(c, frame, passes);
    scheduleUpsample(c, frame, passes, stats);
    const std::function<void(FrameStats&)> compositeTimes = scheduleComposite(c, frame, passes);
    passes.run(stats);
    checkDenoiser();
    compositeTimes(stats);
    // One line per pass, the half frame's denoiser's and the frame's summed (in a loop with
    // the pass before it where either was).
    for (PassTime& t : stats.passes) {
        const std::size_t at = t.name.find(" (half)");
        if (at != std::string::npos) t.name.erase(at);
        auto same = std::find_if(frame.stats.passes.begin(), frame.stats.passes.end(),
                                 [&](const PassTime& p) { return p.name == t.name; });
        if (same != frame.stats.passes.end()) same->ms += t.ms, same->fused |= t.fused;
        else frame.stats.passes.push_back(t);
    }
}

bool readsHistory(const TraceSettings& s) {
    return (s.ssr && s.resolve.radiance == HitRadiance::Reprojected) || (s.ssgi && s.ssgiFeedback);
}

namespace {

// A non-finite value (a NaN from a bad input, an overflow) is committed as 0, no light: the
// next frames read the history through the reprojection (SSR's reprojected radiance, SSGI
// feedback), and a NaN kept there would spread to every pixel that reflects it, frame after
// frame, long after the input that made it is gone.
void commitPlanes(const PassReads& r, Res id, PlaneF* dst, int w, int h) {
    for (int ch = 0; ch < 3; ++ch) {
        dst[ch].ensureSize(w, h);  // kept across frames: no allocation once sized
        const ViewF src = r.view(id, ch);
        for (int y = 0; y < h; ++y) {
            const float* in = src.row(y);
            float* out = dst[ch].row(y);
            for (int x = 0; x < w; ++x) out[x] = std::isfinite(in[x]) ? in[x] : 0.0f;
        }
    }
}

}  // namespace

void commitHistory(const CompiledGraph& graph, const Frame& frame, FrameHistory& history) {
    const int w = frame.width, h = frame.height;
    const PassReads r(graph, frame, pass::kHistoryCommit);
    // The colour always (FrameHistory::usableAt goes by its size); for SSGI's feedback, the
    // incoming diffuse radiance its next hits reflect: the planes the composite multiplied by
    // the diffuse colour, the denoiser's where it ran (a bounce of one-ray noise fed back would
    // come back as noise), else SSGI's.
    commitPlanes(r, Res::Color, history.color, w, h);
    if (r.has(Res::DenoisedDiffuse)) commitPlanes(r, Res::DenoisedDiffuse, history.diffuse, w, h);
    else if (r.has(Res::Ssgi)) commitPlanes(r, Res::Ssgi, history.diffuse, w, h);
    history.valid = true;
}

}  // namespace ssrt
