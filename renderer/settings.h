// The renderer's settings: plain structs with defaults, immutable once a Renderer holds them.
#pragma once

#include <cstdint>
#include <optional>

#include "core/isa.h"
#include "denoise/denoise_settings.h"
#include "trace/march.h"
#include "trace/ray_gen.h"
#include "trace/ssr_resolve.h"
#include "trace/trace_layout.h"
#include "trace/trace_types.h"
#include "trace/world_rays.h"

namespace ssrt {

// The screen-space passes: specular reflections (SSR) and one-bounce diffuse (SSGI), each
// `spp` rays per pixel marched through the depth buffer, resolved, and composited over the
// direct light. With both off the frame is the direct pass alone (as before issue 5).
struct TraceSettings {
    bool ssr = true;
    bool ssgi = true;
    SsrMethod ssrMethod = SsrMethod::VndfBounded;  // how SSR rays sample the GGX lobe
    Marcher marcher = Marcher::HiZ;                // used by both passes
    int ssrSpp = 1;                                // rays per pixel, 1 to kMaxSpp
    int ssgiSpp = 1;
    MarchSettings march;         // its frame and sample are set per pass by the renderer
    SsrResolveSettings resolve;  // hit radiance source, fades, mip or ray-reuse mode
    // Rays also where the composite hides what they find: SSR where the roughness fade
    // does (perceptual roughness >= resolve.roughnessFadeEnd: SSR opacity 0), as HDRP does
    // not, and SSGI where the diffuse colour albedo (1 - metallic) is 0 (metals). Off: no
    // ray there (RayGenStats::hidden); the composite is the same at those pixels (the
    // passes' outputs being finite), and only the SSR reuse resolve of a smoother neighbour
    // misses their rays.
    bool traceHidden = false;
    // Multi-bounce diffuse (issue 17): an SSGI hit also sends on the light it received the
    // frame before, its diffuse colour times the previous frame's incoming diffuse radiance
    // at the hit (FrameHistory::diffuse, reprojected), so every frame of a sequence adds one
    // bounce. Off (and on a sequence's first frame, after a reset or a size change): one
    // bounce, as trace/ssgi.h describes.
    bool ssgiFeedback = false;
    // Which pixels get rays (trace/trace_layout.h): every one (full), half of them in a
    // checkerboard that alternates per frame, SSR and SSGI on opposite phases, or (SSGI only)
    // one per 2x2 block on a half-resolution frame. The others are reconstructed from the
    // traced ones (trace/reconstruct.h) before anything reads the planes.
    // The defaults are the default quality preset's (renderer/quality.h: medium).
    TraceLayout ssrLayout = TraceLayout::Checkerboard;
    // How each signal's rays are answered (trace/world_rays.h): mixed and world need world
    // rays (FrameInput::world).
    TraceMode ssrTrace = TraceMode::Screen;
    TraceMode ssgiTrace = TraceMode::Screen;
    TraceLayout ssgiLayout = TraceLayout::Half;
    // SSR's checkerboard thinned where the denoiser needs fewer new rays: a pixel with at least
    // this many frames of specular history (the last frame's, found through the motion
    // vectors) gets a ray every fourth frame instead of every second, its 2x2 block keeping one
    // traced pixel a frame (trace/trace_layout.h, sparseBlockPick). kSparseOff: never.
    static constexpr int kSparseOff = 64;
    int ssrSparseFrames = kSparseOff;
    DenoiseSettings denoise;  // REBLUR over both signals (denoise/denoise.h)

    static constexpr int kMaxSpp = 64;
    bool any() const { return ssr || ssgi; }
    // Whether a signal is answered in world space (mixed or world): the frame needs world rays.
    bool worldRays() const {
        return (ssr && ssrTrace != TraceMode::Screen) || (ssgi && ssgiTrace != TraceMode::Screen);
    }
    void validate() const;  // throws std::invalid_argument naming the field
};

struct RenderSettings {
    int width = 1280;
    int height = 720;
    int threads = 0;               // worker threads; 0 = every core
    std::optional<Isa> isa;        // nullopt: best the CPU runs (or $SSRT_ISA)
    int shadowMapSize = 2048;      // texels per side
    float shadowBias = 0.1f;       // texels of depth the map may lie off the receiver's plane
    float shadowSlopeBias = 1.0f;  // more per unit of tan(angle to the light) (shading/
                                   // direct_lanes.h, shade::shadowVisibility)
    int pcfRadius = 1;             // PCF kernel is (2r+1)^2 texels
    float exposure = 1.0f;         // scale on linear radiance before the tone map
    bool idPlanes = true;          // also hand out instanceId and triangleId float planes
    // Hand out the G-buffer and material planes, and the traced and denoised planes, in the
    // Frame (file layers; with tracePlanes also the direct pass's parts, Frame::direct, which
    // the truth reads). Off (`ssrt render` to a PNG): each is transient, its memory reused
    // once its last pass has read it, and every other plane keeps its bits.
    bool gbufferPlanes = true;
    bool tracePlanes = true;
    // Also make the planes that only a file or a person reads (renderer/frame.h says which):
    // the march steps, the undenoised full-resolution SSGI where the diffuse is denoised at
    // half resolution, the denoiser's history lengths. Off (`ssrt render` to a PNG): not made,
    // and every other plane keeps its bits.
    bool debugPlanes = true;  // (a trace plane: none without tracePlanes)
    TraceSettings trace;      // SSR and SSGI (on by default)

    // Throws std::invalid_argument with a one-line message naming the bad field.
    void validate() const;
};

inline constexpr int kMaxImageSize = 8192;  // per side; the fixed-point budget in raster/

}  // namespace ssrt
