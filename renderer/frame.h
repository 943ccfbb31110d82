// What a frame is made of, and the history a sequence carries from one frame to the next.
//
// Its outputs are held by resource (PlaneStore: Frame::rgb, Frame::plane), but for the
// G-buffer and the direct pass's parts, typed groups of planes that list their planes once, in
// `table` (core/plane_table.h), because passes read them as one view. Every plane is named
// from the frame's resource table (renderer/resources.h), the only place a plane's name is
// spelled: it gives the EXR channel names (io/image_io.h) and Frame::plane(name). A resource the
// settings leave out (SSR off, no id planes) holds empty planes, and empty planes are not layers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/plane_pool.h"
#include "core/plane_table.h"
#include "denoise/denoise.h"
#include "raster/hiz.h"
#include "raster/raster.h"
#include "raster/raster_stats.h"
#include "raster/resolve_kernel.h"
#include "raster/shadow_map.h"
#include "renderer/in_use.h"
#include "renderer/plane_store.h"
#include "renderer/resources.h"
#include "trace/color_pyramid.h"
#include "trace/hit_proof.h"
#include "trace/march.h"
#include "trace/ray_gen.h"
#include "trace/ssr_resolve.h"
#include "trace/trace_layout.h"
#include "trace/trace_types.h"
#include "trace/world_rays.h"

namespace ssrt {

// A plane with its layer name and group.
struct PlaneRef {
    std::string_view name;
    const PlaneF* plane;
    LayerGroup group = LayerGroup::Color;
};

// The frame's G-buffer (core/gbuffer_view.h lists its planes and says what each holds), named
// as the resource table names its channels.
//
// Its material terms are per-pixel planes the texture pass writes when some material needs
// them, each empty (and no layer) otherwise: emission with emissive textures (every surface
// pixel's, the material's factor alone where it has no texture; 0 on background), which the
// direct pass reads instead of its per-material table; occlusion with occlusion textures (1
// where a material has none, and on background), which scales indirect light only
// (shading/direct_kernel.h, DirectArgs::occlusion). The instance and triangle ids, as floats,
// with RenderSettings::idPlanes.
struct GBuffer : PlaneTable<GBuffer>, GBufferPlanesF {
    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        forEachGBufferChannel("", g, kGAllPlanes, fn);
    }
    // Its planes as passes and kernels read them (every plane of one size, so one stride;
    // the view checks it); a freed plane is missing from it.
    GBufferView view() const;
};

// The direct pass's parts for the composite and the truth (shading/direct_kernel.h, DirectArgs
// says what each holds), scene-linear; and the light SSGI reads at its hits. Not file layers.
// f16 (IEEE binary16 bits, clamped to 65504: core/float_planes.h), half an f32's memory: they
// live from the direct pass to the composite, across SSR and the denoiser, where the frame's
// memory peaks; readers decode them (core/signal_lanes.h; FloatPlane::at).
struct DirectParts : PlaneTable<DirectParts> {
    PlaneU16 direct[3];
    PlaneU16 emission[3];    // only where some material emits (DirectArgs::anyEmissive)
    PlaneU16 envDiffuse[3];  // only without SSGI (whose light the composite reads instead)
    PlaneU16 envSpecular[3];
    PlaneU16 specWeight[3];
    PlaneU16 hitLight[3];  // DirectArgs::hitLight; only with SSGI (with its feedback, the
                           // reflected last frame's light too: DirectArgs::prevDiffuse)

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        forEachChannel(Res::Direct, g.direct, fn);
        forEachChannel(Res::Emission, g.emission, fn);
        forEachChannel(Res::EnvDiffuse, g.envDiffuse, fn);
        forEachChannel(Res::EnvSpecular, g.envSpecular, fn);
        forEachChannel(Res::SpecWeight, g.specWeight, fn);
        forEachChannel(Res::HitLight, g.hitLight, fn);
    }
};

// What a frame leaves the next one of a sequence. The caller owns it and hands it to every
// frame (Renderer::render); the renderer reads it, then commits the new frame's into it after
// the composite.
struct FrameHistory : PlaneTable<FrameHistory> {
    PlaneF color[3];  // the last frame's final colour (exposed), for reprojected SSR hits
    // The last frame's incoming diffuse radiance (scene-linear, before the diffuse colour:
    // what the composite multiplied by it), for SSGI hits with TraceSettings::ssgiFeedback;
    // empty without it.
    PlaneF diffuse[3];
    bool valid = false;      // a frame has committed colour (false: nothing to reproject)
    DenoiseHistory denoise;  // the denoiser's own (it says when it is usable)
    // The diffuse signal's, at half resolution, where SSGI traces at half (TraceLayout::Half):
    // it is denoised on the half frame and brought to full resolution after.
    DenoiseHistory denoiseHalf;
    // Mixed tracing's tile classifier, per signal (renderer/world_stage.h: MixedTileClassifier).
    MixedTiles mixedSsr, mixedSsgi;
    // Held by the render call reading and committing it: a second call at once is refused.
    InUse inUse;

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        forEachChannel(Res::HistoryColor, g.color, fn);
        forEachChannel(Res::HistoryDiffuse, g.diffuse, fn);
    }
    // Usable by a frame of this size.
    bool usableAt(int width, int height) const {
        return valid && color[0].width() == width && color[0].height() == height;
    }
    // Whether a frame of this size reads any of it: the colour, or the denoiser's own history
    // (which the default preset keeps without the colour; the half one at half the size).
    bool readableAt(int width, int height) const {
        return usableAt(width, height) || denoise.usableAt(width, height) ||
               denoiseHalf.usableAt((width + 1) / 2, (height + 1) / 2);
    }
};

