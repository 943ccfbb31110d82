#include <algorithm>
#include <chrono>
#include <deque>
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/frame_scheduler.h"
#include "renderer/trace_stages.h"
#include "trace/reconstruct.h"

namespace ssrt::trace_stages {

namespace {

// What both of the frame's denoiser calls share: the camera they run at (the half frame's or
// the frame's), the frame, whether the history is replaced and the temporal pass runs, and the
// frame's pool of scratch.
DenoiseCall denoiseCall(const TraceContext& c, Frame& frame, const TraceCamera& camera, bool half) {
    DenoiseCall in;
    in.camera = camera;
    in.frameIndex = c.frameIndex;
    in.replaceHistory = c.replaceHistory;
    // (Where the graph culls the temporal pass: no history to read or keep.)
    in.temporal = c.graph.runs(half ? pass::kDenoiseTemporalHalf : pass::kDenoiseTemporal);
    in.pool = &frame.scratch.pool;
    return in;
}

// A signal's history lengths, a plane only to be looked at: absent when not asked for.
OutF historyLengths(const TraceContext& c, PlaneStore& store, Res id, int w, int h) {
    return c.settings.debugPlanes ? store.output(id, 0, w, h) : OutF{};
}

// The diffuse signal where SSGI traces at half resolution: denoised on the half frame (a
// quarter of the pixels, at the resolution it was traced), on guides from each block's first
// pixel (HalfFrame::guide), then brought to the frame by the guided upsample that brings the
// raw signal (trace/reconstruct.h), placing each half pixel at that first pixel.
DenoiseCall halfDiffuseCall(const TraceContext& c, Frame& frame) {
    Frame::Scratch::HalfTrace& ht = frame.scratch.half;
    const HalfFrame& hf = ht.frame;
    DenoiseCall in = denoiseCall(c, frame, hf.camera, true);
    // The guides, with the chosen pixels' albedo and metallic for the diffuse signal.
    in.g = withPlanes(
        gbufferView("the half frame's guides", hf.camera.width, hf.camera.height, hf.guide),
        hf.view(), kGAlbedo | kGMetallic);
    for (int i = 0; i < 3; ++i) in.diffuse[i] = viewIn(ht.resolved, ht.resolved.color[i]);
    in.diffuseHitDistance = viewIn(ht.resolved, ht.resolved.hitDistance);
    if (tracedSignalsPooled(c.settings))
        in.signalsRead = [&frame] { frame.scratch.pool.give(frame.scratch.half.resolved); };
    PlaneStore& half = ht.denoised;
    const int w = hf.camera.width, h = hf.camera.height;
    for (int ch = 0; ch < 3; ++ch)
        in.denoisedDiffuse[ch] = half.output(Res::HalfDenoised, ch, w, h);
    in.diffuseFrames = historyLengths(c, half, Res::HalfDiffuseFrames, w, h);
    return in;
}

// The half frame's denoised diffuse brought to the frame's planes (where the composite does
// not bring it tile by tile).
void upsampleHalfDiffuse(const TraceContext& c, Frame& frame, FrameStats& stats) {
    const ScopedPass timer(stats, "denoise upsample");
    PlaneStore& half = frame.scratch.half.denoised;
    // (The history length, a plane to look at, is blended as the hit share is.)
    const std::span<PlaneF, 3> from = half.rgb(Res::HalfDenoised);
    const std::span<PlaneF, 3> to = frame.rgb(Res::DenoisedDiffuse);
    const ReconstructSource source{
        {&from[0], &from[1], &from[2]}, nullptr, c.debugPlane(half.plane(Res::HalfDiffuseFrames))};
    const ReconstructPlanes target{
        {&to[0], &to[1], &to[2]}, nullptr, c.debugPlane(frame.plane(Res::DiffuseFrames))};
    upsampleHalf(c.isa, c.guides(frame), PixelOffset{0, 0}, frame.scratch.half.rays.pdf, source,
                 target, c.threads());
}

// The full-resolution call: SSGI's diffuse where it traced at full resolution, SSR's signal.
DenoiseCall fullCall(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts();
    const int w = c.camera.width, h = c.camera.height;
    DenoiseCall in = denoiseCall(c, frame, c.camera, false);
    in.g = frame.gbuffer.view();
    if (ts.ssgi && ts.ssgiLayout != TraceLayout::Half) {
        for (int ch = 0; ch < 3; ++ch) {
            in.diffuse[ch] = frame.view(Res::Ssgi, ch);
            in.denoisedDiffuse[ch] = frame.outputs.output(Res::DenoisedDiffuse, ch, w, h);
        }
        in.diffuseHitDistance = frame.view(Res::SsgiHitDistance);
        in.diffuseFrames = historyLengths(c, frame.outputs, Res::DiffuseFrames, w, h);
    }
    if (ts.ssr) {
        for (int ch = 0; ch < 3; ++ch) {
            in.ssr[ch] = frame.view(Res::Ssr, ch);
            in.envSpecular[ch] = viewIn(frame.direct, frame.direct.envSpecular[ch]);
            in.denoisedSpecular[ch] = frame.outputs.output(Res::DenoisedSpecular, ch, w, h);
        }
        in.specularFrames = historyLengths(c, frame.outputs, Res::SpecularFrames, w, h);
        in.ssrOpacity = frame.view(Res::SsrOpacity);
        in.specularHitDistance = frame.view(Res::SsrHitDistance);
        // Where SSR has faded out the blend is the environment alone: nothing to denoise.
        in.specularMaxRoughness = ts.resolve.roughnessFadeEnd;
    }
    // The traced signals no later pass reads go back to the pool before the denoiser's later
    // passes take their results from it.
    in.signalsRead = [&c] { c.memory.giveThrough(pass::kDenoiseFrontEnd); };
    return in;
}

// A run's steps as the frame graph's passes ("denoise " + the step + `suffix`), each on the
// run's tiles; `before` (optional) runs before the first step's set-up. Every step must be a
// pass the graph runs, and the graph may run no pass of this denoiser that is not a step:
// else std::logic_error (the two disagree on the passes, and an output would go unwritten).
void schedule(FrameScheduler& passes, const CompiledGraph& graph, const DenoiseRun& run,
              std::string_view suffix, std::deque<std::string>& names,
              std::function<void()> before = {}) {
    const std::size_t first = names.size();
    for (const DenoiseStep& s : run.steps()) {
        names.push_back("denoise " + std::string(s.name) + std::string(suffix));
        if (!graph.runs(names.back()))
            throw std::logic_error("the frame graph does not run '" + names.back() +
                                   "', which the denoiser does");
        std::function<void()> setUp = s.setUp;
        if (before && names.size() == first + 1)
            setUp = [before, setUp] {
                before();
                if (setUp) setUp();
            };
        passes.tiled(names.back(), s.tile, std::move(setUp), s.finish, &run.grid());
    }
    for (const GraphPass& g : graph.passes) {
        const std::string_view name = g.decl->name;
        const bool ours = name.rfind("denoise ", 0) == 0 && name != pass::kDenoiseUpsample &&
                          (name.size() >= 7 && name.substr(name.size() - 7) == " (half)") ==
                              (suffix == " (half)");
        if (ours &&
            std::find(names.begin() + std::ptrdiff_t(first), names.end(), name) == names.end())
            throw std::logic_error("the frame graph runs '" + std::string(name) +
                                   "', which the denoiser does not");
    }
}

}  // namespace

// REBLUR over SSGI's and SSR's signals (denoise/denoise.h) into the frame's denoised outputs
// (Res::DenoisedDiffuse, Res::DenoisedSpecular), which the composite then reads; the traced
// planes stay as they were (the undenoised layers). The denoiser's passes run on the frame
// scheduler, so those the frame graph chains share a loop over the tiles.
void denoisePass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts();
    const bool halfDiffuse = ts.ssgi && ts.ssgiLayout == TraceLayout::Half;
    FrameScheduler passes(c.graph, TileGrid(c.camera.width, c.camera.height), c.threads(),
                          c.cancel);
    std::deque<std::string> names;  // (the passes' names, which the scheduler keeps views of)
    // The half frame's diffuse first (the graph's order): its planes go back before the
    // full-resolution denoiser takes its scratch.
    const DenoiseSettings halfSettings = halfResolutionDiffuse(ts.denoise);
    std::optional<DenoiseCall> halfIn;
    std::optional<DenoiseRun> half;
    if (halfDiffuse) {
        halfIn.emplace(halfDiffuseCall(c, frame));
        DenoiseHistory* history = c.sequence ? &c.sequence->denoiseHalf : nullptr;
        half.emplace(c.isa, halfSettings, *halfIn, history, c.resetHistory,
                     frame.scratch.half.denoise, c.threads());
        schedule(passes, c.graph, *half, " (half)", names);
    }
    FrameStats stats;
    if (halfDiffuse && !diffuseUpsampledInComposite(c.settings))
        passes.whole(pass::kDenoiseUpsample, [&] { upsampleHalfDiffuse(c, frame, stats); });
    const DenoiseCall in = fullCall(c, frame);
    std::optional<DenoiseRun> full;
    if (in.hasDiffuse() || in.hasSpecular()) {
        DenoiseHistory* history = c.sequence ? &c.sequence->denoise : nullptr;
        full.emplace(c.isa, ts.denoise, in, history, c.resetHistory, frame.scratch.denoise,
                     c.threads());
        std::function<void()> before;
        if (halfDiffuse) before = [&c] { c.memory.giveThrough(pass::kDenoiseUpsample); };
        schedule(passes, c.graph, *full, "", names, std::move(before));
    }
    passes.run(stats);
    // One line per pass, the half frame's and the frame's summed.
    for (PassTime& t : stats.passes) {
        const std::size_t at = t.name.find(" (half)");
        if (at != std::string::npos) t.name.erase(at);
        auto same = std::find_if(frame.stats.passes.begin(), frame.stats.passes.end(),
                                 [&](const PassTime& p) { return p.name == t.name; });
        if (same != frame.stats.passes.end()) same->ms += t.ms;
        else frame.stats.passes.push_back(t);
    }
}

}  // namespace ssrt::trace_stages
