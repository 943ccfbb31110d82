#include "renderer/trace_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "renderer/pass_timer.h"
#include "shading/composite.h"
#include "trace/hit_stats.h"
#include "trace/reconstruct.h"
#include "trace/ssgi.h"
#include "trace/tile_chain.h"

namespace ssrt {

namespace {

// The back-face depth layer when the frame has one (renderer.cpp, backDepthPass), else null.
const PlaneF* backZ(const PlaneF& p) { return p.empty() ? nullptr : &p; }

// What the passes below share: the frame's G-buffer as each stage reads it, the pyramid.
struct TraceContext {
    const TracePassArgs& args;
    const TraceSettings& ts;
    TraceCamera camera;
    MarchGBuffer march;
    RayGenGBuffer rayGen;
    const HiZPyramid* hiz = nullptr;

    TraceContext(const TracePassArgs& a, const Frame& f) : args(a), ts(a.settings.trace) {
        const GBuffer& g = f.gbuffer;
        camera = f.camera;
        march = {&g.viewZ, {&g.normal[0], &g.normal[1], &g.normal[2]}, backZ(f.scratch.backZ)};
        // (albedo and metallic: the diffuse colour the composite multiplies SSGI by)
        rayGen = {&g.viewZ,
                  {&g.normal[0], &g.normal[1], &g.normal[2]},
                  &g.roughness,
                  {&g.albedo[0], &g.albedo[1], &g.albedo[2]},
                  &g.metallic};
    }
    int threads() const { return args.settings.threads; }
    // A plane only made to be looked at (RenderSettings::debugPlanes): null when not asked for.
    PlaneF* debugPlane(PlaneF& p) const { return args.settings.debugPlanes ? &p : nullptr; }
    // What the reconstruction of a layout's untraced pixels is guided by.
    ReconstructGuides guides(const Frame& f) const {
        const GBuffer& g = f.gbuffer;
        return {camera, &g.viewZ, {&g.normal[0], &g.normal[1], &g.normal[2]}};
    }
};

// Hi-Z pyramid of the depth buffer, shared by both passes.
void hiZPass(TraceContext& c, Frame& frame) {
    if (c.ts.marcher != Marcher::HiZ) return;
    // (Half-resolution SSGI marches on its own pyramid.)
    if (!c.ts.ssr && c.ts.ssgiLayout == TraceLayout::Half) return;
    const ScopedPass timer(frame.stats, "hi-z");
    buildHiZ(frame.gbuffer.viewZ, frame.scratch.hiz, c.threads());
    c.hiz = &frame.scratch.hiz;
}

// Times of one trace pass's stages, summed over its samples.
struct StageTimes {
    double rays = 0.0, march = 0.0, resolve = 0.0;
    double reconstruct = -1.0;  // reported when a layout other than full ran (>= 0)
    void report(FrameStats& stats, const char* pass) const {
        const std::string p(pass);
        stats.passes.push_back({p + " rays", rays});
        stats.passes.push_back({p + " march", march});
        stats.passes.push_back({p + " resolve", resolve});
        if (reconstruct >= 0.0) stats.passes.push_back({p + " reconstruct", reconstruct});
    }
};

// The frame a pass's rays are generated and marched on: the frame's own camera, G-buffer and
// pyramid, or the half frame's (`half`, TraceLayout::Half).
struct MarchFrame {
    const TraceCamera& camera;
    const MarchGBuffer& gbuffer;
    const HiZPyramid* hiz;
    const HalfFrame* half;
};

// One sample's march of the frame's batch `rays` into `result`, shown to the observer.
void marchSample(const TraceContext& c, const MarchFrame& on, TracePass pass, int sample,
                 const RayBatch& rays, MarchResult& result, TraceStats& stats, StageTimes& times) {
    addTime(times.march, [&] {
        stats.march.add(marchRays(c.args.isa, c.ts.marcher, c.ts.march,
                                  {c.args.frameIndex, uint32_t(sample)}, on.camera, on.gbuffer,
                                  on.hiz, rays, result, c.threads()));
    });
    if (c.args.observer && *c.args.observer)
        (*c.args.observer)(pass, sample, rays, result, on.half);
}

// The SSR resolve's inputs: this frame's direct light, or the last frame's composite (when the
// history has one) through the motion vectors; the colour pyramid for the mip mode.
SsrResolveInputs ssrInputs(const TraceContext& c, Frame& frame, SsrResolveSettings& rs,
                           double& pyramidMs) {
    const GBuffer& g = frame.gbuffer;
    const bool reproject = rs.radiance == HitRadiance::Reprojected && c.args.history;
    if (!reproject) rs.radiance = HitRadiance::Current;
    SsrResolveInputs in;
    in.camera = c.camera;
    in.viewZ = &g.viewZ;
    for (int ch = 0; ch < 3; ++ch) {
        in.normal[ch] = &g.normal[ch];
        in.color[ch] = &frame.image.color[ch];
        in.prevColor[ch] = reproject ? &c.args.history->color[ch] : nullptr;
    }
    in.motion[0] = &g.motion[0];
    in.motion[1] = &g.motion[1];
    in.roughness = &g.roughness;
    in.radianceScale = 1.0f / c.args.settings.exposure;
    if (rs.mode == SsrResolveMode::Mip) {
        addTime(pyramidMs, [&] {
            buildColorPyramid(reproject ? in.prevColor : in.color, frame.scratch.colorPyramid,
                              c.threads());
        });
        in.pyramid = &frame.scratch.colorPyramid;
    }
    return in;
}

// The frame's SSR colour and opacity planes, lent to the resolve's output while it runs.
void swapSsrOutput(SsrPlanes& planes, SsrOutput& out) {
    for (int ch = 0; ch < 3; ++ch) std::swap(out.color[ch], planes.color[ch]);
    std::swap(out.opacity, planes.opacity);
}

// What one sample of SSR needs besides its rays and march results.
struct SsrSample {
    const TraceContext& c;
    const SsrResolveSettings& rs;
    const SsrResolveInputs& in;
    const HitStatsPlanes& hp;
    float maxRoughness;
    RayGenCheckerboard checker;