// Wall-clock time of one pass, in milliseconds.
struct PassTime {
    std::string name;
    double ms = 0.0;
    // It ran in one loop over the tiles with the pass before it (the frame scheduler's chains,
    // renderer/frame_scheduler.h): each tile through that pass, then through this one.
    bool fused = false;
};

// What one screen-space pass did, over all its samples.
struct TraceStats {
    bool ran = false;
    int spp = 0;
    RayGenStats rays;
    MarchStats march;
    WorldRayStats world;  // mixed and world tracing (renderer/world_stage.h)
};

// What one resource group of a frame holds in memory, row padding included (`--stats`'s
// memory table; renderer/memory_use.h).
struct MemoryUse {
    std::string name;
    std::size_t bytes = 0;
};

struct FrameStats {
    std::vector<PassTime> passes;
    std::vector<MemoryUse> memory;  // after the frame: its groups, scratch and history
    // What the frame graph declares for the same frame (renderer/frame_graph.h, `ssrt graph`):
    // transient memory after reuse, outputs, history; at the declared formats, no padding.
    std::vector<MemoryUse> declared;
    TraceStats ssr, ssgi;
    RasterStats visibility;  // camera pass
    RasterStats shadow;      // light pass
    Isa isa = Isa::Scalar;
    int threads = 0;
};

struct Frame {
    int width = 0, height = 0;
    TraceCamera camera;  // the camera it was rendered from, as the trace passes see it
    uint32_t index = 0;  // the FrameInput::frameIndex it was rendered with
    // The image (Res::Color: linear radiance times the exposure; Res::Display: tone mapped,
    // sRGB encoded, in [0, 1]; Res::Shadow: the light's visibility, 0..1), what SSR and SSGI
    // hand out (Res::Ssr ... Res::SsgiSteps) and what the denoiser does (Res::DenoisedDiffuse
    // ... Res::SpecularFrames: the composite reads these in place of the traced signals, which
    // stay layers, undenoised); renderer/resources.cpp says what each holds.
    PlaneStore outputs = PlaneStore::frameOutputs();
    GBuffer gbuffer;
    DirectParts direct;  // only when a trace pass runs
    // Layers a caller adds after rendering (`ssrt compare`: the truth's), written after ours.
    std::vector<NamedPlane> extraLayers;
    FrameStats stats;
    // Held by the render call filling it: a second call at once is refused.
    InUse inUse;

    // Buffers the passes need but do not hand out; kept so that rendering into the same
    // Frame again reuses every allocation (no page faults, no clears).
    struct Scratch {
        // The planes of the groups below marked "pooled" while their pass is not running
        // (renderer/trace_pass.cpp): those groups are empty between frames; and the planes of
        // the frame's own groups outside their lifetimes (renderer/frame_memory.h).
        PlanePool pool;
        VisibilityBuffer visibility;
        // The back faces' raster and the depth layer made of it (raster/back_depth.h), when
        // the marchers use it (MarchSettings::backFaces); empty otherwise.
        VisibilityBuffer backVisibility;
        PlaneF backZ;
        ShadowMap shadow;
        // UV and its screen derivatives per set (raster/resolve_kernel.h: ResolveUv), for
        // textured scenes: set 0, and set 1 when read
        PlaneF uv[kResolveUvSets][kResolveUvOutputs];
        // The tangent frame (x, y, z, w) for normal maps (raster/resolve_kernel.h)
        PlaneF tangent[kResolveTangentOutputs];
        HiZPyramid hiz;
        ThinFeatures thin;  // mixed tracing's (trace/hit_proof.h)
        RayBatch rays;      // pooled
        MarchResult march;  // pooled
        ColorPyramid colorPyramid;
        SsrOutput
            ssr;  // pooled: the resolve's scratch; its colour and opacity are lent trace.ssr's
        DenoiseScratch denoise;  // pooled (by the denoiser: DenoiseInputs::pool)
        // SSGI's half-resolution trace (TraceLayout::Half): the chosen pixels' frame, its
        // depth pyramid, rays, march and resolved planes before the upsample.
        struct HalfTrace {
            HalfFrame frame;
            HiZPyramid hiz;
            ThinFeatures thin;  // mixed tracing's on the half frame (trace/hit_proof.h)
            RayBatch rays;
            MarchResult march;
            struct Resolved : PlaneTable<Resolved> {
                PlaneF color[3], hit, hitDistance, steps;

