// The denoiser's per-ISA kernels (denoise/*_kernel.cpp, a file a pass, each compiled once per
// ISA) and their argument block; denoise/denoise.cpp fills them and runs them per tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "core/dispatch.h"
#include "core/float_planes.h"
#include "core/gbuffer_view.h"
#include "core/plane_view.h"
#include "denoise/reblur_math.h"

namespace ssrt {

// The frame as every pass sees it, one block shared by all four kernels (NRD's constant buffer of
// CommonSettings and ReblurSettings): the guides (the G-buffer's view, which carries the frame's
// size and the one stride of every plane here; albedo and metallic for the front end, motion for
// the temporal pass), the camera, the previous frame's camera and guides, the front end's
// classification and the tuning. Filled once per frame; a pass adds only its signals
// (ReblurPassArgs).
struct ReblurFrame : GBufferView {
    int tilesX = 0;
    float tanHalfX = 1.0f, tanHalfY = 1.0f;
    float viewToWorld[9] = {};
    float frustum = 1.0f;  // the frustum's short side at view depth 1 (NRD's GetFrustumSize)
    reblur::HitDistanceScale hitScale{};
    uint32_t frameIndex = 0;  // the spatial passes' per-pixel rotation's counter
    // The view depth where the diffuse / specular signal exists, else 0: one read says both.
    const float* signalZ[2] = {};
    const uint8_t* tiles = nullptr;  // per tile: bit 0 diffuse, bit 1 specular signal
    // The previous frame's guides and camera (null: none; the temporal pass reads them).
    GBufferOf<const float*> prev;  // viewZ, normal; roughness with the specular
    float prevViewToWorld[9] = {};
    float prevTanHalfX = 1.0f, prevTanHalfY = 1.0f;
    float cameraDelta[3] = {};  // this camera's position minus the previous one's
    // Tuning (DenoiseSettings, denoise/denoise_settings.h, as the kernels read it).
    float specularMaxRoughness = 1.0f;  // rougher pixels have no specular signal
    float minBlurRadius = 1.0f;
    float lobeFraction2 = 0.0225f;  // lobeAngleFraction squared
    float roughnessFraction = 0.15f;
    float planeDistance = 0.02f;
    float minHitWeight = 0.1f;
    float maxAccumulatedFrames = 30.0f, maxFastAccumulatedFrames = 6.0f;
    float disocclusion = 0.01f;
    float fireflyScale = 2.0f;
    bool virtualMotion = true;
    float historyFixFrames = 3.0f, historyFixStride = 14.0f;
};

inline constexpr uint8_t kTileDiffuse = 1, kTileSpecular = 2;

enum class ReblurSpatial { PreBlur, Blur, PostBlur };

// Signal planes (radiance, normalised hit distance, fast luma) as a pass reads and writes them
// (SignalIn, SignalOut, and for radiance with hit distance SignalIn4, SignalOut4:
// core/float_planes.h): the denoiser keeps its own in f16, radiance and hit distance as f16x4
// (a pixel's four values in one 64-bit element: a tap is one gather), decoded on load, the
// arithmetic in f32; a caller may hand a plane per channel, f32 or f16 (the tests' walls).
// Their stride is the frame's.

// The traced signals the denoiser reads, views of the frame's size: what a caller hands it
// (DenoiseCall), and as they are what the front end's kernel reads. A signal whose first view
// is absent is not traced.
struct DenoiseSignals {
    // Diffuse (absent: no SSGI): incoming radiance and the mean hit distance (0: no hit).
    ViewF diffuse[3], diffuseHitDistance;
    // Specular (absent: no SSR): the composite's incoming specular radiance is
    // opacity ssr + (1 - opacity) environment; the mean hit distance (0: no hit).
    ViewF ssr[3], ssrOpacity;
    FloatView envSpecular[3];  // f32 or f16 (the direct pass's)
    ViewF specularHitDistance;
    bool hasDiffuse() const { return bool(diffuse[0]); }
    bool hasSpecular() const { return bool(ssr[0]); }
};

// One pass over one signal: the frame, and the planes that pass reads and writes (each pass
// sets its own fields below; the rest stay empty).
struct ReblurPassArgs {
    ReblurFrame frame;
    bool specular = false;  // the signal (front end: both)
    SignalIn4 in;           // the previous pass's result
    SignalOut4 out;         // a channel null: not written (the post-blur's hit distance)

    // Front end: the traced signals (DenoiseSignals, as the caller gave them) and what it writes.
    DenoiseSignals signals;
    SignalOut4 noisyDiffuse, noisySpecular;  // RGB and the normalised hit distance
    float* signalZ[2] = {};
    uint8_t* tiles = nullptr;

    // Spatial passes (pre-blur, blur, post-blur).
    ReblurSpatial pass = ReblurSpatial::PreBlur;
    SignalOut4 copy;                // a second destination (the history), or none
    const float* frames = nullptr;  // accumulation speed (blur, post-blur, history fix); null:
                                    // noFrames (history fix: 0)
    float noFrames = 10.0f;         // every pixel's speed without `frames`: the pre-blur's 10, or 0
    uint32_t stream = 0;            // the per-pixel rotation's stream
    float radius = 30.0f;           // pre-blur's radius, or the blur's largest
    float maxFrames = 1.0e9f;       // pixels with this many frames of history or more are copied
    SignalIn steadyFast;            // post-blur: only where the luma is near this fast history
    float fractionScale = 1.0f;     // 2 pre-blur (looser), 1 blur, 0.5 post-blur (stricter)

    // Temporal: the previous frame's signal (all null: no history) and what it writes.
    SignalIn4 prevSignal;
    const float* prevFrames = nullptr;  // accumulation speed + 1 (REBLUR's internal data)
    SignalIn prevFast;
    float* outFrames = nullptr;
    SignalOut outFast;

    // History fix: the fast history (null: no anti-lag clamp, unless fastIsInputLuma).
    SignalIn fast;
    // The fast history is the input's own luma (a frame without history, where the temporal
    // pass, which would have written it so, does not run).
    bool fastIsInputLuma = false;
};

// (They cross into code compiled once per ISA: plain data, copied as bytes.)
static_assert(std::is_trivially_copyable_v<ReblurFrame> &&
              std::is_trivially_copyable_v<ReblurPassArgs>);

SSRT_DECLARE_KERNEL(void, reblurFrontEndTile, (const ReblurPassArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, reblurSpatialTile, (const ReblurPassArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, reblurTemporalTile, (const ReblurPassArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, reblurHistoryFixTile, (const ReblurPassArgs& args, int tile))

}  // namespace ssrt