    RayGenerator rays(int s) const {
        return RayGenerator::specular(c.args.isa, c.ts.ssrMethod, c.args.frameIndex, uint32_t(s),
                                      c.camera, c.rayGen, maxRoughness, checker);
    }
};

// A traced signal's planes from the pool (tracedSignalsPooled; the denoiser gives them back
// once its front end has read them), its march steps aside: only looked at, not made then.
template <class Group>
void takeSignal(PlanePool& pool, Group& g, int w, int h) {
    g.forEachPlane([&](std::string_view, PlaneF& p) {
        if (&p != &g.steps) pool.take(p, w, h);
    });
}

// Whether the trace runs tile by tile (trace/tile_chain.h): unless the observer (the truth's
// ray check) asks for the frame's rays and march results.
bool tiled(const TraceContext& c) { return !(c.args.observer && *c.args.observer); }

// The frame's batches where the passes read them: every plane for the observer's stage-by-stage
// path; for the tile chain only the pdf (and the hits: `hits`) that what runs after the chain
// reads around each pixel.
void takeBatches(const TraceContext& c, Frame& frame, bool hits) {
    Frame::Scratch& sc = frame.scratch;
    const int w = frame.width, h = frame.height;
    if (!tiled(c)) {
        sc.pool.take(sc.rays, w, h);
        sc.pool.take(sc.march, w, h);
        return;
    }
    sc.pool.take(sc.rays.pdf, w, h);
    if (hits) sc.pool.take(sc.march.hit, w, h);
}

// One sample's tile chain (trace/tile_chain.h): on each tile's batches the resolve's
// per-pixel pass, then the hit statistics. Adds the march's counters and the stages' times;
// returns the rays' counters.
template <class Resolve>
RayGenStats traceTiles(const TraceContext& c, const RayGenerator& rays, const RayMarcher& march,
                       const Resolve& resolveTile, const HitStatsAccumulator& hitStats,
                       TraceStats& st, StageTimes& times) {
    const TileChainStats r = runTileChain({rays, march,
                                           [&](int t, const RayBatch& b, const MarchResult& m) {
                                               resolveTile(t, b, m);
                                               hitStats.tile(t, b, m);
                                           }},
                                          c.threads());
    st.march.add(r.march);
    times.rays += r.raysMs;
    times.march += r.marchMs;
    times.resolve += r.consumeMs;
    return r.rays;
}

// Stage by stage over the frame, for the observer, which reads the frame's batches.
void ssrFrameSamples(const SsrSample& q, Frame& frame, TraceStats& st, StageTimes& times) {
    const TraceContext& c = q.c;
    Frame::Scratch& sc = frame.scratch;
    for (int s = 0; s < c.ts.ssrSpp; ++s) {
        addTime(times.rays, [&] { st.rays.add(q.rays(s).frame(sc.rays, c.threads())); });
        marchSample(c, {c.camera, c.march, c.hiz, nullptr}, TracePass::Ssr, s, sc.rays, sc.march,
                    st, times);
        addTime(times.resolve, [&] {
            resolveSsr(c.args.isa, q.rs, q.in, sc.rays, sc.march, sc.ssr, s, c.ts.ssrSpp,
                       c.threads());
            accumulateHitStats(c.args.isa, c.camera, sc.rays, sc.march, q.hp, s, c.ts.ssrSpp,
                               c.threads());
        });
    }
}

// Tile by tile: the resolve's first pass and the hit statistics take each tile's batches.
void ssrTileSamples(const SsrSample& q, Frame& frame, TraceStats& st, StageTimes& times) {
    const TraceContext& c = q.c;
    const Isa isa = c.args.isa;
    Frame::Scratch& sc = frame.scratch;
    for (int s = 0; s < c.ts.ssrSpp; ++s) {
        const RayGenerator rays = q.rays(s);
        const RayMarcher march(isa, c.ts.marcher, c.ts.march, {c.args.frameIndex, uint32_t(s)},
                               c.camera, c.march, c.hiz, c.threads());
        const SsrResolver resolve(isa, q.rs, q.in, sc.ssr, s, c.ts.ssrSpp, sc.rays, sc.march);
        const HitStatsAccumulator hitStats(isa, c.camera, q.hp, s, c.ts.ssrSpp);
        const auto resolveTile = [&](int t, const RayBatch& b, const MarchResult& m) {
            resolve.hitTile(t, b, m);
        };
        st.rays.add(traceTiles(c, rays, march, resolveTile, hitStats, st, times));
        addTime(times.resolve, [&] { resolve.resolveFrame(c.threads()); });
    }
}

void ssrPass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts;
    Frame::Scratch& sc = frame.scratch;
    SsrPlanes& planes = frame.trace.ssr;
    StageTimes times;
    SsrResolveSettings rs = ts.resolve;
    const SsrResolveInputs in = ssrInputs(c, frame, rs, times.resolve);
    // Per-pixel hit fraction, mean steps and mean hit distance (trace/hit_stats.h).
    const HitStatsPlanes hp{&planes.hit, c.debugPlane(planes.steps), &planes.hitDistance};
    TraceStats& st = frame.stats.ssr;
    st.ran = true;
    st.spp = ts.ssrSpp;
    const float maxRoughness =
        ts.traceHidden ? std::numeric_limits<float>::infinity() : rs.roughnessFadeEnd;
    const SsrSample q{
        c,  rs,           in,
        hp, maxRoughness, {ts.ssrLayout == TraceLayout::Checkerboard, kSsrCheckerboardPhase}};
    // The batches and the resolve's scratch come from the pool and go back to it once the
    // checkerboard fill has read the rays' pdf (the denoiser takes them next).
    takeBatches(c, frame, rs.mode == SsrResolveMode::Reuse);
    if (tracedSignalsPooled(c.args.settings))  // (back to the pool in denoisePass)
        takeSignal(sc.pool, planes, frame.width, frame.height);
    swapSsrOutput(planes, sc.ssr);
    sc.pool.take(sc.ssr, frame.width, frame.height);
    if (tiled(c)) ssrTileSamples(q, frame, st, times);
    else ssrFrameSamples(q, frame, st, times);
    swapSsrOutput(planes, sc.ssr);
    sc.pool.give(sc.ssr);
    // The checkerboard's other phase, from this frame's traced pixels (marked in the rays).
    if (q.checker.on) {
        times.reconstruct = 0.0;
        addTime(times.reconstruct, [&] {
            const ReconstructPlanes rp{{&planes.color[0], &planes.color[1], &planes.color[2]},
                                       &planes.opacity,
                                       &planes.hit,
                                       &planes.hitDistance};
            fillCheckerboard(c.args.isa, c.guides(frame), sc.rays.pdf, rp, c.threads());
        });
    }
    sc.pool.give(sc.rays);
    sc.pool.give(sc.march);
    times.report(frame.stats, "ssr");
}

// One SSGI sample's stages on a camera (the frame's, or the half frame's) and its G-buffer:
// tile by tile (trace/tile_chain.h), the rays' pdf copied into rays.pdf for the layouts'
// reconstruction; or, for the observer, stage by stage over the batches `rays` and `result`.
struct SsgiSample {
    const TraceContext& c;
    MarchFrame on;
    const RayGenGBuffer& rayGen;
    const SsgiInputs& in;
    const HitStatsPlanes& hp;
    DiffuseCut cut;
    RayGenCheckerboard checker;
    PlaneF* out;  // the resolve's colour planes
};

RayGenStats ssgiSample(const SsgiSample& q, int s, RayBatch& rays, MarchResult& result,
                       TraceStats& st, StageTimes& times) {
    const TraceContext& c = q.c;
    const Isa isa = c.args.isa;
    const int spp = c.ts.ssgiSpp;
    const TraceCamera& camera = q.on.camera;
    const RayGenerator gen = RayGenerator::diffuse(isa, c.args.frameIndex, uint32_t(s), camera,
                                                   q.rayGen, q.cut, q.checker);
    const RaySeed seed{c.args.frameIndex, uint32_t(s)};
    if (!tiled(c)) {
        RayGenStats rs;
        addTime(times.rays, [&] { rs = gen.frame(rays, c.threads()); });
        marchSample(c, q.on, TracePass::Ssgi, s, rays, result, st, times);
        addTime(times.resolve, [&] {
            resolveSsgi(isa, q.in, rays, result, q.out, s, spp, c.threads());
            accumulateHitStats(isa, camera, rays, result, q.hp, s, spp, c.threads());
        });
        return rs;
    }
    const RayMarcher march(isa, c.ts.marcher, c.ts.march, seed, camera, q.on.gbuffer, q.on.hiz,
                           c.threads());
    const SsgiResolver resolve(isa, q.in, q.out, s, spp, &rays.pdf);
    rays.corner = {};
    const HitStatsAccumulator hitStats(isa, camera, q.hp, s, spp);
    const auto resolveTile = [&](int t, const RayBatch& b, const MarchResult& m) {
        resolve.tile(t, b, m);
    };
    return traceTiles(c, gen, march, resolveTile, hitStats, st, times);
}

// SSGI at half resolution (TraceLayout::Half): the chosen pixel of each 2x2 block makes a
// half-resolution frame with its own depth pyramid; rays, march, resolve and hit statistics
// run on it, and the upsample brings them to the frame's planes. The observer sees the half
// frame's batches with the half frame (TraceObserver).
void ssgiHalf(const TraceContext& c, Frame& frame, const SsgiInputs& full, DiffuseCut cut,
              TraceStats& st, StageTimes& times) {
    const TraceSettings& ts = c.ts;
    const Isa isa = c.args.isa;
    const GBuffer& g = frame.gbuffer;
    Frame::Scratch::HalfTrace& ht = frame.scratch.half;
    HalfFrame& hf = ht.frame;
    addTime(times.rays, [&] {
        HalfFrameSource src{
            &g.viewZ,
            {&g.normal[0], &g.normal[1], &g.normal[2]},
            {&g.albedo[0], &g.albedo[1], &g.albedo[2]},
            &g.metallic,
            {&frame.direct.hitLight[0], &frame.direct.hitLight[1], &frame.direct.hitLight[2]},
            {},
            backZ(frame.scratch.backZ)};
        // (Or the direct pass wrote the half frame's hit light itself: hitLightAtHalf.)
        if (hitLightAtHalf(c.args.settings))
            for (const PlaneF*& p : src.hitLight) p = nullptr;
        // (Motion for the denoiser, which runs on the half frame: denoisePass.)
        if (ts.denoise.enabled) src.motion[0] = &g.motion[0], src.motion[1] = &g.motion[1];
        buildHalfFrame(c.camera, src, c.args.frameIndex, hf, c.threads());
        if (ts.marcher == Marcher::HiZ) buildHiZ(hf.viewZ, ht.hiz, c.threads());
    });
    const RayGenGBuffer rayGen{&hf.viewZ,
                               {&hf.normal[0], &hf.normal[1], &hf.normal[2]},
                               nullptr,
                               {&hf.albedo[0], &hf.albedo[1], &hf.albedo[2]},
                               &hf.metallic};
    const MarchGBuffer march{
        &hf.viewZ, {&hf.normal[0], &hf.normal[1], &hf.normal[2]}, backZ(hf.backZ)};
    SsgiInputs in = full;
    in.camera = hf.camera;
    in.viewZ = &hf.viewZ;
    for (int ch = 0; ch < 3; ++ch) in.hitLight[ch] = &hf.hitLight[ch];
    if (tracedSignalsPooled(c.args.settings))  // (back to the pool in denoiseHalfDiffuse)
        takeSignal(frame.scratch.pool, ht.resolved, hf.camera.width, hf.camera.height);
    const HitStatsPlanes hp{&ht.resolved.hit, c.debugPlane(ht.resolved.steps),
                            &ht.resolved.hitDistance};
    const HiZPyramid* hiz = ts.marcher == Marcher::HiZ ? &ht.hiz : nullptr;
    const SsgiSample q{c, {hf.camera, march, hiz, &hf}, rayGen, in, hp, cut, {}, ht.resolved.color};
    for (int s = 0; s < ts.ssgiSpp; ++s) {
        RayGenStats rs = ssgiSample(q, s, ht.rays, ht.march, st, times);
        // The frame's surface pixels: the chosen ones traced here, the others cut (hidden
        // and background stay counts of half pixels).
        rs.pixels += hf.cutPixels;
        rs.cut += hf.cutPixels;
        st.rays.add(rs);
    }
    // The full-resolution planes: what the composite reads without the denoiser, and only to
    // be looked at with it (which denoises the half frame's: denoiseHalfDiffuse).
    SsgiPlanes& planes = frame.trace.ssgi;
    if (planes.color[0].empty()) return;
    times.reconstruct = 0.0;
    addTime(times.reconstruct, [&] {
        const ReconstructSource from{
            {&ht.resolved.color[0], &ht.resolved.color[1], &ht.resolved.color[2]},
            nullptr,
            &ht.resolved.hit,
            &ht.resolved.hitDistance,
            c.debugPlane(ht.resolved.steps)};
        const ReconstructPlanes to{{&planes.color[0], &planes.color[1], &planes.color[2]},
                                   nullptr,
                                   &planes.hit,
                                   &planes.hitDistance,
                                   c.debugPlane(planes.steps)};
        upsampleHalf(isa, c.guides(frame), hf.offset, ht.rays.pdf, from, to, c.threads());
    });
}

// Multi-bounce diffuse (TraceSettings::ssgiFeedback): the last frame's incoming diffuse
// radiance, where the history has it at this size, reflected into the hit light SSGI reads
// (trace/ssgi.h); none (one bounce) otherwise.
void feedbackPass(const TraceContext& c, Frame& frame) {
    const FrameHistory* h = c.args.history;
    if (!c.ts.ssgiFeedback || !h || h->diffuse[0].width() != frame.width ||
        h->diffuse[0].height() != frame.height)
        return;
    const GBuffer& g = frame.gbuffer;
    SsgiFeedbackInputs in;
    in.viewZ = &g.viewZ;
    for (int ch = 0; ch < 3; ++ch) {
        in.albedo[ch] = &g.albedo[ch];
        in.prevDiffuse[ch] = &h->diffuse[ch];
    }
    in.metallic = &g.metallic;
    if (!frame.material.occlusion.empty()) in.occlusion = &frame.material.occlusion;
    in.motion[0] = &g.motion[0];
    in.motion[1] = &g.motion[1];
    const ScopedPass timer(frame.stats, "ssgi feedback");
    addSsgiFeedback(c.args.isa, in, frame.direct.hitLight, c.threads());
}

void ssgiPass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts;
    const Isa isa = c.args.isa;
    const GBuffer& g = frame.gbuffer;
    const DirectParts& parts = frame.direct;
    Frame::Scratch& sc = frame.scratch;
    SsgiPlanes& planes = frame.trace.ssgi;
    SsgiInputs in;
    in.camera = c.camera;
    in.viewZ = &g.viewZ;
    for (int ch = 0; ch < 3; ++ch) {
        in.normal[ch] = &g.normal[ch];
        in.albedo[ch] = &g.albedo[ch];
        in.emission[ch] = c.args.direct.anyEmissive ? &parts.emission[ch] : nullptr;
        // The direct pass's hit light (then the G-buffer planes above are not read).
        in.hitLight[ch] = &parts.hitLight[ch];
    }
    in.metallic = &g.metallic;
    in.shadow = &frame.image.shadow;
    in.lighting = &c.args.direct;
    const HitStatsPlanes hp{&planes.hit, c.debugPlane(planes.steps), &planes.hitDistance};
    TraceStats& st = frame.stats.ssgi;
    st.ran = true;
    st.spp = ts.ssgiSpp;
    StageTimes times;
    feedbackPass(c, frame);
    const DiffuseCut cut = ts.traceHidden ? DiffuseCut::None : DiffuseCut::NoDiffuseColour;
    if (ts.ssgiLayout == TraceLayout::Half) {
        ssgiHalf(c, frame, in, cut, st, times);
        times.report(frame.stats, "ssgi");
        return;
    }
    const RayGenCheckerboard checker{ts.ssgiLayout == TraceLayout::Checkerboard,
                                     kSsgiCheckerboardPhase};
    takeBatches(c, frame, false);
    if (tracedSignalsPooled(c.args.settings))  // (back to the pool in denoisePass)
        takeSignal(sc.pool, planes, frame.width, frame.height);
    const SsgiSample q{
        c, {c.camera, c.march, c.hiz, nullptr}, c.rayGen, in, hp, cut, checker, planes.color};
    for (int s = 0; s < ts.ssgiSpp; ++s)
        st.rays.add(ssgiSample(q, s, sc.rays, sc.march, st, times));
    if (checker.on) {
        times.reconstruct = 0.0;
        addTime(times.reconstruct, [&] {
            const ReconstructPlanes rp{{&planes.color[0], &planes.color[1], &planes.color[2]},
                                       nullptr,
                                       &planes.hit,
                                       &planes.hitDistance};
            fillCheckerboard(isa, c.guides(frame), sc.rays.pdf, rp, c.threads());
        });
    }
    sc.pool.give(sc.rays);
    sc.pool.give(sc.march);
    times.report(frame.stats, "ssgi");
}