                template <class G, class Fn>
                static void table(G& g, Fn& fn) {
                    fn("half.ssgi.R", g.color[0]), fn("half.ssgi.G", g.color[1]);
                    fn("half.ssgi.B", g.color[2]), fn("half.ssgi.hit", g.hit);
                    fn("half.ssgi.hitDistance", g.hitDistance), fn("half.ssgiSteps", g.steps);
                }
            } resolved;
            // The diffuse signal denoised on the half frame (with the denoiser), before the
            // upsample, and its history lengths (debug planes).
            DenoiseScratch denoise;
            PlaneStore denoised{Res::HalfDenoised, Res::HalfDiffuseFrames};
        } half;

        // Every buffer above but the pool, once: fn(group, name, buffer), where `name` is the
        // plane's channel name in the resource table (renderer/resources.h) where it holds a
        // declared resource (a pyramid: its resource's first channel), `group` what `--stats`
        // calls the struct it lies in, and `buffer` a plane, a pyramid or a vector. The --stats
        // memory table counts the scratch by it (renderer/memory_use.h).
        template <class Fn>
        void forEachBuffer(Fn&& fn) const;
    } scratch;

    // Every plane of the frame's own groups (image, G-buffer, material, ids, direct parts,
    // traced signals, denoised), named from the resource table: fn(name, plane), PlaneF and
    // PlaneU16 planes. The one list of them: the file's layers (each an output's), the frame's
    // memory (renderer/frame_memory.h) and the --stats memory table walk it.
    template <class Fn>
    void forEachPlane(Fn&& fn) {
        forEachPlaneOf(*this, fn);
    }
    template <class Fn>
    void forEachPlane(Fn&& fn) const {
        forEachPlaneOf(*this, fn);
    }

    // An output's planes, one per channel, an RGB one's three, and one of its planes
    // (PlaneStore).
    PlaneF* planes(Res id) { return outputs.planes(id); }
    const PlaneF* planes(Res id) const { return outputs.planes(id); }
    std::span<PlaneF, 3> rgb(Res id) { return outputs.rgb(id); }
    std::span<const PlaneF, 3> rgb(Res id) const { return outputs.rgb(id); }
    PlaneF& plane(Res id, int channel = 0) { return outputs.plane(id, channel); }
    const PlaneF& plane(Res id, int channel = 0) const { return outputs.plane(id, channel); }
    ViewF view(Res id, int channel = 0) const { return outputs.view(id, channel); }

    // Every non-empty plane of image, gbuffer and trace, in that order, then
    // extraLayers: the file's layers, each with its LayerGroup.
    std::vector<PlaneRef> layers() const;
    // The layer called `name`; throws std::out_of_range if there is none.
    const PlaneF& plane(std::string_view name) const;
    bool has(std::string_view name) const;

private:
    template <class F, class Fn>
    static void forEachPlaneOf(F& f, Fn& fn) {
        f.outputs.forEachPlane(LayerGroup::Color, fn);
        f.gbuffer.forEachPlane(fn);
        f.direct.forEachPlane(fn);
        f.outputs.forEachPlane(LayerGroup::Trace, fn);
    }
};

template <class Fn>
void Frame::Scratch::forEachBuffer(Fn&& fn) const {
    const auto in = [&fn](std::string_view group, const auto& table, std::string_view prefix = "") {
        table.forEachPlane([&](std::string_view name, const auto& p) {
            fn(group, prefix.empty() ? std::string(name) : std::string(prefix) + std::string(name),
               p);
        });
    };
    fn("visibility buffer", "visibility.depth", visibility.depth);
    fn("visibility buffer", "visibility.ids", visibility.ids);
    fn("back faces", "back.depth", backVisibility.depth);
    fn("back faces", "back.ids", backVisibility.ids);
    fn("back faces", "backZ", backZ);
    fn("shadow map", "shadowMap", shadow.depth);
    for (int set = 0; set < kResolveUvSets; ++set)
        for (int i = 0; i < kResolveUvOutputs; ++i)
            fn("uv", channelName(set == 0 ? Res::Uv0 : Res::Uv1, i), uv[set][i]);
    for (int i = 0; i < kResolveTangentOutputs; ++i)
        fn("tangent", channelName(Res::Tangent, i), tangent[i]);
    fn("hi-z", "hiz.minZ", hiz);
    for (std::size_t l = 0; l < thin.levels.size(); ++l)
        fn("thin features", "thinFeatures." + std::to_string(l), thin.levels[l]);
    in("rays", rays);
    in("march", march);
    fn("colour pyramid", "colorPyramid.R", colorPyramid);
    in("ssr resolve", ssr);
    in("denoise scratch", denoise);
    in("half frame", half.frame);
    fn("half hi-z", "half.hiz.minZ", half.hiz);
    in("half rays", half.rays, "half.");
    in("half march", half.march, "half.");
    in("half resolved", half.resolved);
    in("half denoise scratch", half.denoise, "half.");
    in("half denoised", half.denoised);
}

}  // namespace ssrt
