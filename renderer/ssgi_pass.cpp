#include <vector>

#include "renderer/trace_stages.h"
#include "renderer/world_stage.h"
#include "trace/reconstruct.h"
#include "trace/ssgi.h"

namespace ssrt::trace_stages {

namespace {

// One SSGI sample's stages on a camera (the frame's, or the half frame's) and its G-buffer:
// tile by tile (trace/tile_chain.h), the rays' pdf copied into rays.pdf for the layouts'
// reconstruction; or, for the observer, stage by stage over the batches `rays` and `result`.
struct SsgiSample {
    const TraceContext& c;
    MarchFrame on;
    const SsgiArgs& in;
    const HitStatsArgs& hp;
    DiffuseCut cut;
    RayGenCheckerboard checker;
    PlaneF* out;                 // the resolve's colour planes
    WorldStage world;            // the rays the screen does not answer (TraceSettings::ssgiTrace)
    MixedTileClassifier* tiles;  // on the camera's grid; counts each sample's world stage
};

RayGenStats ssgiSample(const SsgiSample& q, int s, RayBatch& rays, MarchResult& result,
                       TraceStats& st, StageTimes& times) {
    const TraceContext& c = q.c;
    const Isa isa = c.isa;
    const int spp = c.ts().ssgiSpp;
    const TraceCamera& camera = q.on.camera;
    const RayGenerator gen =
        RayGenerator::diffuse(isa, c.frameIndex, uint32_t(s), camera, q.on.g, q.cut, q.checker);
    const RaySeed seed{c.frameIndex, uint32_t(s)};
    const bool answers = q.world.mode != TraceMode::Screen;
    if (!tiled(c)) {
        RayGenStats rs;
        addTime(times.rays, [&] { rs = gen.frame(rays, c.threads()); });
        std::vector<WorldLit> lit;
        const auto answer = [&](MarchResult& m) {
            times.worldRan = true;
            addTime(times.world, [&] {
                std::vector<WorldRayStats> perTile;
                st.world.add(answerInWorldByTile(q.world, q.tiles->grid(), rays, m, perTile, lit));
                q.tiles->add(perTile);
            });
        };
        marchSample(c, q.on, TracePass::Ssgi, s, rays, result, st, times,
                    answers ? std::function<void(MarchResult&)>(answer)
                            : std::function<void(MarchResult&)>(),
                    &q.tiles->skips());
        addTime(times.resolve, [&] {
            resolveSsgi(isa, q.in, rays, result, q.out, s, spp, c.threads(), lit);
            accumulateHitStats(isa, camera, rays, result, q.hp, s, spp, c.threads());
        });
        return rs;
    }
    RayMarcher march(isa, c.ts().marcher, c.ts().march, seed, camera, q.on.g, q.on.backZ, q.on.hiz,
                     c.threads());
    if (skipsMarch(c, TracePass::Ssgi)) march.skipMarch();
    march.skipTiles(q.tiles->skips());
    const SsgiResolver resolve(isa, q.in, q.out, s, spp, &rays.pdf);
    rays.corner = {};
    const HitStatsAccumulator hitStats(isa, camera, q.hp, s, spp);
    // The world-lit hits of the tile the answer stage just ran on (the same thread runs a
    // tile's stages one after another).
    thread_local std::vector<WorldLit> lit;
    const auto resolveTile = [&](int t, const RayBatch& b, const MarchResult& m) {
        resolve.tile(t, b, m, lit);
        lit.clear();
    };
    const TileGrid& grid = q.tiles->grid();
    std::vector<WorldRayStats> answered(std::size_t(grid.count()));
    const auto answer = [&](int t, const RayBatch& b, MarchResult& m) {
        lit.clear();
        answered[std::size_t(t)] = answerInWorld(q.world, b, m, grid.rect(t), lit);
    };
    const RayGenStats rs =
        traceTiles(c, gen, march, resolveTile, hitStats, st, times, {},
                   answers ? std::function<void(int, const RayBatch&, MarchResult&)>(answer)
                           : std::function<void(int, const RayBatch&, MarchResult&)>());
    for (const WorldRayStats& a : answered) st.world.add(a);
    q.tiles->add(answered);
    return rs;
}

// SSGI at half resolution (TraceLayout::Half): the chosen pixel of each 2x2 block makes a
// half-resolution frame with its own depth pyramid; rays, march, resolve and hit statistics
// run on it, and the upsample brings them to the frame's planes. The observer sees the half
// frame's batches with the half frame (TraceObserver).
void ssgiHalf(const TraceContext& c, Frame& frame, const PassReads& r, const SsgiArgs& full,
              DiffuseCut cut, TraceStats& st, StageTimes& times) {
    const TraceSettings& ts = c.ts();
    const Isa isa = c.isa;
    Frame::Scratch::HalfTrace& ht = frame.scratch.half;
    HalfFrame& hf = ht.frame;
    addTime(times.rays, "ssgi half frame build", [&] {
        // (Motion for the denoiser, which runs on the half frame: denoisePass.)
        HalfFrameSource src{full.g, ts.denoise.enabled};
        // (Absent where the direct pass wrote the half frame's hit light itself:
        // hitLightAtHalf.)
        for (int ch = 0; ch < 3; ++ch) src.hitLight[ch] = r.value(Res::HitLight, ch).f16;
        if (c.backZ) src.backZ = viewOf(*c.backZ, "backZ");
        // (Mixed tracing's proof, on the half frame's pixels: world_stage.h.)
        if (ts.ssgiTrace == TraceMode::Mixed) src.ids = r.ids(Res::VisibilityIds);
        buildHalfFrame(c.camera, src, c.frameIndex, hf, c.threads());
        if (ts.marcher == Marcher::HiZ) buildHiZ(hf.viewZ, ht.hiz, c.threads());
        if (ts.ssgiTrace == TraceMode::Mixed)
            findThinFeatures(viewIn(hf, hf.viewZ), ht.thin, c.threads());
    });
    const GBufferView hg = hf.view();
    SsgiArgs in = full;
    in.camera = hf.camera;
    in.g = hg;
    for (int ch = 0; ch < 3; ++ch) in.hitLight[ch] = viewIn(hf, hf.hitLight[ch]);
    if (tracedSignalsPooled(c.settings))  // (back to the pool in denoiseHalfDiffuse)
        takeSignal(frame.scratch.pool, ht.resolved, hf.camera.width, hf.camera.height);
    const HitStatsArgs hp{stageOutput(ht.resolved, &ht.resolved.hit, hf.camera),
                          stageOutput(ht.resolved, c.debugPlane(ht.resolved.steps), hf.camera),
                          stageOutput(ht.resolved, &ht.resolved.hitDistance, hf.camera)};
    const HiZPyramid* hiz = ts.marcher == Marcher::HiZ ? &ht.hiz : nullptr;
    MixedTileClassifier tiles(c, TracePass::Ssgi, hf.camera);
    const SsgiSample q{c,
                       {hf.camera, hg, backZ(hf.backZ), hiz, &hf},
                       in,
                       hp,
                       cut,
                       {},
                       ht.resolved.color,
                       worldStage(c, frame, pass::kSsgiHalf, ts.ssgiTrace, false, &hf),
                       &tiles};
    for (int s = 0; s < ts.ssgiSpp; ++s) {
        RayGenStats rs = ssgiSample(q, s, ht.rays, ht.march, st, times);
        // The frame's surface pixels: the chosen ones traced here, the others cut (hidden
        // and background stay counts of half pixels).
        rs.pixels += hf.cutPixels;
        rs.cut += hf.cutPixels;
        st.rays.add(rs);
    }
    tiles.keep();
    // The full-resolution planes: what the composite reads without the denoiser, and only to
    // be looked at with it (which denoises the half frame's: denoiseHalfDiffuse).
    const std::span<PlaneF, 3> color = frame.rgb(Res::Ssgi);
    if (color[0].empty()) return;
    times.reconstruct = 0.0;
    addTime(times.reconstruct, "ssgi reconstruct", [&] {
        const ReconstructSource from{
            {&ht.resolved.color[0], &ht.resolved.color[1], &ht.resolved.color[2]},
            nullptr,
            &ht.resolved.hit,
            &ht.resolved.hitDistance,
            c.debugPlane(ht.resolved.steps)};
        const ReconstructPlanes to{{&color[0], &color[1], &color[2]},
                                   nullptr,
                                   &frame.plane(Res::SsgiHit),
                                   &frame.plane(Res::SsgiHitDistance),
                                   c.debugPlane(frame.plane(Res::SsgiSteps))};
        upsampleHalf(isa, c.guides(frame, pass::kSsgiUpsample), hf.offset, ht.rays.pdf, from, to,
                     c.threads());
    });
}

}  // namespace

void ssgiPass(const TraceContext& c, Frame& frame) {
    const ProfileScope slice("ssgi");  // (its stages' slices are named after it)
    const TraceSettings& ts = c.ts();
    const Isa isa = c.isa;
    Frame::Scratch& sc = frame.scratch;
    const std::span<PlaneF, 3> color = frame.rgb(Res::Ssgi);
    const bool half = ts.ssgiLayout == TraceLayout::Half;
    // (At half resolution, what the half frame is made of.)
    const PassReads r(c.graph, frame, half ? pass::kSsgiHalfFrame : pass::kSsgi);
    SsgiArgs in;
    in.camera = c.camera;
    in.g = r.gbuffer();
    // The direct pass's hit light: the light at a hit, so the resolve reads no shadow or
    // emission and no material of the hit pixel.
    for (int ch = 0; ch < 3; ++ch) in.hitLight[ch] = r.value(Res::HitLight, ch);
    in.lighting = &c.lighting;
    TraceStats& st = frame.stats.ssgi;
    st.ran = true;
    st.spp = ts.ssgiSpp;
    StageTimes times;
    const DiffuseCut cut = ts.traceHidden ? DiffuseCut::None : DiffuseCut::NoDiffuseColour;
    if (half) {
        ssgiHalf(c, frame, r, in, cut, st, times);
        times.report(frame.stats, "ssgi");
        return;
    }
    const RayGenCheckerboard checker{ts.ssgiLayout == TraceLayout::Checkerboard,
                                     kSsgiCheckerboardPhase};
    const HitStatsArgs hp{stageOutput(frame, Res::SsgiHit, c.camera),
                          stageOutput(frame, Res::SsgiSteps, c.camera, c.settings.debugPlanes),
                          stageOutput(frame, Res::SsgiHitDistance, c.camera)};
    takeBatches(c, frame);
    MixedTileClassifier tiles(c, TracePass::Ssgi, c.camera);
    const SsgiSample q{c,
                       {c.camera, in.g, c.backZ, c.hiz, nullptr},
                       in,
                       hp,
                       cut,
                       checker,
                       color.data(),
                       worldStage(c, frame, pass::kSsgi, ts.ssgiTrace, false),
                       &tiles};
    for (int s = 0; s < ts.ssgiSpp; ++s)
        st.rays.add(ssgiSample(q, s, sc.rays, sc.march, st, times));
    tiles.keep();
    if (checker.on) {
        times.reconstruct = 0.0;
        addTime(times.reconstruct, "ssgi reconstruct", [&] {
            const ReconstructPlanes rp{{&color[0], &color[1], &color[2]},
                                       nullptr,
                                       &frame.plane(Res::SsgiHit),
                                       &frame.plane(Res::SsgiHitDistance)};
            fillCheckerboard(isa, c.guides(frame, pass::kSsgiReconstruct), sc.rays.pdf, rp,
                             c.threads());
        });
    }
    sc.pool.give(sc.rays);
    sc.pool.give(sc.march);
    times.report(frame.stats, "ssgi");
}

}  // namespace ssrt::trace_stages
