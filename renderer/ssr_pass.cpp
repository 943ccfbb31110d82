#include <limits>
#include <utility>

#include "renderer/trace_stages.h"
#include "renderer/world_stage.h"
#include "trace/reconstruct.h"

namespace ssrt::trace_stages {

namespace {

// The SSR resolve's inputs: this frame's direct light, or the last frame's composite (when the
// history has one) through the motion vectors; the colour pyramid for the mip mode.
SsrResolveArgs ssrInputs(const TraceContext& c, Frame& frame, SsrResolveSettings& rs,
                         double& pyramidMs) {
    const PassReads r(c.graph, frame, pass::kSsr, c.history);
    const bool reproject = r.has(Res::HistoryColor);
    if (!reproject) rs.radiance = HitRadiance::Current;
    SsrResolveArgs in;
    in.camera = c.camera;
    in.g = r.gbuffer();
    const PlaneF* source[3];
    for (int ch = 0; ch < 3; ++ch) {
        in.color[ch] = r.view(Res::Color, ch);
        in.prevColor[ch] = r.view(Res::HistoryColor, ch);
        source[ch] = reproject ? &c.history->color[ch] : &frame.rgb(Res::Color)[ch];
    }
    in.radianceScale = 1.0f / c.settings.exposure;
    if (rs.mode == SsrResolveMode::Mip) {
        addTime(pyramidMs, "ssr colour pyramid",
                [&] { buildColorPyramid(source, frame.scratch.colorPyramid, c.threads()); });
        in.pyramid = &frame.scratch.colorPyramid;
    }
    return in;
}

// The frame's SSR colour and opacity planes, lent to the resolve's output while it runs.
void swapSsrOutput(Frame& frame, SsrOutput& out) {
    for (int ch = 0; ch < 3; ++ch) std::swap(out.color[ch], frame.plane(Res::Ssr, ch));
    std::swap(out.opacity, frame.plane(Res::SsrOpacity));
}

// What one sample of SSR needs besides its rays and march results.
struct SsrSample {
    const TraceContext& c;
    const SsrResolveSettings& rs;
    const SsrResolveArgs& in;
    const HitStatsArgs& hp;
    float maxRoughness;
    RayGenCheckerboard checker;
    WorldStage world;  // the rays the screen does not answer (TraceSettings::ssrTrace)

