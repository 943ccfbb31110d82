#include "renderer/resources.h"

#include <algorithm>
#include <array>
#include <bit>
#include <stdexcept>

#include "denoise/denoise.h"
#include "renderer/direct_lighting.h"
#include "renderer/resolve_tables.h"
#include "renderer/trace_pass.h"
#include "trace/trace_layout.h"

namespace ssrt {

namespace {

using F = PixelFormat;
using R = Resolution;
using L = Lifetime;
using G = LayerGroup;

// When an output only looked at is handed out (ResourceDecl::handedOut).
bool gbufferPlanes(const GraphKey& k) { return k.settings.gbufferPlanes; }
bool tracePlanes(const GraphKey& k) { return k.settings.tracePlanes; }
bool debugPlanes(const GraphKey& k) { return tracePlanes(k) && k.settings.debugPlanes; }
bool notPooled(const GraphKey& k) { return tracePlanes(k) && !tracedSignalsPooled(k.settings); }

// --- The resource table, in Res order ---
// (Every resource is f32 today but the ids, which are u32, and the denoiser's signals, which
// are f16: the formats the data needs come with the typed views.)
const std::array<ResourceDecl, kResourceCount> kResources = {{
    // The image: linear radiance times the exposure; tone mapped, sRGB encoded, in [0, 1]; the
    // light's visibility, 0..1.
    {Res::Color, "color", "R,G,B", F::F32, R::Full, L::Output, G::Color},
    {Res::Display, "display", "R,G,B", F::F32, R::Full, L::Output, G::Color},
    {Res::Shadow, "shadow", "", F::F32, R::Full, L::Output, G::Color},
    {Res::ViewZ, "viewZ", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes, kGViewZ},
    {Res::Normal, "normal", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes, kGNormal},
    {Res::Albedo, "albedo", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes, kGAlbedo},
    {Res::Metallic, "metallic", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes,
     kGMetallic},
    {Res::Roughness, "roughness", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes,
     kGRoughness},
    {Res::MaterialId, "materialId", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes,
     kGMaterialId},
    {Res::Motion, "motion", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes, kGMotion},
    {Res::Emissive, "emissive", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes,
     kGEmission},
    {Res::Occlusion, "occlusion", "", F::F32, R::Full, L::Output, G::GBuffer, gbufferPlanes,
     kGOcclusion},
    {Res::InstanceId, "instanceId", "", F::F32, R::Full, L::Output, G::GBuffer, nullptr,
     kGInstanceId},
    {Res::TriangleId, "triangleId", "", F::F32, R::Full, L::Output, G::GBuffer, nullptr,
     kGTriangleId},
    // What SSR hands out: reflected radiance (before the BRDF factor); opacity, 0..1, the share
    // of SSR over the environment; the share of the pixel's rays that hit; the view-space
    // distance to the hit, mean over hits (0 without one: the denoiser's guide); mean march
    // steps (the heat map).
    {Res::Ssr, "ssr", "R,G,B", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsrOpacity, "ssrOpacity", "", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsrHit, "ssrHit", "", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsrHitDistance, "ssrHitDistance", "", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsrSteps, "ssrSteps", "", F::F32, R::Full, L::Output, G::Trace, debugPlanes},
    // What SSGI hands out: incoming diffuse radiance, then as SSR's.
    {Res::Ssgi, "ssgi", "R,G,B", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsgiHit, "ssgiHit", "", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsgiHitDistance, "ssgiHitDistance", "", F::F32, R::Full, L::Output, G::Trace, notPooled},
    {Res::SsgiSteps, "ssgiSteps", "", F::F32, R::Full, L::Output, G::Trace, debugPlanes},
    {Res::DenoisedDiffuse, "denoisedDiffuse", "R,G,B", F::F32, R::Full, L::Output, G::Trace,
     tracePlanes},
    {Res::DenoisedSpecular, "denoisedSpecular", "R,G,B", F::F32, R::Full, L::Output, G::Trace,
     tracePlanes},
    {Res::DiffuseFrames, "diffuseFrames", "", F::F32, R::Full, L::Output, G::Trace, debugPlanes},
    {Res::SpecularFrames, "specularFrames", "", F::F32, R::Full, L::Output, G::Trace, debugPlanes},
    // Embree's check of the first sample's rays of each pass, at each ray's pixel (truth/
    // ray_check.h): its class, the pixel and relative depth error where both hit, Embree's hit
    // distance. Written by `ssrt compare` alone, after the frame: no pass declares them.
    {Res::SsrCheck, "ssrCheck", "class,pixelError,depthError,trueT", F::F32, R::Full, L::Output,
     G::Truth},
    {Res::SsgiCheck, "ssgiCheck", "class,pixelError,depthError,trueT", F::F32, R::Full, L::Output,
     G::Truth},
    {Res::ShadowMap, "shadowMap", "", F::F32, R::ShadowMap, L::Transient},
    {Res::VisibilityDepth, "visibility.depth", "", F::F32, R::Full, L::Transient},
    {Res::VisibilityIds, "visibility.ids", "", F::U32, R::Full, L::Transient},
    {Res::BackDepth, "back.depth", "", F::F32, R::Full, L::Transient},
    {Res::BackIds, "back.ids", "", F::U32, R::Full, L::Transient},
    {Res::BackZ, "backZ", "", F::F32, R::Full, L::Transient},
    {Res::Uv0, "uv0", "u,v,dudx,dvdx,dudy,dvdy", F::F32, R::Full, L::Transient},
    {Res::Uv1, "uv1", "u,v,dudx,dvdx,dudy,dvdy", F::F32, R::Full, L::Transient},
    {Res::Tangent, "tangent", "X,Y,Z,W", F::F32, R::Full, L::Transient},
    {Res::Direct, "direct", "R,G,B", F::F16, R::Full, L::Transient},
    {Res::Emission, "emission", "R,G,B", F::F16, R::Full, L::Transient},
    {Res::EnvDiffuse, "envDiffuse", "R,G,B", F::F16, R::Full, L::Transient},
    {Res::EnvSpecular, "envSpecular", "R,G,B", F::F16, R::Full, L::Transient},
    {Res::SpecWeight, "specWeight", "R,G,B", F::F16, R::Full, L::Transient},
    {Res::HitLight, "hitLight", "R,G,B", F::F16, R::Full, L::Transient},
    {Res::HiZ, "hiz.minZ", "", F::F32, R::Pyramid, L::Transient},
    {Res::HiZPacked, "hiz.packed", "", F::F32, R::Pyramid, L::Transient},
    // (Full: its 8- and 64-pixel levels add 1/64 and 1/4096.)
    {Res::ThinFeatures, "thinFeatures", "", F::F32, R::Full, L::Transient},
    {Res::ColorPyramid, "colorPyramid", "R,G,B", F::F32, R::Pyramid, L::Transient},
    {Res::RayPdf, "ray.pdf", "", F::F32, R::Full, L::Transient},
    {Res::MarchHit, "march.hit", "", F::F32, R::TileRing, L::Transient},
    {Res::SsrHitRadiance, "resolve.hitRadiance", "R,G,B,fade", F::F32, R::TileRing, L::Transient},
    {Res::SsrHitTarget, "resolve.hitTarget", "X,Y,Z", F::F32, R::TileRing, L::Transient},
    {Res::HalfGBuffer, "half.gbufferPlanes", "", F::F32, R::Half, L::Transient, G::Color, nullptr,
     HalfFrame::kPlanes},
    {Res::HalfHitLight, "half.hitLight", "R,G,B", F::F16, R::Half, L::Transient},
    {Res::HalfBackZ, "half.backZ", "", F::F32, R::Half, L::Transient},
    {Res::HalfIds, "half.ids", "", F::U32, R::Half, L::Transient},
    {Res::HalfThinFeatures, "half.thinFeatures", "", F::F32, R::Half, L::Transient},
    {Res::HalfGuides, "half.guide", "", F::F32, R::Half, L::Transient, G::Color, nullptr,
     HalfFrame::kGuidePlanes},
    {Res::HalfHiZ, "half.hiz", "minZ,packed", F::F32, R::HalfPyramid, L::Transient},
    {Res::HalfRayPdf, "half.ray.pdf", "", F::F32, R::Half, L::Transient},
    {Res::HalfSsgi, "half.ssgi", "R,G,B,hit,hitDistance", F::F32, R::Half, L::Transient},
    {Res::HalfSsgiSteps, "half.ssgiSteps", "", F::F32, R::Half, L::Transient},
    // The denoiser's signals are f16 (radiance, normalised hit distance, fast luma: decoded to
    // f32 by each pass), radiance with hit distance as f16x4 (R, G, B, hit in a pixel's 64 bits),
    // its guides and accumulation speeds f32 (denoise/denoise.h).
    {Res::DenoiseNoisyDiffuse, "noisy.diffuse", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseNoisySpecular, "noisy.specular", "", F::F16x4, R::Full, L::Transient},
    // Each pass's result per signal, named for the pass (NRD's resources).
    {Res::DenoisePreBlurredDiffuse, "preBlurred.diffuse", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoisePreBlurredSpecular, "preBlurred.specular", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseTemporalDiffuse, "temporal.diffuse", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseTemporalSpecular, "temporal.specular", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseFixedDiffuse, "fixed.diffuse", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseFixedSpecular, "fixed.specular", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseBlurredDiffuse, "blurred.diffuse", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseBlurredSpecular, "blurred.specular", "", F::F16x4, R::Full, L::Transient},
    {Res::DenoiseDiffuseState, "state.diffuse", "signalZ,frames", F::F32, R::Full, L::Transient},
    {Res::DenoiseSpecularState, "state.specular", "signalZ,frames", F::F32, R::Full, L::Transient},
    {Res::DenoiseDiffuseFast, "fast.diffuse", "", F::F16, R::Full, L::Transient},
    {Res::DenoiseSpecularFast, "fast.specular", "", F::F16, R::Full, L::Transient},
    {Res::HalfDenoiseNoisy, "half.noisy.diffuse", "", F::F16x4, R::Half, L::Transient},
    {Res::HalfDenoisePreBlurred, "half.preBlurred.diffuse", "", F::F16x4, R::Half, L::Transient},
    {Res::HalfDenoiseTemporal, "half.temporal.diffuse", "", F::F16x4, R::Half, L::Transient},
    {Res::HalfDenoiseFixed, "half.fixed.diffuse", "", F::F16x4, R::Half, L::Transient},
    {Res::HalfDenoiseBlurred, "half.blurred.diffuse", "", F::F16x4, R::Half, L::Transient},
    {Res::HalfDenoiseState, "half.state.diffuse", "signalZ,frames", F::F32, R::Half, L::Transient},
    {Res::HalfDenoiseFast, "half.fast.diffuse", "", F::F16, R::Half, L::Transient},
    {Res::HalfDenoised, "half.denoisedDiffuse", "R,G,B", F::F32, R::Half, L::Transient},
    {Res::HalfDiffuseFrames, "half.diffuseFrames", "", F::F32, R::Half, L::Transient},
    {Res::HistoryColor, "history.color", "R,G,B", F::F32, R::Full, L::History},
    {Res::HistoryDiffuse, "history.diffuse", "R,G,B", F::F32, R::Full, L::History},
    {Res::DenoiseHistoryGuides, "history.denoise.guide", "", F::F32, R::Full, L::History, G::Color,
     nullptr, DenoiseHistory::kGuidePlanes},
    {Res::DenoiseHistoryDiffuse, "history.denoise.diffuse", "", F::F16x4, R::Full, L::History},
    {Res::DenoiseHistorySpecular, "history.denoise.specular", "", F::F16x4, R::Full, L::History},
    {Res::DenoiseHistoryDiffuseFrames, "history.denoise.diffuseFrames", "", F::F32, R::Full,
     L::History},
    {Res::DenoiseHistorySpecularFrames, "history.denoise.specularFrames", "", F::F32, R::Full,
     L::History},
    {Res::DenoiseHistoryDiffuseFast, "history.denoise.diffuseFast", "", F::F16, R::Full,
     L::History},
    {Res::DenoiseHistorySpecularFast, "history.denoise.specularFast", "", F::F16, R::Full,
     L::History},
    {Res::HalfDenoiseHistory, "history.half.denoise",
     "viewZ,normal.X,normal.Y,normal.Z,"
     "roughness,frames",
     F::F32, R::Half, L::History},
    {Res::HalfDenoiseHistorySignal, "history.half.denoise.diffuse", "", F::F16x4, R::Half,
     L::History},
    {Res::HalfDenoiseHistoryFast, "history.half.denoise.diffuseFast", "", F::F16, R::Half,
     L::History},
}};

// Every resource's channel names, made once.
const std::array<std::vector<std::string>, kResourceCount>& allChannelNames() {
    static const auto names = [] {
        std::array<std::vector<std::string>, kResourceCount> n;
        for (int r = 0; r < kResourceCount; ++r) n[r] = kResources[r].channelNames();
        return n;
    }();
    return names;
}

}  // namespace

const ResourceDecl& resourceDecl(Res id) { return kResources[std::size_t(id)]; }

std::string_view resolutionName(Resolution r) {
    switch (r) {
        case Resolution::Full: return "full";
        case Resolution::Half: return "half";
        case Resolution::ShadowMap: return "shadow map";
        case Resolution::Pyramid: return "pyramid";
        case Resolution::HalfPyramid: return "half pyramid";
        case Resolution::TileRing: return "tile ring";
    }
    return "?";
}

std::string_view lifetimeName(Lifetime l) {
    switch (l) {
        case Lifetime::Transient: return "transient";
        case Lifetime::History: return "history";
        case Lifetime::Output: return "output";
    }
    return "?";
}

SceneFacts SceneFacts::of(const Scene& scene) {
    SceneFacts f;
    f.textured = anyTextured(scene);
    f.uvSet1 = anyUvSet1(scene);
    f.normalMapped = anyNormalMapped(scene);
    f.emissive = anyEmissive(scene);
    f.emissiveTextured = anyEmissiveTextured(scene);
    f.occlusionTextured = anyOcclusionTextured(scene);
    return f;
}

int ResourceDecl::channelCount() const {
    if (gbuffer) return std::popcount(gbuffer);
    return channels.empty() ? 1 : int(std::count(channels.begin(), channels.end(), ',')) + 1;
}

std::vector<std::string> ResourceDecl::channelNames() const {
    std::vector<std::string> out;
    if (gbuffer) {
        // (The frame's G-buffer layers are named as their planes; a group held elsewhere
        // prefixes its planes' names with its own.)
        const std::string prefix = group == LayerGroup::GBuffer ? "" : std::string(name) + ".";
        for (int i = 0; i < kGBufferPlaneCount; ++i)
            if (gbuffer & (1u << i))
                out.push_back(prefix + std::string(gbufferPlaneName(GBufferPlane(1u << i))));
        return out;
    }
    if (channels.empty()) return {std::string(name)};
    std::size_t at = 0;
    while (at <= channels.size()) {
        const std::size_t end = std::min(channels.find(',', at), channels.size());
        out.push_back(std::string(name) + "." + std::string(channels.substr(at, end - at)));
        at = end + 1;
    }
    return out;
}

Res resourceOfChannel(std::string_view channel) {
    static const std::vector<std::pair<std::string, Res>> channels = [] {
        std::vector<std::pair<std::string, Res>> all;
        for (int r = 0; r < kResourceCount; ++r)
            for (std::string& name : resourceDecl(Res(r)).channelNames())
                all.emplace_back(std::move(name), Res(r));
        return all;
    }();
    for (const auto& [name, id] : channels)
        if (name == channel) return id;
    return Res::Count;
}

std::string_view channelName(Res id, int i) {
    const std::vector<std::string>& names = allChannelNames()[std::size_t(id)];
    if (i < 0 || i >= int(names.size()))
        throw std::logic_error("resource '" + std::string(resourceDecl(id).name) +
                               "' has no channel " + std::to_string(i));
    return names[std::size_t(i)];
}

void checkChannelCount(Res id, int count) {
    if (count != resourceDecl(id).channelCount())
        throw std::logic_error("resource '" + std::string(resourceDecl(id).name) + "' has " +
                               std::to_string(resourceDecl(id).channelCount()) + " channels, not " +
                               std::to_string(count));
}

}  // namespace ssrt
