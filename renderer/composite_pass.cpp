#include <chrono>
#include <vector>

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
void upsampleAndComposite(const TraceContext& c, Frame& frame, const CompositeInputs& ci) {
    using Clock = std::chrono::steady_clock;
    const DenoiseOutputs& half = frame.scratch.half.denoised.out;
    const ReconstructSource from{{&half.diffuse[0], &half.diffuse[1], &half.diffuse[2]}};
    const HalfUpsampler up(c.args.isa, c.guides(frame), PixelOffset{0, 0},
                           frame.scratch.half.rays.pdf, from);
    const Compositor comp(c.args.isa, ci, frame.image.color, frame.image.display, true);
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
        const PlaneF* const ssgi[3] = {&light[0], &light[1], &light[2]};
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
    frame.stats.passes.push_back({"composite", compMs * k});
}

}  // namespace

void compositePass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts;
    const bool inComposite = diffuseUpsampledInComposite(c.args.settings);
    const DirectParts& parts = frame.direct;
    CompositeInputs ci;
    for (int ch = 0; ch < 3; ++ch) {
        ci.direct[ch] = &parts.direct[ch];
        ci.emission[ch] = c.args.direct.anyEmissive ? &parts.emission[ch] : nullptr;
        if (!ts.ssgi) ci.envDiffuse[ch] = &parts.envDiffuse[ch];
        ci.envSpecular[ch] = &parts.envSpecular[ch];
        ci.specWeight[ch] = &parts.specWeight[ch];
        const DenoiseOutputs& d = frame.trace.denoise.out;
        if (ts.ssgi) {
            if (!inComposite)
                ci.ssgi[ch] = ts.denoise.enabled ? &d.diffuse[ch] : &frame.trace.ssgi.color[ch];
        }
        if (ts.ssr) {  // the denoiser's output, or SSR's own
            if (ts.denoise.enabled) ci.specular[ch] = &d.specular[ch];
            else ci.ssrColor[ch] = &frame.trace.ssr.color[ch];
        }
    }
    if (ts.ssgi) {
        ci.g = frame.gbuffer.view();
        if (!frame.material.occlusion.empty()) ci.occlusion = &frame.material.occlusion;
    }
    if (ts.ssr && !ts.denoise.enabled) ci.ssrOpacity = &frame.trace.ssr.opacity;
    ci.exposure = c.args.settings.exposure;
    // The composite reads the direct pass's colour through the parts only, so it may write
    // over the image's planes.
    if (inComposite) return upsampleAndComposite(c, frame, ci);
    const ScopedPass timer(frame.stats, "composite");
    composite(c.args.isa, ci, frame.image.color, frame.image.display, c.threads());
}

}  // namespace ssrt::trace_stages
