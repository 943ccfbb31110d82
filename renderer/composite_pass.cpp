#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "core/plane_view.h"
#include "core/profile.h"
#include "renderer/frame_scheduler.h"
#include "renderer/pass_reads.h"
#include "renderer/resources.h"
#include "renderer/trace_stages.h"
#include "shading/composite.h"
#include "trace/reconstruct.h"

namespace ssrt::trace_stages {

namespace {

// Direct + diffuse (SSGI or the sky's irradiance) + specular (SSR over the environment), tone
// mapped; replaces the direct pass's colour and display. What it reads, as the graph declares
// it: the diffuse denoised or raw (none here where the half frame's is brought in tile by
// tile), the specular denoised or SSR's over the environment.
CompositeArgs compositeArgs(const TraceContext& c, Frame& frame, const PassReads& r) {
    const Res diffuse = r.has(Res::DenoisedDiffuse) ? Res::DenoisedDiffuse : Res::Ssgi;
    CompositeArgs ca;
    for (int ch = 0; ch < 3; ++ch) {
        ca.direct[ch] = r.value(Res::Direct, ch);
        ca.emission[ch] = r.value(Res::Emission, ch);
        ca.envDiffuse[ch] = r.value(Res::EnvDiffuse, ch);
        ca.envSpecular[ch] = r.value(Res::EnvSpecular, ch);
        ca.specWeight[ch] = r.value(Res::SpecWeight, ch);
        ca.ssgi[ch] = r.view(diffuse, ch);
        ca.specular[ch] = r.view(Res::DenoisedSpecular, ch);
        ca.ssrColor[ch] = r.view(Res::Ssr, ch);
        ca.color[ch] = outputOf(frame.rgb(Res::Color)[ch], channelName(Res::Color, ch));
        ca.display[ch] = outputOf(frame.rgb(Res::Display)[ch], channelName(Res::Display, ch));
    }
    ca.g = r.gbuffer();
    ca.occlusion = r.view(Res::Occlusion);
    ca.ssrOpacity = r.view(Res::SsrOpacity);
    ca.exposure = c.settings.exposure;
    return ca;
}

// The composite's kernel, made as its pass starts, and where the half frame's denoised diffuse
// is brought to the frame inside it, the upsample's kernel and each tile's time in both.
struct CompositeStep {
    std::optional<Compositor> comp;
    std::optional<HalfUpsampler> up;
    std::vector<double> upMs, compMs;  // per tile
    ProfileSink* profile = nullptr;    // the upsample's slices (core/profile.h)
};

// One tile: the upsample's tile of SSGI light into the thread's tile planes first, where it
// runs inside the composite.
void upsampleAndCompositeTile(CompositeStep& s, int tile) {
    if (!s.up) return s.comp->tile(tile);
    using Clock = std::chrono::steady_clock;
    thread_local PlaneF light[3];
    for (PlaneF& p : light)
        if (p.empty()) p = PlaneF(kTileSize, kTileSize);
    const TileRect r = s.comp->grid().rect(tile);
    const Clock::time_point a = Clock::now();
    s.up->tile(tile, ReconstructPlanes{{&light[0], &light[1], &light[2]}}, r.x0, r.y0);
    const Clock::time_point b = Clock::now();
    if (s.profile) s.profile->slice("denoise upsample", std::this_thread::get_id(), a, b);
    const ViewF ssgi[3] = {viewOf(light[0], channelName(Res::DenoisedDiffuse, 0)),
                           viewOf(light[1], channelName(Res::DenoisedDiffuse, 1)),
                           viewOf(light[2], channelName(Res::DenoisedDiffuse, 2))};
    s.comp->tile(tile, ssgi, r.x0, r.y0);
    s.upMs[std::size_t(tile)] = std::chrono::duration<double, std::milli>(b - a).count();
    s.compMs[std::size_t(tile)] =
        std::chrono::duration<double, std::milli>(Clock::now() - b).count();
}

}  // namespace

// The composite as a tiled pass (it reads the direct pass's colour through the parts only, so
// it may write over the image's planes), in one loop with the passes the graph chains before it.
// Where the half frame's denoised diffuse is brought to the frame tile by tile inside it
// (diffuseUpsampledInComposite), the returned function, called once the scheduler has run into
// `stats`, gives that upsample's share of the composite's time a line of its own.
std::function<void(FrameStats&)> scheduleComposite(const TraceContext& c, Frame& frame,
                                                   FrameScheduler& passes) {
    const auto s = std::make_shared<CompositeStep>();
    const bool inComposite = diffuseUpsampledInComposite(c.settings);
    passes.tiled(
        pass::kComposite, [s](int tile) { upsampleAndCompositeTile(*s, tile); },
        [&c, &frame, s, inComposite] {
            const PassReads r(c.graph, frame, pass::kComposite);
            s->comp.emplace(c.isa, compositeArgs(c, frame, r), inComposite);
            if (!inComposite) return;
            const std::span<const PlaneF, 3> half =
                std::as_const(frame.scratch.half.denoised).rgb(Res::HalfDenoised);
            s->up.emplace(c.isa, ReconstructGuides{c.camera, r.gbuffer()}, PixelOffset{0, 0},
                          frame.scratch.half.rays.pdf,
                          ReconstructSource{{&half[0], &half[1], &half[2]}});
            s->upMs.assign(std::size_t(s->comp->grid().count()), 0.0);
            s->profile = profileSink();
            s->compMs = s->upMs;
        });
    return [s](FrameStats& stats) {
        if (!s->up) return;
        const auto line =
            std::find_if(stats.passes.begin(), stats.passes.end(),
                         [](const PassTime& p) { return p.name == pass::kComposite; });
        if (line == stats.passes.end()) return;
        double up = 0.0, all = 0.0;
        for (std::size_t i = 0; i < s->upMs.size(); ++i)
            up += s->upMs[i], all += s->upMs[i] + s->compMs[i];
        const double upMs = all > 0.0 ? line->ms * up / all : 0.0;
        line->ms -= upMs;
        const bool fused = line->fused;
        line->fused = true;  // (in the upsample's loop)
        stats.passes.insert(line, {"denoise upsample", upMs, fused});
    };
}

}  // namespace ssrt::trace_stages
