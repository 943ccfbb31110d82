// The frame graph's passes, in the order they run, over the resources of renderer/resources.h
// (renderer/frame_graph.h). The conditions below say when the code runs a pass and which
// resources it reads and writes; tests/renderer/frame_graph_test.cpp renders frames over many
// settings and checks that the outputs compiled from here are the frame's layers, name for
// name, every pixel written, and that the denoiser's passes are the ones the frame timed.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "renderer/frame_graph.h"
#include "renderer/trace_pass.h"

namespace ssrt {

namespace {

using P = Footprint;

// --- Conditions (each a plain function, so that a declaration can point at it) ---
const TraceSettings& tr(const GraphKey& k) { return k.settings.trace; }
bool trace(const GraphKey& k) { return tr(k).any(); }
bool ssr(const GraphKey& k) { return tr(k).ssr; }
bool ssgi(const GraphKey& k) { return tr(k).ssgi; }
bool denoise(const GraphKey& k) { return trace(k) && tr(k).denoise.enabled; }
// (the planes only looked at are trace planes: none without those)
bool debug(const GraphKey& k) { return k.settings.debugPlanes && k.settings.tracePlanes; }
bool noTrace(const GraphKey& k) { return !trace(k); }
bool halfSsgi(const GraphKey& k) { return ssgi(k) && tr(k).ssgiLayout == TraceLayout::Half; }
bool fullSsgi(const GraphKey& k) { return ssgi(k) && !halfSsgi(k); }
bool backFaces(const GraphKey& k) { return trace(k) && tr(k).march.backFaces; }
bool hiZMarcher(const GraphKey& k) { return tr(k).marcher == Marcher::HiZ; }
bool textured(const GraphKey& k) { return k.scene.textured; }
bool uvSet1(const GraphKey& k) { return k.scene.textured && k.scene.uvSet1; }
bool normalMapped(const GraphKey& k) { return k.scene.textured && k.scene.normalMapped; }
bool emissiveTextured(const GraphKey& k) { return k.scene.textured && k.scene.emissiveTextured; }
bool occlusionTextured(const GraphKey& k) { return k.scene.textured && k.scene.occlusionTextured; }
bool idPlanes(const GraphKey& k) { return k.settings.idPlanes; }
bool traceEmissive(const GraphKey& k) { return trace(k) && k.scene.emissive; }
bool traceNoSsgi(const GraphKey& k) { return trace(k) && !ssgi(k); }
bool hitLightFull(const GraphKey& k) { return ssgi(k) && !hitLightAtHalf(k.settings); }
bool hitLightHalf(const GraphKey& k) { return hitLightAtHalf(k.settings); }
bool ssgiOcclusion(const GraphKey& k) { return ssgi(k) && occlusionTextured(k); }
// SSR's proof of its march hits (mixed tracing, trace/hit_proof.h) reads the triangle ids.
bool ssrMixed(const GraphKey& k) { return ssr(k) && tr(k).ssrTrace == TraceMode::Mixed; }
// SSR's world rays (mixed and world tracing) light a hidden hit with the frame's shadow map
// (world/hit_light.h).
bool ssrWorld(const GraphKey& k) { return ssr(k) && tr(k).ssrTrace != TraceMode::Screen; }
// The same of SSGI's (on the half frame, its proof reads the chosen pixels' ids).
bool ssgiMixed(const GraphKey& k) { return ssgi(k) && tr(k).ssgiTrace == TraceMode::Mixed; }
bool halfMixed(const GraphKey& k) { return halfSsgi(k) && ssgiMixed(k); }
bool ssgiWorld(const GraphKey& k) { return ssgi(k) && tr(k).ssgiTrace != TraceMode::Screen; }
// (The half frame's proof reads the half frame's own: HalfThinFeatures.)
bool proves(const GraphKey& k) { return ssrMixed(k) || (fullSsgi(k) && ssgiMixed(k)); }
// The Hi-Z pyramid of the frame: for SSR, and for SSGI unless it marches on the half frame's.
bool hiZ(const GraphKey& k) { return hiZMarcher(k) && (ssr(k) || fullSsgi(k)); }
bool reuseResolve(const GraphKey& k) { return tr(k).resolve.mode == SsrResolveMode::Reuse; }
bool mipResolve(const GraphKey& k) { return ssr(k) && tr(k).resolve.mode == SsrResolveMode::Mip; }
bool reprojected(const GraphKey& k) {
    return k.history && k.lastColor && tr(k).resolve.radiance == HitRadiance::Reprojected;
}
bool current(const GraphKey& k) { return !reprojected(k); }
bool ssrChecker(const GraphKey& k) {
    return ssr(k) && tr(k).ssrLayout == TraceLayout::Checkerboard;
}
// (thinned by the denoiser's last specular history lengths, where it reads them)
bool ssrSparse(const GraphKey& k) {
    return ssrChecker(k) && k.history && denoise(k) &&
           tr(k).ssrSparseFrames < TraceSettings::kSparseOff;
}
bool ssgiChecker(const GraphKey& k) {
    return fullSsgi(k) && tr(k).ssgiLayout == TraceLayout::Checkerboard;
}
bool feedback(const GraphKey& k) {
    return k.history && k.lastDiffuse && ssgi(k) && tr(k).ssgiFeedback;
}
bool halfGuides(const GraphKey& k) { return halfSsgi(k) && denoise(k); }
bool halfHiZ(const GraphKey& k) { return halfSsgi(k) && hiZMarcher(k); }
bool halfBack(const GraphKey& k) { return halfSsgi(k) && backFaces(k); }
bool debugHalfSsgi(const GraphKey& k) { return halfSsgi(k) && debug(k); }
// The denoiser's signals: SSR's, and SSGI's at full resolution or on the half frame.
bool denoiseSpecular(const GraphKey& k) { return denoise(k) && ssr(k); }
bool denoiseFullDiffuse(const GraphKey& k) { return denoise(k) && fullSsgi(k); }
bool debugSpecular(const GraphKey& k) { return denoiseSpecular(k) && debug(k); }
bool debugFullDiffuse(const GraphKey& k) { return denoiseFullDiffuse(k) && debug(k); }
bool denoiseFull(const GraphKey& k) { return denoiseSpecular(k) || denoiseFullDiffuse(k); }
bool denoiseHalf(const GraphKey& k) { return denoise(k) && halfSsgi(k); }
bool debugHalfDenoise(const GraphKey& k) { return denoiseHalf(k) && debug(k); }
// The denoiser's history: read (the last frame's), kept (this frame's, for the next).
bool readFull(const GraphKey& k) { return k.history && denoiseFull(k); }
bool readHalf(const GraphKey& k) { return k.history && denoiseHalf(k); }
bool readSpecular(const GraphKey& k) { return k.history && denoiseSpecular(k); }
bool readFullDiffuse(const GraphKey& k) { return k.history && denoiseFullDiffuse(k); }
bool keepFull(const GraphKey& k) { return k.keepHistory && denoiseFull(k); }
bool keepHalf(const GraphKey& k) { return k.keepHistory && denoiseHalf(k); }
bool keepSpecular(const GraphKey& k) { return k.keepHistory && denoiseSpecular(k); }
bool keepFullDiffuse(const GraphKey& k) { return k.keepHistory && denoiseFullDiffuse(k); }
// The pre-blur per signal (DenoiseSettings' prepass radii; the half diffuse always has one:
// halfResolutionDiffuse).
bool preBlurFullDiffuse(const GraphKey& k) {
    return denoiseFullDiffuse(k) && tr(k).denoise.diffusePrepassRadius > 0.0f;
}
bool preBlurSpecular(const GraphKey& k) {
    return denoiseSpecular(k) && tr(k).denoise.specularPrepassRadius > 0.0f;
}
bool preBlurFull(const GraphKey& k) { return preBlurFullDiffuse(k) || preBlurSpecular(k); }
bool unblurredFullDiffuse(const GraphKey& k) {
    return denoiseFullDiffuse(k) && !preBlurFullDiffuse(k);
}
bool unblurredSpecular(const GraphKey& k) { return denoiseSpecular(k) && !preBlurSpecular(k); }
bool never(const GraphKey&) { return false; }
// The temporal pass: where a history is read, or kept (the speeds and fast luma it writes are
// what the commit keeps). A single image has neither: the pass would copy its input, with no
// speed and its own luma as the fast history, which the passes after take as read.
bool temporalFull(const GraphKey& k) { return denoiseFull(k) && (k.history || k.keepHistory); }
bool temporalHalf(const GraphKey& k) { return denoiseHalf(k) && (k.history || k.keepHistory); }
// What the history fix reads where the temporal pass does not run: the pre-blur's result, or
// the front end's.
bool fixReadsTemporalFullDiffuse(const GraphKey& k) {
    return temporalFull(k) && denoiseFullDiffuse(k);
}
bool fixReadsTemporalSpecular(const GraphKey& k) { return temporalFull(k) && denoiseSpecular(k); }
bool fixReadsPreBlurredFullDiffuse(const GraphKey& k) {
    return preBlurFullDiffuse(k) && !temporalFull(k);
}
bool fixReadsPreBlurredSpecular(const GraphKey& k) {
    return preBlurSpecular(k) && !temporalFull(k);
}
bool fixReadsPreBlurredHalf(const GraphKey& k) { return denoiseHalf(k) && !temporalHalf(k); }
bool fixReadsNoisyFullDiffuse(const GraphKey& k) {
    return unblurredFullDiffuse(k) && !temporalFull(k);
}
bool fixReadsNoisySpecular(const GraphKey& k) { return unblurredSpecular(k) && !temporalFull(k); }
bool upsampleInComposite(const GraphKey& k) { return diffuseUpsampledInComposite(k.settings); }
bool denoiseUpsample(const GraphKey& k) { return denoiseHalf(k) && !upsampleInComposite(k); }
bool compositeSsgiRaw(const GraphKey& k) { return ssgi(k) && !denoise(k); }
bool compositeSsrRaw(const GraphKey& k) { return ssr(k) && !denoise(k); }
bool commit(const GraphKey& k) { return k.keepHistory && trace(k) && readsHistory(tr(k)); }
bool keepDiffuse(const GraphKey& k) { return k.keepHistory && ssgi(k) && tr(k).ssgiFeedback; }
bool keepDenoised(const GraphKey& k) { return keepDiffuse(k) && denoise(k); }
bool keepRaw(const GraphKey& k) { return keepDiffuse(k) && !denoise(k); }

// The G-buffer as the passes after the resolve read it at their own pixel.
void gbufferReads(std::vector<Access>& reads, Footprint f = P::Pixel) {
    for (Res r : {Res::ViewZ, Res::Normal, Res::Albedo, Res::Metallic, Res::Roughness})
        reads.push_back({r, f});
}

// The denoiser's passes over one set of signals (denoise/denoise.h): at full resolution
// (SSR's and SSGI's when it traces at full resolution), or SSGI's on the half frame.
struct DenoiseSite {
    const char* suffix;  // "" or " (half)"
    GraphCondition on;
    std::vector<Access> signals;  // the traced signals the front end reads
    std::vector<Access> guides;   // the frame's G-buffer, or the half frame's
    Res noisy[2];                 // diffuse, specular (Res::Count: none at this site)
    GraphCondition signal[2];
    // The pre-blur: whether it runs, and per signal whether it filters it (else the temporal
    // pass reads the front end's output directly).
    GraphCondition preBlur, preBlurred[2], unblurred[2];
    // Each pass's result per signal: the pre-blur's, the temporal pass's, the history fix's, the
    // blur's (Res::Count: none at this site).
    Res preBlurOut[2], temporalOut[2], fixOut[2], blurOut[2];
    Res state[2], fast[2], outputs[2], frames[2];
    GraphCondition framesMade[2];  // the history lengths, a plane only looked at: when made
    Res history[3];                // guides, diffuse, specular (Res::Count: none)
    GraphCondition historyRead[3], historyKept[3];
    // Each signal's history accumulation speeds (f32; Res::Count: in history[0], the guides')
    Res historyFrames[2];
    Res historyFast[2];  // each signal's fast history (f16 luma; Res::Count: none)
    // The temporal pass, and what the history fix reads per signal: the temporal pass's
    // result, or without it the pre-blur's or the front end's (noisy).
    GraphCondition temporal, fixReadsTemporal[2], fixReadsPreBlurred[2], fixReadsNoisy[2];
};

// Names made once, with the list of passes (which keeps views of them).
std::string_view keep(std::string s) {
    static std::vector<std::unique_ptr<std::string>> names;
    names.push_back(std::make_unique<std::string>(std::move(s)));
    return *names.back();
}

std::vector<Access> around(std::vector<Access> a) {
    for (Access& x : a) x.footprint = P::Around;
    return a;
}

void append(std::vector<Access>& to, const std::vector<Access>& more) {
    to.insert(to.end(), more.begin(), more.end());
}

void addDenoiser(std::vector<PassDecl>& passes, const DenoiseSite& s) {
    const auto name = [&](std::string_view pass) { return keep(std::string(pass) + s.suffix); };
    // Per signal: its state (own pixel: signal depth, speeds, fast luma).
    std::vector<Access> state;
    for (int i = 0; i < 2; ++i)
        if (s.noisy[i] != Res::Count) {
            state.push_back({s.state[i], P::Pixel, s.signal[i]});
            state.push_back({s.fast[i], P::Pixel, s.signal[i]});
        }
    // A spatial pass: the guides and the last result around, the state at the pixel; writes
    // its result per signal.
    const auto spatial = [&](const char* pass, std::vector<Access> reads, const Res(&out)[2],
                             const GraphCondition(&when)[2]) {
        PassDecl d{name(pass), s.on, around(s.guides), {}, true};
        append(d.reads, reads);
        append(d.reads, state);
        for (int i = 0; i < 2; ++i)
            if (out[i] != Res::Count) d.writes.push_back({out[i], P::Pixel, when[i]});
        return d;
    };
    // Front end: the signals sanitised, hit distances normalised, where each signal exists.
    PassDecl front{name("denoise front end"), s.on, s.guides, {}, true};
    append(front.reads, s.signals);
    for (int i = 0; i < 2; ++i)
        if (s.noisy[i] != Res::Count) front.writes.push_back({s.noisy[i], P::Pixel, s.signal[i]});
    append(front.writes, state);
    passes.push_back(front);
    std::vector<Access> noisy;
    for (int i = 0; i < 2; ++i)
        if (s.noisy[i] != Res::Count) noisy.push_back({s.noisy[i], P::Around, s.preBlurred[i]});
    PassDecl pre = spatial("denoise pre-blur", noisy, s.preBlurOut, s.preBlurred);
    pre.enabled = s.preBlur;
    passes.push_back(pre);
    // Temporal: the history through the motion (anywhere), this frame's speeds and fast luma;
    // this frame's signal pre-blurred, or as the front end left it.
    PassDecl temporal{name("denoise temporal"), s.temporal, s.guides, {}, true};
    for (int i = 0; i < 2; ++i) {
        if (s.noisy[i] == Res::Count) continue;
        temporal.reads.push_back({s.preBlurOut[i], P::Pixel, s.preBlurred[i]});
        temporal.reads.push_back({s.noisy[i], P::Pixel, s.unblurred[i]});
        temporal.writes.push_back({s.temporalOut[i], P::Pixel, s.signal[i]});
    }
    append(temporal.reads, state);
    append(temporal.writes, state);
    for (int i = 0; i < 3; ++i)
        if (s.history[i] != Res::Count)
            temporal.reads.push_back({s.history[i], P::Anywhere, s.historyRead[i]});
    for (int i = 0; i < 2; ++i)
        for (Res r : {s.historyFrames[i], s.historyFast[i]})
            if (r != Res::Count) temporal.reads.push_back({r, P::Anywhere, s.historyRead[i + 1]});
    passes.push_back(temporal);
    std::vector<Access> fixReads, blurReads, postReads;
    for (int i = 0; i < 2; ++i) {
        if (s.noisy[i] == Res::Count) continue;
        fixReads.push_back({s.temporalOut[i], P::Around, s.fixReadsTemporal[i]});
        fixReads.push_back({s.preBlurOut[i], P::Around, s.fixReadsPreBlurred[i]});
        fixReads.push_back({s.noisy[i], P::Around, s.fixReadsNoisy[i]});
        blurReads.push_back({s.fixOut[i], P::Around, s.signal[i]});
        postReads.push_back({s.blurOut[i], P::Around, s.signal[i]});
    }
    passes.push_back(spatial("denoise history fix", fixReads, s.fixOut, s.signal));
    passes.push_back(spatial("denoise blur", blurReads, s.blurOut, s.signal));
    // Post-blur: the outputs, and the history the next frame reads.
    const Res none[2] = {Res::Count, Res::Count};
    PassDecl post = spatial("denoise post-blur", postReads, none, s.signal);
    for (int i = 0; i < 2; ++i) {
        if (s.noisy[i] == Res::Count) continue;
        post.writes.push_back({s.outputs[i], P::Pixel, s.signal[i]});
        if (s.frames[i] != Res::Count)
            post.writes.push_back({s.frames[i], P::Pixel, s.framesMade[i]});
    }
    // (The signals' history planes: radiance and hit distance.)
    for (int i = 1; i < 3; ++i)
        if (s.history[i] != Res::Count)
            post.writes.push_back({s.history[i], P::Pixel, s.historyKept[i]});
    passes.push_back(post);
    // The history's guides, speeds and fast luma for the next frame.
    PassDecl commit{name(pass::kDenoiseHistory), s.historyKept[0], s.guides, {}, true};
    append(commit.reads, state);
    commit.writes.push_back({s.history[0], P::Pixel, s.historyKept[0]});
    for (int i = 0; i < 2; ++i)
        for (Res r : {s.historyFrames[i], s.historyFast[i]})
            if (r != Res::Count) commit.writes.push_back({r, P::Pixel, s.historyKept[i + 1]});
    passes.push_back(commit);
}

std::vector<PassDecl> declarePasses() {
    std::vector<PassDecl> p;
    p.push_back({pass::kShadow, nullptr, {}, {{Res::ShadowMap}}});
    // (The rasters read their own depth: the depth test.)
    p.push_back({pass::kVisibility,
                 nullptr,
                 {{Res::VisibilityDepth}},
                 {{Res::VisibilityDepth}, {Res::VisibilityIds}}});
    p.push_back({pass::kBackFaces,
                 backFaces,
                 {{Res::VisibilityDepth}, {Res::VisibilityIds}, {Res::BackDepth}, {Res::BackIds}},
                 {{Res::BackDepth}, {Res::BackIds}, {Res::BackZ}}});
    p.push_back({pass::kResolve,
                 nullptr,
                 {{Res::VisibilityIds}},
                 {{Res::ViewZ},
                  {Res::Normal},
                  {Res::Albedo},
                  {Res::Metallic},
                  {Res::Roughness},
                  {Res::MaterialId},
                  {Res::Motion},
                  {Res::Uv0, P::Pixel, textured},
                  {Res::Uv1, P::Pixel, uvSet1},
                  {Res::Tangent, P::Pixel, normalMapped}}});
    p.back().tiled = true;
    p.push_back({pass::kTextures,
                 textured,
                 {{Res::Uv0},
                  {Res::Uv1, P::Pixel, uvSet1},
                  {Res::Tangent, P::Pixel, normalMapped},
                  {Res::MaterialId},
                  {Res::Albedo},
                  {Res::Metallic},
                  {Res::Roughness},
                  {Res::Normal, P::Pixel, normalMapped}},
                 {{Res::Albedo},
                  {Res::Metallic},
                  {Res::Roughness},
                  {Res::Normal, P::Pixel, normalMapped},
                  {Res::Emissive, P::Pixel, emissiveTextured},
                  {Res::Occlusion, P::Pixel, occlusionTextured}}});
    p.back().tiled = true;
    p.push_back(
        {pass::kIds, idPlanes, {{Res::VisibilityIds}}, {{Res::InstanceId}, {Res::TriangleId}}});
    p.back().tiled = true;
    // Direct light, sky and tone map; with a trace pass, the parts the composite rebuilds
    // the colour from.
    PassDecl shading{pass::kShading,
                     nullptr,
                     {{Res::ShadowMap, P::Anywhere},
                      {Res::MaterialId},
                      {Res::Motion},
                      {Res::Emissive, P::Pixel, emissiveTextured},
                      {Res::Occlusion, P::Pixel, occlusionTextured},
                      // SSGI's multi-bounce: last frame's diffuse light reflected into the hit
                      // light (shading/direct_kernel.h, prevDiffuse).
                      {Res::HistoryDiffuse, P::Anywhere, feedback}},
                     {{Res::Color},
                      {Res::Shadow},
                      {Res::Display, P::Pixel, noTrace},
                      {Res::Direct, P::Pixel, trace},
                      {Res::Emission, P::Pixel, traceEmissive},
                      {Res::EnvDiffuse, P::Pixel, traceNoSsgi},
                      {Res::EnvSpecular, P::Pixel, trace},
                      {Res::SpecWeight, P::Pixel, trace},
                      {Res::HitLight, P::Pixel, hitLightFull},
                      {Res::HalfHitLight, P::Around, hitLightHalf}}};
    gbufferReads(shading.reads);
    shading.tiled = true;
    p.push_back(shading);
    p.push_back({pass::kHiZ, hiZ, {{Res::ViewZ, P::Anywhere}}, {{Res::HiZ}, {Res::HiZPacked}}});
    // Mixed tracing's proof looks for thin features beside a ray's path (trace/hit_proof.h).
    p.push_back({pass::kThinFeatures, proves, {{Res::ViewZ, P::Around}}, {{Res::ThinFeatures}}});
    // SSR: rays from the G-buffer, the march through the depth (anywhere), the resolve.
    p.push_back(
        {"ssr colour pyramid",
         mipResolve,
         {{Res::Color, P::Anywhere, current}, {Res::HistoryColor, P::Anywhere, reprojected}},
         {{Res::ColorPyramid}}});
    p.push_back({pass::kSsr,
                 ssr,
                 {{Res::ViewZ, P::Anywhere},
                  {Res::Normal, P::Anywhere},
                  {Res::Roughness},
                  {Res::Motion},
                  {Res::HiZ, P::Anywhere, hiZMarcher},
                  {Res::HiZPacked, P::Anywhere, hiZMarcher},
                  {Res::BackZ, P::Anywhere, backFaces},
                  {Res::Color, P::Anywhere, current},
                  {Res::HistoryColor, P::Anywhere, reprojected},
                  {Res::ColorPyramid, P::Anywhere, mipResolve},
                  {Res::MarchHit, P::Around, reuseResolve},
                  {Res::SsrHitRadiance, P::Around},
                  {Res::SsrHitTarget, P::Around, reuseResolve},
                  {Res::DenoiseHistorySpecularFrames, P::Anywhere, ssrSparse},
                  {Res::VisibilityIds, P::Anywhere, ssrMixed},
                  {Res::ThinFeatures, P::Anywhere, ssrMixed},
                  {Res::ShadowMap, P::Anywhere, ssrWorld}},
                 {{Res::Ssr},
                  {Res::SsrOpacity},
                  {Res::SsrHit},
                  {Res::SsrHitDistance},
                  {Res::SsrSteps, P::Pixel, debug},
                  {Res::RayPdf},
                  {Res::MarchHit, P::Pixel, reuseResolve},
                  {Res::SsrHitRadiance},
                  {Res::SsrHitTarget, P::Pixel, reuseResolve}}});
    // The checkerboard's other phase, from the traced pixels around.
    p.push_back({pass::kSsrReconstruct,
                 ssrChecker,
                 {{Res::RayPdf, P::Around},
                  {Res::ViewZ, P::Around},
                  {Res::Normal, P::Around},
                  {Res::Ssr, P::Around},
                  {Res::SsrOpacity, P::Around},
                  {Res::SsrHit, P::Around},
                  {Res::SsrHitDistance, P::Around}},
                 {{Res::Ssr}, {Res::SsrOpacity}, {Res::SsrHit}, {Res::SsrHitDistance}}});
    // The half frame: one chosen pixel of each 2x2 block, its own pyramid.
    p.push_back({pass::kSsgiHalfFrame,
                 halfSsgi,
                 {{Res::ViewZ, P::Around},
                  {Res::Normal, P::Around},
                  {Res::Albedo, P::Around},
                  {Res::Metallic, P::Around},
                  {Res::HitLight, P::Around, hitLightFull},
                  {Res::Motion, P::Around, halfGuides},
                  {Res::BackZ, P::Around, backFaces},
                  {Res::VisibilityIds, P::Around, ssgiMixed}},
                 {{Res::HalfGBuffer},
                  {Res::HalfHitLight, P::Pixel, hitLightFull},
                  {Res::HalfBackZ, P::Pixel, halfBack},
                  {Res::HalfIds, P::Pixel, halfMixed},
                  {Res::HalfThinFeatures, P::Pixel, halfMixed},
                  {Res::HalfGuides, P::Pixel, halfGuides},
                  {Res::HalfHiZ, P::Pixel, halfHiZ}}});
    p.push_back({pass::kSsgiHalf,
                 halfSsgi,
                 {{Res::HalfGBuffer, P::Anywhere},
                  {Res::HalfHitLight, P::Anywhere},
                  {Res::HalfBackZ, P::Anywhere, halfBack},
                  {Res::HalfHiZ, P::Anywhere, halfHiZ},
                  {Res::HalfIds, P::Anywhere, halfMixed},
                  {Res::HalfThinFeatures, P::Anywhere, halfMixed},
                  {Res::ViewZ, P::Anywhere, ssgiWorld},
                  {Res::ShadowMap, P::Anywhere, ssgiWorld}},
                 {{Res::HalfSsgi}, {Res::HalfRayPdf}, {Res::HalfSsgiSteps, P::Pixel, debug}}});
    p.push_back(
        {pass::kSsgiUpsample,
         halfSsgi,
         {{Res::HalfSsgi, P::Around},
          {Res::HalfSsgiSteps, P::Around, debugHalfSsgi},
          {Res::HalfRayPdf, P::Around},
          {Res::ViewZ},
          {Res::Normal}},
         {{Res::Ssgi}, {Res::SsgiHit}, {Res::SsgiHitDistance}, {Res::SsgiSteps, P::Pixel, debug}}});
    p.push_back({pass::kSsgi,
                 fullSsgi,
                 {{Res::ViewZ, P::Anywhere},
                  {Res::Normal, P::Anywhere},
                  {Res::Albedo},
                  {Res::Metallic},
                  {Res::HiZ, P::Anywhere, hiZMarcher},
                  {Res::HiZPacked, P::Anywhere, hiZMarcher},
                  {Res::BackZ, P::Anywhere, backFaces},
                  {Res::HitLight, P::Anywhere},
                  {Res::VisibilityIds, P::Anywhere, ssgiMixed},
                  {Res::ThinFeatures, P::Anywhere, ssgiMixed},
                  {Res::ShadowMap, P::Anywhere, ssgiWorld}},
                 {{Res::Ssgi},
                  {Res::SsgiHit},
                  {Res::SsgiHitDistance},
                  {Res::SsgiSteps, P::Pixel, debug},
                  {Res::RayPdf}}});
    p.push_back({pass::kSsgiReconstruct,
                 ssgiChecker,
                 {{Res::RayPdf, P::Around},
                  {Res::ViewZ, P::Around},
                  {Res::Normal, P::Around},
                  {Res::Ssgi, P::Around},
                  {Res::SsgiHit, P::Around},
                  {Res::SsgiHitDistance, P::Around}},
                 {{Res::Ssgi}, {Res::SsgiHit}, {Res::SsgiHitDistance}}});
    // SSGI's diffuse denoised on the half frame, on guides from each block's first pixel.
    const DenoiseSite half{" (half)",
                           denoiseHalf,
                           {{Res::HalfSsgi}},
                           {{Res::HalfGuides}, {Res::HalfGBuffer}},
                           {Res::HalfDenoiseNoisy, Res::Count},
                           {denoiseHalf, nullptr},
                           denoiseHalf,
                           {denoiseHalf, nullptr},
                           {never, nullptr},
                           {Res::HalfDenoisePreBlurred, Res::Count},
                           {Res::HalfDenoiseTemporal, Res::Count},
                           {Res::HalfDenoiseFixed, Res::Count},
                           {Res::HalfDenoiseBlurred, Res::Count},
                           {Res::HalfDenoiseState, Res::Count},
                           {Res::HalfDenoiseFast, Res::Count},
                           {Res::HalfDenoised, Res::Count},
                           {Res::HalfDiffuseFrames, Res::Count},
                           {debugHalfDenoise, nullptr},
                           {Res::HalfDenoiseHistory, Res::HalfDenoiseHistorySignal, Res::Count},
                           {readHalf, readHalf, nullptr},
                           {keepHalf, keepHalf, nullptr},
                           {Res::Count, Res::Count},
                           {Res::HalfDenoiseHistoryFast, Res::Count},
                           temporalHalf,
                           {temporalHalf, nullptr},
                           {fixReadsPreBlurredHalf, nullptr},  // (it always pre-blurs)
                           {never, nullptr}};
    addDenoiser(p, half);
    p.push_back({pass::kDenoiseUpsample,
                 denoiseUpsample,
                 {{Res::HalfDenoised, P::Around},
                  {Res::HalfDiffuseFrames, P::Around, debug},
                  {Res::HalfRayPdf, P::Around},
                  {Res::ViewZ},
                  {Res::Normal}},
                 {{Res::DenoisedDiffuse}, {Res::DiffuseFrames, P::Pixel, debug}}});
    // The denoiser at full resolution: SSR's signal (over the environment) and SSGI's. (After
    // the half frame's, so the two hold their scratch at once only while the half frame's last
    // passes and the frame's first share a loop over both grids: frame_graph.h's chains.)
    DenoiseSite full{
        "",
        denoiseFull,
        {{Res::Ssgi, P::Pixel, denoiseFullDiffuse},
         {Res::SsgiHitDistance, P::Pixel, denoiseFullDiffuse},
         {Res::Ssr, P::Pixel, denoiseSpecular},
         {Res::SsrOpacity, P::Pixel, denoiseSpecular},
         {Res::SsrHitDistance, P::Pixel, denoiseSpecular},
         {Res::EnvSpecular, P::Pixel, denoiseSpecular}},
        {},
        {Res::DenoiseNoisyDiffuse, Res::DenoiseNoisySpecular},
        {denoiseFullDiffuse, denoiseSpecular},
        preBlurFull,
        {preBlurFullDiffuse, preBlurSpecular},
        {unblurredFullDiffuse, unblurredSpecular},
        {Res::DenoisePreBlurredDiffuse, Res::DenoisePreBlurredSpecular},
        {Res::DenoiseTemporalDiffuse, Res::DenoiseTemporalSpecular},
        {Res::DenoiseFixedDiffuse, Res::DenoiseFixedSpecular},
        {Res::DenoiseBlurredDiffuse, Res::DenoiseBlurredSpecular},
        {Res::DenoiseDiffuseState, Res::DenoiseSpecularState},
        {Res::DenoiseDiffuseFast, Res::DenoiseSpecularFast},
        {Res::DenoisedDiffuse, Res::DenoisedSpecular},
        {Res::DiffuseFrames, Res::SpecularFrames},
        {debugFullDiffuse, debugSpecular},
        {Res::DenoiseHistoryGuides, Res::DenoiseHistoryDiffuse, Res::DenoiseHistorySpecular},
        {readFull, readFullDiffuse, readSpecular},
        {keepFull, keepFullDiffuse, keepSpecular},
        {Res::DenoiseHistoryDiffuseFrames, Res::DenoiseHistorySpecularFrames},
        {Res::DenoiseHistoryDiffuseFast, Res::DenoiseHistorySpecularFast},
        temporalFull,
        {fixReadsTemporalFullDiffuse, fixReadsTemporalSpecular},
        {fixReadsPreBlurredFullDiffuse, fixReadsPreBlurredSpecular},
        {fixReadsNoisyFullDiffuse, fixReadsNoisySpecular}};
    gbufferReads(full.guides);
    full.guides.push_back({Res::Motion});
    addDenoiser(p, full);
    // Direct + diffuse + specular, tone mapped, over the direct pass's colour.
    p.push_back({pass::kComposite,
                 trace,
                 {{Res::Direct},
                  {Res::Emission, P::Pixel, traceEmissive},
                  {Res::EnvDiffuse, P::Pixel, traceNoSsgi},
                  {Res::EnvSpecular},
                  {Res::SpecWeight},
                  {Res::Albedo, P::Pixel, ssgi},
                  {Res::ViewZ, P::Pixel, ssgi},
                  {Res::Metallic, P::Pixel, ssgi},
                  {Res::Occlusion, P::Pixel, ssgiOcclusion},
                  {Res::Ssgi, P::Pixel, compositeSsgiRaw},
                  {Res::DenoisedDiffuse, P::Pixel, denoiseFullDiffuse},
                  {Res::DenoisedDiffuse, P::Pixel, denoiseUpsample},
                  {Res::HalfDenoised, P::Around, upsampleInComposite},
                  {Res::HalfRayPdf, P::Around, upsampleInComposite},
                  {Res::Normal, P::Around, upsampleInComposite},
                  {Res::Ssr, P::Pixel, compositeSsrRaw},
                  {Res::SsrOpacity, P::Pixel, compositeSsrRaw},
                  {Res::DenoisedSpecular, P::Pixel, denoiseSpecular}},
                 {{Res::Color}, {Res::Display}},
                 true});
    // What the next frame reads.
    p.push_back({pass::kHistoryCommit,
                 commit,
                 {{Res::Color},
                  {Res::DenoisedDiffuse, P::Pixel, keepDenoised},
                  {Res::Ssgi, P::Pixel, keepRaw}},
                 {{Res::HistoryColor}, {Res::HistoryDiffuse, P::Pixel, keepDiffuse}}});
    return p;
}

}  // namespace

const std::vector<PassDecl>& passDecls() {
    static const std::vector<PassDecl> passes = declarePasses();
    return passes;
}

}  // namespace ssrt
