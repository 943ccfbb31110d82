// The screen-space passes of a frame, after the G-buffer and the direct light: Hi-Z, then
// per sample ray generation, march and resolve for SSR and SSGI, then the composite that
// replaces the direct pass's image.
#pragma once

#include "renderer/frame.h"
#include "renderer/frame_graph.h"
#include "renderer/frame_memory.h"
#include "renderer/pass_reads.h"
#include "renderer/renderer.h"
#include "renderer/resolve_tables.h"
#include "renderer/settings.h"
#include "shading/direct_kernel.h"
#include "trace/reconstruct.h"

namespace ssrt {

// What the screen-space passes of one frame share: what the renderer hands them, and the
// camera, back-face layer and depth pyramid they read as they go. (Each pass takes the
// G-buffer's view, GBuffer::view, as it starts: the frame's memory frees a plane after its last
// reader, and a freed plane is then missing from the view, never a stale row.)
struct TraceContext {
    const RenderSettings& settings;
    const CompiledGraph& graph;  // which passes run (renderer/frame_graph.h)
    FrameMemory& memory;         // takes and gives back the frame's planes around each pass
    Isa isa;
    uint32_t frameIndex;
    // The direct pass's lighting alone (DirectLighting::light: sun, sky, emission table; no
    // plane of the frame).
    const DirectArgs& lighting;
    const FrameHistory* history;  // the last frame's colour, usable at this size; null: none
    // The sequence's history for the denoiser, which reads and replaces its own part
    // (DenoiseHistory); null: no history (each pixel starts afresh, nothing is kept).
    FrameHistory* sequence;
    bool resetHistory;                // a cut: the denoiser's history is not read
    bool replaceHistory;              // false: the denoiser reads its history, leaves it as it was
    const TraceObserver* observer;    // optional: sees each sample's rays and march result
    const std::atomic<bool>* cancel;  // optional: read before each pass (render_cancel.h)
    const WorldRays* world;           // the scene's world rays (FrameInput::world), or null
    // What the proof of a march hit reads (mixed tracing, trace/hit_proof.h): the G-buffer
    // resolve's triangles and view-space vertices, and per instance whether its material cuts
    // out (null: no proof).
    const ResolveTables* tables = nullptr;
    const std::vector<uint8_t>* cutOut = nullptr;
    // Set by runTracePasses from the frame:
    TraceCamera camera{};           // the frame's, as the kernels take it
    const PlaneF* backZ = nullptr;  // the march's back-face layer (trace/march.h); null: none
    const HiZPyramid* hiz = nullptr;

    const TraceSettings& ts() const { return settings.trace; }
    int threads() const { return settings.threads; }
    // A plane only made to be looked at (RenderSettings::debugPlanes): null when not asked for.
    PlaneF* debugPlane(PlaneF& p) const { return settings.debugPlanes ? &p : nullptr; }
    // What the reconstruction of a layout's untraced pixels (or the half frame's upsample) in
    // `pass` is guided by: the G-buffer's planes the pass declares reading.
    ReconstructGuides guides(const Frame& f, std::string_view pass) const {
        return {camera, PassReads(graph, f, pass).gbuffer()};
    }
};

// How `pass`'s rays are answered (TraceSettings::ssrTrace, ssgiTrace).
inline TraceMode traceMode(const TraceContext& c, TracePass pass) {
    return pass == TracePass::Ssr ? c.ts().ssrTrace : c.ts().ssgiTrace;
}

// Fills SSR's, SSGI's and the denoiser's outputs (Res::Ssr ... Res::SpecularFrames) and replaces
// the image's colour and display (Res::Color, Res::Display) with the composite; appends pass
// times and stats to frame.stats.
void runTracePasses(TraceContext c, Frame& frame);

// Whether the half-resolution diffuse, once denoised, is brought to the frame tile by tile
// inside the composite, which alone reads it, instead of into the frame's planes
// (Res::DenoisedDiffuse, then not made): unless a file shows them (debugPlanes)
// or the next frame's SSGI feedback reads them.
bool diffuseUpsampledInComposite(const RenderSettings& settings);

// Whether the direct pass writes SSGI's hit light at half resolution, straight into the half
// frame (DirectArgs::hitLightHalf), instead of a full-resolution plane buildHalfFrame copies
// from (frame.direct.hitLight, then not made): SSGI traced on the half frame, without the
// feedback that adds to the full-resolution plane, and without a file to show it.
bool hitLightAtHalf(const RenderSettings& settings);

// Whether the traced signals the denoiser reads (SSR's and SSGI's outputs, the half frame's
// SSGI) come from the pool and go back to it once the denoiser's front end has read them, for
// its later passes to reuse: with the denoiser on (the composite then reads its output
// instead) and no file to show them.
bool tracedSignalsPooled(const RenderSettings& settings);

// Whether the next frame reads what this one commits (SSR hits with HitRadiance::Reprojected,
// SSGI with ssgiFeedback). The denoiser's history is its own (denoise/denoise.h).
bool readsHistory(const TraceSettings& settings);
// The frame's final colour into `history` and, with SSGI feedback, its incoming diffuse
// radiance, for the next frame.
void commitHistory(const CompiledGraph& graph, const Frame& frame, FrameHistory& history);

}  // namespace ssrt
