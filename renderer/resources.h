// The frame's resources: one table, in Res order, of every resource a frame may hold, each
// with its name (its EXR layer: the channels' names are the layer's and a suffix), the format
// its channels are stored in, where its texels lie, how long it lives and, for an output, its
// part of a file. The frame's plane groups (renderer/frame.h) name their planes from here; the
// frame graph (renderer/frame_graph.h) declares the passes over them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/gbuffer_view.h"
#include "core/pixel_formats.h"
#include "renderer/settings.h"
#include "scenes/scene.h"

namespace ssrt {

// Which part of the frame a file layer belongs to, for choosing what a file holds (`ssrt
// render --layers`, renderer/layer_groups.h).
enum class LayerGroup : uint8_t {
    Color,    // colour, display, shadow
    GBuffer,  // the G-buffer, the material planes, the ids
    Trace,    // SSR, SSGI, the denoiser's
    Truth,    // `ssrt compare`'s: the ray checks, and Frame::extraLayers (the reference)
};
inline constexpr int kLayerGroupCount = 4;

// Where a resource's texels lie: the frame's pixels, the half frame's (one per 2x2 block),
// the shadow map's (RenderSettings::shadowMapSize squared), a pyramid over the frame's or
// the half frame's pixels (that size, then each level halved down to one texel: the Hi-Z and
// colour pyramids), or a tile chain's ring (trace/tile_chain.h: kChainRingTileRows tile rows
// of the frame's width, the frame's height where that is less; the frame's on the truth's
// stage-by-stage path).
enum class Resolution : uint8_t { Full, Half, ShadowMap, Pyramid, HalfPyramid, TileRing };
// "full", "half", "shadow map", "pyramid", "half pyramid", "tile ring"
std::string_view resolutionName(Resolution r);

// How long a resource lives: within the frame (its memory reused once its last pass has run),
// across frames (the caller's FrameHistory, exchanged each frame), or handed out in the Frame.
enum class Lifetime : uint8_t { Transient, History, Output };
std::string_view lifetimeName(Lifetime l);  // "transient", "history", "output"

// The facts of a scene that decide which passes and resources a frame has.
struct SceneFacts {
    bool textured = false;           // some material has a texture: UVs are resolved
    bool uvSet1 = false;             // a texture reads TEXCOORD_1
    bool normalMapped = false;       // the tangent frame is resolved
    bool emissive = false;           // something emits
    bool emissiveTextured = false;   // an emissive texture: per-pixel emission
    bool occlusionTextured = false;  // an occlusion texture: per-pixel occlusion
    static SceneFacts of(const Scene& scene);
};

// What a graph is compiled for.
struct GraphKey {
    RenderSettings settings;
    SceneFacts scene;
    // The last frame's history is read (FrameHistory::readableAt: its colour or the
    // denoiser's, at this size; no cut).
    bool history = true;
    // This frame's history is kept for the next (FrameInput::replaceHistory with a history
    // given). Both false: a single image.
    bool keepHistory = true;
    // Where `history` holds, which of the last frame's own parts it has at this size: its
    // colour (FrameHistory::usableAt), its diffuse light (with SSGI's feedback). A history
    // carried from a frame of other settings may hold the denoiser's alone.
    bool lastColor = true, lastDiffuse = true;
};

using GraphCondition = bool (*)(const GraphKey&);

// The resources, one per layer (a layer's channels share a name, format and lifetime).
enum class Res : uint8_t {
    // Colour (file layers)
    Color,
    Display,
    Shadow,
    // G-buffer (file layers)
    ViewZ,
    Normal,
    Albedo,
    Metallic,
    Roughness,
    MaterialId,
    Motion,
    Emissive,
    Occlusion,
    InstanceId,
    TriangleId,
    // Traced signals and the denoiser's outputs (file layers)
    Ssr,
    SsrOpacity,
    SsrHit,
    SsrHitDistance,
    SsrSteps,
    Ssgi,
    SsgiHit,
    SsgiHitDistance,
    SsgiSteps,
    DenoisedDiffuse,
    DenoisedSpecular,
    DiffuseFrames,
    SpecularFrames,
    SsrCheck,
    SsgiCheck,
    // Raster
    ShadowMap,
    VisibilityDepth,
    VisibilityIds,
    BackDepth,
    BackIds,
    BackZ,
    Uv0,
    Uv1,
    Tangent,
    // The direct pass's parts
    Direct,
    Emission,
    EnvDiffuse,
    EnvSpecular,
    SpecWeight,
    HitLight,
    // Tracing
    HiZ,
    HiZPacked,
    ThinFeatures,  // mixed tracing's thin-feature check (trace/hit_proof.h)
    ColorPyramid,
    RayPdf,
    MarchHit,
    SsrHitRadiance,
    SsrHitTarget,
    // SSGI's half frame (TraceLayout::Half)
    HalfGBuffer,
    HalfHitLight,
    HalfBackZ,
    HalfIds,
    HalfThinFeatures,
    HalfGuides,
    HalfHiZ,
    HalfRayPdf,
    HalfSsgi,
    HalfSsgiSteps,
    // The denoiser's scratch: at full resolution, and on the half frame for the diffuse
    DenoiseNoisyDiffuse,
    DenoiseNoisySpecular,
    DenoisePreBlurredDiffuse,
    DenoisePreBlurredSpecular,
    DenoiseTemporalDiffuse,
    DenoiseTemporalSpecular,
    DenoiseFixedDiffuse,
    DenoiseFixedSpecular,
    DenoiseBlurredDiffuse,
    DenoiseBlurredSpecular,
    DenoiseDiffuseState,
    DenoiseSpecularState,
    DenoiseDiffuseFast,
    DenoiseSpecularFast,
    HalfDenoiseNoisy,
    HalfDenoisePreBlurred,
    HalfDenoiseTemporal,
    HalfDenoiseFixed,
    HalfDenoiseBlurred,
    HalfDenoiseState,
    HalfDenoiseFast,
    HalfDenoised,
    HalfDiffuseFrames,
    // History (FrameHistory)
    HistoryColor,
    HistoryDiffuse,
    DenoiseHistoryGuides,
    DenoiseHistoryDiffuse,
    DenoiseHistorySpecular,
    DenoiseHistoryDiffuseFrames,
    DenoiseHistorySpecularFrames,
    DenoiseHistoryDiffuseFast,
    DenoiseHistorySpecularFast,
    HalfDenoiseHistory,
    HalfDenoiseHistorySignal,
    HalfDenoiseHistoryFast,
    Count
};
inline constexpr int kResourceCount = int(Res::Count);

struct ResourceDecl {
    Res id;
    std::string_view name;      // the layer's name: "normal" (channels normal.X, ...)
    std::string_view channels;  // comma-separated channel suffixes ("X,Y,Z"); "" for one
    PixelFormat format;         // how each channel is stored (core/pixel_formats.h)
    Resolution resolution;
    Lifetime lifetime;
    LayerGroup group = LayerGroup::Color;  // outputs only: which part of a file
    // An output that exists only to be looked at: handed out when this holds, and otherwise
    // transient (gone when no later pass reads it). Null: always handed out.
    GraphCondition handedOut = nullptr;
    // G-buffer planes (core/gbuffer_view.h names them), `channels` then empty: the channels
    // are the planes' names in the G-buffer's order, for a layer of the frame's G-buffer (group
    // GBuffer: "normal.X", ...), and after the resource's name for a group of planes held
    // elsewhere ("half.guide.normal.X").
    GBufferPlanes gbuffer = 0;
    int channelCount() const;
    // The file's channel names ("normal.X", ...; "viewZ" for one channel).
    std::vector<std::string> channelNames() const;
};

// (Throws std::logic_error unless `count` is the resource's channel count.)
void checkChannelCount(Res id, int count);

// The table, in Res order.
const ResourceDecl& resourceDecl(Res id);
// The resource one of whose channels is called `channel` ("normal.X": Res::Normal), as the
// Frame's plane tables name their planes (renderer/frame.h); Res::Count if none is.
Res resourceOfChannel(std::string_view channel);
// The name of a resource's channel `i` ("normal.X" for Res::Normal, 0; "viewZ" for Res::ViewZ):
// the one spelling of a plane's name, which the Frame's plane tables use.
std::string_view channelName(Res id, int i = 0);
// Calls fn(channelName(id, i), planes[i]) for each of a resource's channels (a PlaneTable's
// table; std::logic_error when the array is not one plane per channel).
template <class P, std::size_t N, class Fn>
void forEachChannel(Res id, P (&planes)[N], Fn& fn) {
    checkChannelCount(id, int(N));
    for (std::size_t i = 0; i < N; ++i) fn(channelName(id, int(i)), planes[i]);
}

}  // namespace ssrt