// What both of the frame's denoiser calls share: the camera they run at, the frame, whether
// the history is replaced, the debug planes and the frame's pool of scratch.
DenoiseInputs denoiseCall(const TraceContext& c, Frame& frame, const TraceCamera& camera) {
    DenoiseInputs in;
    in.camera = camera;
    in.frameIndex = c.args.frameIndex;
    in.replaceHistory = c.args.replaceHistory;
    in.historyLengths = c.args.settings.debugPlanes;
    in.pool = &frame.scratch.pool;
    return in;
}

// The diffuse signal where SSGI traces at half resolution: denoised on the half frame (a
// quarter of the pixels, at the resolution it was traced), on guides from each block's first
// pixel (HalfFrame::guideZ), then brought to the frame by the guided upsample that brings the
// raw signal (trace/reconstruct.h), placing each half pixel at that first pixel.
void denoiseHalfDiffuse(const TraceContext& c, Frame& frame, std::vector<DenoisePassTime>& times) {
    Frame::Scratch::HalfTrace& ht = frame.scratch.half;
    const HalfFrame& hf = ht.frame;
    DenoiseInputs in = denoiseCall(c, frame, hf.camera);
    in.viewZ = &hf.guideZ;
    in.metallic = &hf.metallic;
    for (int i = 0; i < 3; ++i) {
        in.normal[i] = &hf.guideNormal[i];
        in.albedo[i] = &hf.albedo[i];
        in.diffuse[i] = &ht.resolved.color[i];
    }
    in.motion[0] = &hf.guideMotion[0];
    in.motion[1] = &hf.guideMotion[1];
    in.diffuseHitDistance = &ht.resolved.hitDistance;
    if (tracedSignalsPooled(c.args.settings))
        in.signalsRead = [&frame] { frame.scratch.pool.give(frame.scratch.half.resolved); };
    DenoiseHistory* history = c.args.sequence ? &c.args.sequence->denoiseHalf : nullptr;
    DenoiseOutputs& half = ht.denoised.out;
    denoise(c.args.isa, halfResolutionDiffuse(c.ts.denoise), in, history, c.args.resetHistory,
            ht.denoise, half, c.threads(), &times);
    if (diffuseUpsampledInComposite(c.args.settings)) return;  // (compositePass)
    const auto t0 = std::chrono::steady_clock::now();
    DenoiseOutputs& out = frame.trace.denoise.out;
    // (The history length, a plane to look at, is blended as the hit share is.)
    const ReconstructSource from{{&half.diffuse[0], &half.diffuse[1], &half.diffuse[2]},
                                 nullptr,
                                 c.debugPlane(half.diffuseFrames)};
    const ReconstructPlanes to{{&out.diffuse[0], &out.diffuse[1], &out.diffuse[2]},
                               nullptr,
                               c.debugPlane(out.diffuseFrames)};
    upsampleHalf(c.args.isa, c.guides(frame), PixelOffset{0, 0}, ht.rays.pdf, from, to,
                 c.threads());
    const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - t0;
    times.push_back({"denoise upsample", ms.count()});
}

