#include <algorithm>
#include <chrono>
#include <span>
#include <vector>

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
void denoiseHalfDiffuse(const TraceContext& c, Frame& frame, std::vector<DenoisePassTime>& times) {
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
    DenoiseHistory* history = c.sequence ? &c.sequence->denoiseHalf : nullptr;
    denoise(c.isa, halfResolutionDiffuse(c.ts().denoise), in, history, c.resetHistory, ht.denoise,
            c.threads(), &times);
    if (diffuseUpsampledInComposite(c.settings)) return;  // (compositePass)
    const auto t0 = std::chrono::steady_clock::now();
    // (The history length, a plane to look at, is blended as the hit share is.)
    const std::span<PlaneF, 3> from = half.rgb(Res::HalfDenoised);
    const std::span<PlaneF, 3> to = frame.rgb(Res::DenoisedDiffuse);
    const ReconstructSource source{
        {&from[0], &from[1], &from[2]}, nullptr, c.debugPlane(half.plane(Res::HalfDiffuseFrames))};
    const ReconstructPlanes target{
        {&to[0], &to[1], &to[2]}, nullptr, c.debugPlane(frame.plane(Res::DiffuseFrames))};
    upsampleHalf(c.isa, c.guides(frame), PixelOffset{0, 0}, ht.rays.pdf, source, target,
                 c.threads());
    const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - t0;
    times.push_back({"denoise upsample", ms.count()});
}

}  // namespace

// REBLUR over SSGI's and SSR's signals (denoise/denoise.h) into the frame's denoised outputs
// (Res::DenoisedDiffuse, Res::DenoisedSpecular), which the composite then reads; the traced
// planes stay as they were (the undenoised layers).
void denoisePass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts();
    const bool halfDiffuse = ts.ssgi && ts.ssgiLayout == TraceLayout::Half;
    const int w = c.camera.width, h = c.camera.height;
    DenoiseCall in = denoiseCall(c, frame, c.camera, false);
    in.g = frame.gbuffer.view();
    if (ts.ssgi && !halfDiffuse) {
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
    // The traced signals no later pass reads go back to the pool before the denoiser's
    // scratch is taken from it.
    in.signalsRead = [&c] { c.memory.giveThrough(pass::kDenoiseFrontEnd); };
    DenoiseHistory* history = c.sequence ? &c.sequence->denoise : nullptr;
    std::vector<DenoisePassTime> times;
    // The half frame's diffuse first (the graph's order): its planes go back before the
    // full-resolution denoiser takes its scratch.
    if (halfDiffuse) {
        denoiseHalfDiffuse(c, frame, times);
        c.memory.giveThrough(pass::kDenoiseUpsample);
    }
    if (in.hasDiffuse() || in.hasSpecular())
        denoise(c.isa, ts.denoise, in, history, c.resetHistory, frame.scratch.denoise, c.threads(),
                &times);
    // One line per pass, summed over the two calls.
    for (const DenoisePassTime& t : times) {
        auto same = std::find_if(frame.stats.passes.begin(), frame.stats.passes.end(),
                                 [&](const PassTime& p) { return p.name == t.name; });
        if (same != frame.stats.passes.end()) same->ms += t.ms;
        else frame.stats.passes.push_back({t.name, t.ms});
    }
}

}  // namespace ssrt::trace_stages