    RayGenerator rays(int s) const {
        return RayGenerator::specular(c.isa, c.ts().ssrMethod, c.frameIndex, uint32_t(s), c.camera,
                                      in.g, maxRoughness, checker);
    }
};

// SSR's checkerboard, thinned where the denoiser's last specular history is long
// (TraceSettings::ssrSparseFrames): only where the denoiser reads that history this frame (not
// after a cut or a change of size, nor from a frame without SSR).
RayGenCheckerboard ssrCheckerboard(const TraceContext& c) {
    const TraceSettings& ts = c.ts();
    RayGenCheckerboard cb{ts.ssrLayout == TraceLayout::Checkerboard, kSsrCheckerboardPhase};
    if (!cb.on || ts.ssrSparseFrames >= TraceSettings::kSparseOff || !ts.denoise.enabled ||
        !c.sequence || c.resetHistory)
        return cb;
    const DenoiseHistory& h = c.sequence->denoise;
    if (!h.usableAt(c.camera.width, c.camera.height) || !h.hasSignal(true)) return cb;
    cb.historyFrames = viewOf(h.specularFrames, "history.denoise.specularFrames");
    cb.sparseMin = float(ts.ssrSparseFrames);
    return cb;
}

// Stage by stage over the frame, for the observer, which reads the frame's batches.
void ssrFrameSamples(const SsrSample& q, Frame& frame, TraceStats& st, StageTimes& times) {
    const TraceContext& c = q.c;
    Frame::Scratch& sc = frame.scratch;
    MixedTileClassifier tiles(c, TracePass::Ssr, c.camera);
    for (int s = 0; s < c.ts().ssrSpp; ++s) {
        addTime(times.rays, [&] { st.rays.add(q.rays(s).frame(sc.rays, c.threads())); });
        std::vector<WorldLit> lit;
        const auto answer = [&](MarchResult& m) {
            times.worldRan = true;
            addTime(times.world, [&] {
                std::vector<WorldRayStats> perTile;
                st.world.add(answerInWorldByTile(q.world, tiles.grid(), sc.rays, m, perTile, lit));
                tiles.add(perTile);
            });
        };
        marchSample(c, {c.camera, q.in.g, c.backZ, c.hiz, nullptr}, TracePass::Ssr, s, sc.rays,
                    sc.march, st, times,
                    c.ts().ssrTrace == TraceMode::Screen
                        ? std::function<void(MarchResult&)>()
                        : std::function<void(MarchResult&)>(answer),
                    &tiles.skips());
        addTime(times.resolve, [&] {
            if (c.ts().ssrTrace == TraceMode::Screen) {
                resolveSsr(c.isa, q.rs, q.in, sc.rays, sc.march, sc.ssr, s, c.ts().ssrSpp,
                           c.threads());
            } else {
                // Pass 1, the world-lit hits over it, pass 2.
                const SsrResolver resolve(c.isa, q.rs, q.in, sc.ssr, s, c.ts().ssrSpp, sc.rays,
                                          sc.march);
                parallelForTiles(resolve.grid().count(), c.threads(),
                                 [&](int t) { resolve.hitTile(t, sc.rays, sc.march); });
                for (const WorldLit& w : lit) resolve.setHit(w.x, w.y, w.radiance, 1.0f, w.point);
                resolve.resolveFrame(c.threads());
            }
            accumulateHitStats(c.isa, c.camera, sc.rays, sc.march, q.hp, s, c.ts().ssrSpp,
                               c.threads());
        });
    }
    tiles.keep();
}

// Tile by tile: the resolve's first pass and the hit statistics take each tile's batches.
void ssrTileSamples(const SsrSample& q, Frame& frame, TraceStats& st, StageTimes& times) {
    const TraceContext& c = q.c;
    const Isa isa = c.isa;
    Frame::Scratch& sc = frame.scratch;
    MixedTileClassifier tiles(c, TracePass::Ssr, c.camera);
    const TileGrid& grid = tiles.grid();
    for (int s = 0; s < c.ts().ssrSpp; ++s) {
        const RayGenerator rays = q.rays(s);
        RayMarcher march(isa, c.ts().marcher, c.ts().march, {c.frameIndex, uint32_t(s)}, c.camera,
                         q.in.g, c.backZ, c.hiz, c.threads());
        if (skipsMarch(c, TracePass::Ssr)) march.skipMarch();
        march.skipTiles(tiles.skips());
        // (The resolve's scratch a ring of tile rows: its second pass runs in the chain.)
        const SsrResolver resolve(isa, q.rs, q.in, sc.ssr, s, c.ts().ssrSpp, sc.rays, sc.march,
                                  kChainRingTileRows * kTileSize);
        const HitStatsAccumulator hitStats(isa, c.camera, q.hp, s, c.ts().ssrSpp);
        // The world-lit hits of the tile the answer stage just ran on (the same thread runs a
        // tile's stages one after another).
        thread_local std::vector<WorldLit> lit;
        const auto hitTile = [&](int t, const RayBatch& b, const MarchResult& m) {
            resolve.hitTile(t, b, m);
            for (const WorldLit& w : lit) resolve.setHit(w.x, w.y, w.radiance, 1.0f, w.point);
            lit.clear();
        };
        std::vector<WorldRayStats> answered(std::size_t(grid.count()));
        const auto answer = [&](int t, const RayBatch& b, MarchResult& m) {
            lit.clear();
            answered[std::size_t(t)] = answerInWorld(q.world, b, m, grid.rect(t), lit);
        };
        st.rays.add(traceTiles(
            c, rays, march, hitTile, hitStats, st, times, [&](int t) { resolve.resolveTile(t); },
            c.ts().ssrTrace == TraceMode::Screen
                ? std::function<void(int, const RayBatch&, MarchResult&)>()
                : answer));
        for (const WorldRayStats& a : answered) st.world.add(a);
        tiles.add(answered);
    }
    tiles.keep();
}

}  // namespace

void ssrPass(const TraceContext& c, Frame& frame) {
    const ProfileScope slice("ssr");  // (its stages' slices are named after it)
    const TraceSettings& ts = c.ts();
    Frame::Scratch& sc = frame.scratch;
    StageTimes times;
    SsrResolveSettings rs = ts.resolve;
    // Mixed and world tracing's hits are certain, near the border too (trace/ssr_resolve.h).
    if (ts.ssrTrace != TraceMode::Screen) rs.edgeFadeLength = 0.0f;
    const SsrResolveArgs in = ssrInputs(c, frame, rs, times.resolve);
    // Per-pixel hit fraction, mean steps and mean hit distance (trace/hit_stats.h).
    const HitStatsArgs hp{stageOutput(frame, Res::SsrHit, c.camera),
                          stageOutput(frame, Res::SsrSteps, c.camera, c.settings.debugPlanes),
                          stageOutput(frame, Res::SsrHitDistance, c.camera)};
    TraceStats& st = frame.stats.ssr;
    st.ran = true;
    st.spp = ts.ssrSpp;
    const float maxRoughness =
        ts.traceHidden ? std::numeric_limits<float>::infinity() : rs.roughnessFadeEnd;
    const SsrSample q{c,
                      rs,
                      in,
                      hp,
                      maxRoughness,
                      ssrCheckerboard(c),
                      worldStage(c, frame, pass::kSsr, ts.ssrTrace, true)};
    // The batches and the resolve's scratch (which the resolver sizes: the frame's, or a tile
    // chain's ring) go back to the pool once the checkerboard fill has read the rays' pdf (the
    // denoiser takes their memory next). The signal's planes are the frame memory's
    // (renderer/frame_memory.h).
    takeBatches(c, frame);
    swapSsrOutput(frame, sc.ssr);
    if (tiled(c)) ssrTileSamples(q, frame, st, times);
    else ssrFrameSamples(q, frame, st, times);
    swapSsrOutput(frame, sc.ssr);
    sc.pool.give(sc.ssr);
    // The checkerboard's other phase, from this frame's traced pixels (marked in the rays).
    if (q.checker.on) {
        times.reconstruct = 0.0;
        addTime(times.reconstruct, "ssr reconstruct", [&] {
            const std::span<PlaneF, 3> color = frame.rgb(Res::Ssr);
            const ReconstructPlanes rp{{&color[0], &color[1], &color[2]},
                                       &frame.plane(Res::SsrOpacity),
                                       &frame.plane(Res::SsrHit),
                                       &frame.plane(Res::SsrHitDistance)};
            fillCheckerboard(c.isa, c.guides(frame, pass::kSsrReconstruct), sc.rays.pdf, rp,
                             c.threads());
        });
    }
    sc.pool.give(sc.rays);
    sc.pool.give(sc.march);
    times.report(frame.stats, "ssr");
}

}  // namespace ssrt::trace_stages