// REBLUR over SSGI's and SSR's signals (denoise/denoise.h): frame.trace.denoise, which the
// composite then reads; the traced planes stay as they were (the undenoised layers).
void denoisePass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts;
    const bool halfDiffuse = ts.ssgi && ts.ssgiLayout == TraceLayout::Half;
    const GBuffer& g = frame.gbuffer;
    DenoiseInputs in = denoiseCall(c, frame, c.camera);
    in.viewZ = &g.viewZ;
    in.roughness = &g.roughness;
    in.metallic = &g.metallic;
    for (int i = 0; i < 3; ++i) {
        in.normal[i] = &g.normal[i];
        in.albedo[i] = &g.albedo[i];
    }
    in.motion[0] = &g.motion[0];
    in.motion[1] = &g.motion[1];
    if (ts.ssgi && !halfDiffuse) {
        for (int ch = 0; ch < 3; ++ch) in.diffuse[ch] = &frame.trace.ssgi.color[ch];
        in.diffuseHitDistance = &frame.trace.ssgi.hitDistance;
    }
    if (ts.ssr) {
        for (int ch = 0; ch < 3; ++ch) {
            in.ssr[ch] = &frame.trace.ssr.color[ch];
            in.envSpecular[ch] = &frame.direct.envSpecular[ch];
        }
        in.ssrOpacity = &frame.trace.ssr.opacity;
        in.specularHitDistance = &frame.trace.ssr.hitDistance;
        // Where SSR has faded out the blend is the environment alone: nothing to denoise.
        in.specularMaxRoughness = ts.resolve.roughnessFadeEnd;
    }
    if (tracedSignalsPooled(c.args.settings))
        in.signalsRead = [&frame] {
            frame.scratch.pool.give(frame.trace.ssr);
            frame.scratch.pool.give(frame.trace.ssgi);
        };
    DenoiseHistory* history = c.args.sequence ? &c.args.sequence->denoise : nullptr;
    std::vector<DenoisePassTime> times;
    if (in.diffuse[0] || in.ssr[0])
        denoise(c.args.isa, ts.denoise, in, history, c.args.resetHistory, frame.scratch.denoise,
                frame.trace.denoise.out, c.threads(), &times);
    if (halfDiffuse) denoiseHalfDiffuse(c, frame, times);
    // One line per pass, summed over the two calls.
    for (const DenoisePassTime& t : times) {
        auto same = std::find_if(frame.stats.passes.begin(), frame.stats.passes.end(),
                                 [&](const PassTime& p) { return p.name == t.name; });
        if (same != frame.stats.passes.end()) same->ms += t.ms;
        else frame.stats.passes.push_back({t.name, t.ms});
    }
}

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

