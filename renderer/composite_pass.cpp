#include <chrono>
#include <span>
#include <utility>
#include <vector>

#include "core/plane_view.h"
#include "renderer/resources.h"
#include "renderer/trace_stages.h"
#include "shading/composite.h"
#include "trace/reconstruct.h"

namespace ssrt::trace_stages {

namespace {

// Direct + diffuse (SSGI or the sky's irradiance) + specular (SSR over the environment), tone
// mapped; replaces the direct pass's colour and display.
// The composite tile by tile, each tile's SSGI light first brought from the denoised half
// frame into a tile's planes (diffuseUpsampledInComposite): the two stages' times are the
// loop's, shared by the threads' time in each.
void upsampleAndComposite(const TraceContext& c, Frame& frame, const CompositeArgs& ca) {
    using Clock = std::chrono::steady_clock;
    const std::span<const PlaneF, 3> half =
        std::as_const(frame.scratch.half.denoised).rgb(Res::HalfDenoised);
    const ReconstructSource from{{&half[0], &half[1], &half[2]}};
    const HalfUpsampler up(c.isa, c.guides(frame), PixelOffset{0, 0}, frame.scratch.half.rays.pdf,
                           from);
    const Compositor comp(c.isa, ca, true);
    const TileGrid& grid = comp.grid();
    std::vector<double> busy(std::size_t(2 * grid.count()), 0.0);
    const Clock::time_point t0 = Clock::now();
    parallelForTiles(grid.count(), c.threads(), [&](int tile) {
        thread_local PlaneF light[3];
        for (PlaneF& p : light)
            if (p.empty()) p = PlaneF(kTileSize, kTileSize);
        const TileRect r = grid.rect(tile);
        const Clock::time_point a = Clock::now();
        up.tile(tile, ReconstructPlanes{{&light[0], &light[1], &light[2]}}, r.x0, r.y0);
        const Clock::time_point b = Clock::now();
        const ViewF ssgi[3] = {viewOf(light[0], channelName(Res::DenoisedDiffuse, 0)),
                               viewOf(light[1], channelName(Res::DenoisedDiffuse, 1)),
                               viewOf(light[2], channelName(Res::DenoisedDiffuse, 2))};
        comp.tile(tile, ssgi, r.x0, r.y0);
        busy[std::size_t(2 * tile)] = std::chrono::duration<double, std::milli>(b - a).count();
        busy[std::size_t(2 * tile + 1)] =
            std::chrono::duration<double, std::milli>(Clock::now() - b).count();
    });
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    double upMs = 0.0, compMs = 0.0;
    for (std::size_t i = 0; i < busy.size(); i += 2) upMs += busy[i], compMs += busy[i + 1];
    const double k = upMs + compMs > 0.0 ? wall / (upMs + compMs) : 0.0;
    frame.stats.passes.push_back({"denoise upsample", upMs * k});
    frame.stats.passes.push_back({"composite", compMs * k, true});
}

}  // namespace

void compositePass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts();
    const bool inComposite = diffuseUpsampledInComposite(c.settings);
    const DirectParts& parts = frame.direct;
    CompositeArgs ca;
    for (int ch = 0; ch < 3; ++ch) {
        ca.direct[ch] = viewOf(parts.direct[ch], channelName(Res::Direct, ch));
        if (c.direct.anyEmissive)
            ca.emission[ch] = viewOf(parts.emission[ch], channelName(Res::Emission, ch));
        if (!ts.ssgi)
            ca.envDiffuse[ch] = viewOf(parts.envDiffuse[ch], channelName(Res::EnvDiffuse, ch));
        ca.envSpecular[ch] = viewOf(parts.envSpecular[ch], channelName(Res::EnvSpecular, ch));
        ca.specWeight[ch] = viewOf(parts.specWeight[ch], channelName(Res::SpecWeight, ch));
        if (ts.ssgi && !inComposite)
            ca.ssgi[ch] = frame.view(ts.denoise.enabled ? Res::DenoisedDiffuse : Res::Ssgi, ch);
        if (ts.ssr) {  // the denoiser's output, or SSR's own
            if (ts.denoise.enabled) ca.specular[ch] = frame.view(Res::DenoisedSpecular, ch);
            else ca.ssrColor[ch] = frame.view(Res::Ssr, ch);
        }
        ca.color[ch] = outputOf(frame.rgb(Res::Color)[ch], channelName(Res::Color, ch));
        ca.display[ch] = outputOf(frame.rgb(Res::Display)[ch], channelName(Res::Display, ch));
    }
    if (ts.ssgi) {
        ca.g = frame.gbuffer.view();
        if (!frame.gbuffer.occlusion.empty())
            ca.occlusion = viewOf(frame.gbuffer.occlusion, channelName(Res::Occlusion));
    }
    if (ts.ssr && !ts.denoise.enabled)
        ca.ssrOpacity = viewOf(frame.plane(Res::SsrOpacity), channelName(Res::SsrOpacity));
    ca.exposure = c.settings.exposure;
    // The composite reads the direct pass's colour through the parts only, so it may write
    // over the image's planes.
    if (inComposite) return upsampleAndComposite(c, frame, ca);
    const ScopedPass timer(frame.stats, "composite");
    composite(c.isa, ca, c.threads());
}

}  // namespace ssrt::trace_stages
