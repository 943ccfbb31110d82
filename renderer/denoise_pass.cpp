#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

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
    upsampleHalf(c.isa, c.guides(frame, pass::kDenoiseUpsample), PixelOffset{0, 0},
                 frame.scratch.half.rays.pdf, source, target, c.threads());
}

// The full-resolution call: SSGI's diffuse where it traced at full resolution, SSR's signal,
// as the front end declares reading them; each signal denoised into the frame's planes.
DenoiseCall fullCall(const TraceContext& c, Frame& frame) {
    const int w = c.camera.width, h = c.camera.height;
    const PassReads r(c.graph, frame, pass::kDenoiseFrontEnd);
    DenoiseCall in = denoiseCall(c, frame, c.camera, false);
    in.g = r.gbuffer();
    if (r.has(Res::Ssgi)) {
        for (int ch = 0; ch < 3; ++ch) {
            in.diffuse[ch] = r.view(Res::Ssgi, ch);
            in.denoisedDiffuse[ch] = frame.outputs.output(Res::DenoisedDiffuse, ch, w, h);
        }
        in.diffuseHitDistance = r.view(Res::SsgiHitDistance);
        in.diffuseFrames = historyLengths(c, frame.outputs, Res::DiffuseFrames, w, h);
    }
    if (r.has(Res::Ssr)) {
        for (int ch = 0; ch < 3; ++ch) {
            in.ssr[ch] = r.view(Res::Ssr, ch);
            in.envSpecular[ch] = r.value(Res::EnvSpecular, ch);
            in.denoisedSpecular[ch] = frame.outputs.output(Res::DenoisedSpecular, ch, w, h);
        }
        in.specularFrames = historyLengths(c, frame.outputs, Res::SpecularFrames, w, h);
        in.ssrOpacity = r.view(Res::SsrOpacity);
        in.specularHitDistance = r.view(Res::SsrHitDistance);
        // Where SSR has faded out the blend is the environment alone: nothing to denoise.
        in.specularMaxRoughness = c.ts().resolve.roughnessFadeEnd;
    }
    // The traced signals no later pass reads go back to the pool before the denoiser's later
    // passes take their results from it.
    in.signalsRead = [&c] { c.memory.giveThrough(pass::kDenoiseFrontEnd); };
    return in;
}

// One of the frame's two denoiser runs (the half frame's diffuse, or the frame's signals),
// made as its first pass starts: its inputs exist only once SSR and SSGI have run.
struct Denoiser {
    DenoiseSettings settings;
    std::optional<DenoiseCall> call;
    std::optional<DenoiseRun> run;
    TileGrid grid;        // its tiles, once made
    std::size_t ran = 0;  // the steps the scheduler has set up
};

}  // namespace

// Each pass of the denoiser the frame graph runs ("denoise " + the step, and " (half)" on the
// half frame) as a tiled pass of `passes`, on the run's tiles, so the scheduler runs in one loop
// the passes the graph chains. The first makes the run. Every pass the graph runs must be a
// step of the run, and every step must run: else std::logic_error (the two disagree on the
// passes, and an output would go unwritten; checked by the returned function, after the run).
std::function<void()> scheduleDenoiser(const TraceContext& c, Frame& frame,
                                       FrameScheduler& passes) {
    const auto runs = std::make_shared<std::array<Denoiser, 2>>();  // half, full
    (*runs)[0].settings = halfResolutionDiffuse(c.ts().denoise);
    (*runs)[1].settings = c.ts().denoise;
    const auto make = [&c, &frame, runs](bool half) {
        Denoiser& d = (*runs)[half ? 0 : 1];
        d.call.emplace(half ? halfDiffuseCall(c, frame) : fullCall(c, frame));
        DenoiseHistory* history = !c.sequence ? nullptr
                                  : half      ? &c.sequence->denoiseHalf
                                              : &c.sequence->denoise;
        DenoiseScratch& scratch = half ? frame.scratch.half.denoise : frame.scratch.denoise;
        d.run.emplace(c.isa, d.settings, *d.call, history, c.resetHistory, scratch, c.threads());
        d.grid = d.run->grid();
    };
    for (const GraphPass& g : c.graph.passes) {
        const std::string_view name = g.decl->name;
        constexpr std::string_view kPrefix = "denoise ", kHalf = " (half)";
        if (name.rfind(kPrefix, 0) != 0 || name == pass::kDenoiseUpsample) continue;
        const bool half = name.size() > kHalf.size() && name.ends_with(kHalf);
        const std::string_view stepName =
            name.substr(kPrefix.size(), name.size() - kPrefix.size() - (half ? kHalf.size() : 0));
        Denoiser* d = &(*runs)[half ? 0 : 1];
        const auto step = std::make_shared<const DenoiseStep*>(nullptr);
        passes.tiled(
            name, [step](int tile) { (*step)->tile(tile); },
            [make, d, half, step, stepName, name] {
                if (!d->run) make(half);
                *step = d->run->step(stepName);
                if (!*step)
                    throw std::logic_error("the frame graph runs '" + std::string(name) +
                                           "', which the denoiser does not");
                ++d->ran;
                if ((*step)->setUp) (*step)->setUp();
            },
            [step] {
                if ((*step)->finish) (*step)->finish();
            },
            &d->grid);
    }
    return [runs] {
        for (const Denoiser& d : *runs)
            if (d.run && d.ran != d.run->steps().size())
                throw std::logic_error("the denoiser runs a pass the frame graph does not");
    };
}

// The half frame's denoised diffuse brought to the frame's planes, where a later pass reads them
// there (not only the composite, which brings it tile by tile).
void scheduleUpsample(const TraceContext& c, Frame& frame, FrameScheduler& passes,
                      FrameStats& stats) {
    passes.whole(pass::kDenoiseUpsample,
                 [&c, &frame, &stats] { upsampleHalfDiffuse(c, frame, stats); });
}

}  // namespace ssrt::trace_stages