void compositePass(const TraceContext& c, Frame& frame) {
    const TraceSettings& ts = c.ts;
    const bool inComposite = diffuseUpsampledInComposite(c.args.settings);
    const GBuffer& g = frame.gbuffer;
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
            ci.albedo[ch] = &g.albedo[ch];
        }
        if (ts.ssr) {  // the denoiser's output, or SSR's own
            if (ts.denoise.enabled) ci.specular[ch] = &d.specular[ch];
            else ci.ssrColor[ch] = &frame.trace.ssr.color[ch];
        }
    }
    if (ts.ssgi) {
        ci.viewZ = &g.viewZ;
        ci.metallic = &g.metallic;
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

void runTracePasses(const TracePassArgs& args, Frame& frame) {
    TraceContext c(args, frame);
    hiZPass(c, frame);
    if (c.ts.ssr) ssrPass(c, frame);
    if (c.ts.ssgi) ssgiPass(c, frame);
    if (c.ts.denoise.enabled) denoisePass(c, frame);
    compositePass(c, frame);
}

bool readsHistory(const TraceSettings& s) {
    return (s.ssr && s.resolve.radiance == HitRadiance::Reprojected) || (s.ssgi && s.ssgiFeedback);
}

namespace {

// The incoming diffuse radiance the next frame's SSGI hits reflect (ssgiFeedback): the
// planes the composite multiplied by the diffuse colour, the denoiser's where it ran (a
// bounce of one-ray noise fed back would come back as noise), else SSGI's.
const PlaneF* committedDiffuse(const Frame& frame) {
    const DenoiseOutputs& d = frame.trace.denoise.out;
    return d.diffuse[0].empty() ? frame.trace.ssgi.color : d.diffuse;
}

// A non-finite value (a NaN from a bad input, an overflow) is committed as 0, no light: the
// next frames read the history through the reprojection (SSR's reprojected radiance, SSGI
// feedback), and a NaN kept there would spread to every pixel that reflects it, frame after
// frame, long after the input that made it is gone.
void commitPlanes(const PlaneF* src, PlaneF* dst, int w, int h) {
    for (int ch = 0; ch < 3; ++ch) {
        dst[ch].ensureSize(w, h);  // kept across frames: no allocation once sized
        for (int y = 0; y < h; ++y) {
            const float* in = src[ch].row(y);
            float* out = dst[ch].row(y);
            for (int x = 0; x < w; ++x) out[x] = std::isfinite(in[x]) ? in[x] : 0.0f;
        }
    }
}

}  // namespace

void commitHistory(const TraceSettings& s, const Frame& frame, FrameHistory& history) {
    const int w = frame.width, h = frame.height;
    // The colour always (FrameHistory::usableAt goes by its size), the diffuse light for
    // feedback only.
    commitPlanes(frame.image.color, history.color, w, h);
    if (s.ssgi && s.ssgiFeedback) commitPlanes(committedDiffuse(frame), history.diffuse, w, h);
    history.valid = true;
}

}  // namespace ssrt
