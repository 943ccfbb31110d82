// The denoiser's per-ISA kernels (denoise/*_kernel.cpp, a file a pass, each compiled once per
// ISA) and their argument blocks; denoise/denoise.cpp fills them and runs them per tile.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"
#include "core/float_planes.h"
#include "denoise/reblur_math.h"

namespace ssrt {

// The frame as every pass sees it: its size, camera and guides (planes of one stride).
struct ReblurView {
    int width = 0, height = 0, tilesX = 0;
    std::size_t stride = 0;
    float tanHalfX = 1.0f, tanHalfY = 1.0f;
    float viewToWorld[9] = {};
    float frustum = 1.0f;  // the frustum's short side at view depth 1 (NRD's GetFrustumSize)
    const float* viewZ = nullptr;
    const float* normal[3] = {};
    const float* roughness = nullptr;
    // The view depth where the diffuse / specular signal exists, else 0: one read says both.
    const float* signalZ[2] = {};
    const uint8_t* tiles = nullptr;  // per tile: bit 0 diffuse, bit 1 specular signal
    reblur::HitDistanceScale hitScale{};
};

inline constexpr uint8_t kTileDiffuse = 1, kTileSpecular = 2;

// Signal planes (radiance, normalised hit distance, fast luma) as a pass reads and writes them
// (SignalIn, SignalOut, and for radiance with hit distance SignalIn4, SignalOut4:
// core/float_planes.h): the denoiser keeps its own in f16, radiance and hit distance as f16x4
// (a pixel's four values in one 64-bit element: a tap is one gather), decoded on load, the
// arithmetic in f32; a caller may hand a plane per channel, f32 or f16 (the tests' walls).
// Their stride is the view's.

struct ReblurFrontEndArgs {
    ReblurView view;
    const float* diffuse[3] = {};  // null: no diffuse signal
    const float* diffuseHit = nullptr;
    const float* albedo[3] = {};
    const float* metallic = nullptr;
    const float* ssr[3] = {};  // null: no specular signal
    const float* ssrOpacity = nullptr;
    SignalIn envSpecular[3] = {};  // f32 or f16 (the direct pass's)
    const float* specularHit = nullptr;
    float specularMaxRoughness = 1.0f;
    // RGB and the normalised hit distance of each signal given.
    SignalOut4 noisyDiffuse;
    SignalOut4 noisySpecular;
    float* signalZ[2] = {};
    uint8_t* tiles = nullptr;
};

enum class ReblurSpatial { PreBlur, Blur, PostBlur };

struct ReblurSpatialArgs {
    ReblurView view;
    ReblurSpatial pass = ReblurSpatial::PreBlur;
    bool specular = false;
    SignalIn4 in;
    SignalOut4 out;                 // a channel null: not written (the post-blur's hit distance)
    SignalOut4 copy;                // a second destination (the history), or none
    const float* frames = nullptr;  // accumulation speed (blur, post-blur); null: noFrames
    float noFrames = 10.0f;         // every pixel's speed without `frames`: the pre-blur's 10, or 0
    uint32_t frameIndex = 0, stream = 0;  // the per-pixel rotation's counters
    float radius = 30.0f;                 // pre-blur's radius, or the blur's largest
    float minRadius = 1.0f;
    float maxFrames = 1.0e9f;       // pixels with this many frames of history or more are copied
    float lobeFraction2 = 0.0225f;  // lobeAngleFraction squared
    float roughnessFraction = 0.15f;
    float planeDistance = 0.02f;
    float minHitWeight = 0.1f;
    float fractionScale = 1.0f;  // 2 pre-blur (looser), 1 blur, 0.5 post-blur (stricter)
};

struct ReblurTemporalArgs {
    ReblurView view;
    bool specular = false;
    const float* motion[2] = {};
    SignalIn4 in;
    // The previous frame's (all null: no history).
    const float* prevViewZ = nullptr;
    const float* prevNormal[3] = {};
    const float* prevRoughness = nullptr;
    SignalIn4 prevSignal;
    const float* prevFrames = nullptr;  // accumulation speed + 1 (REBLUR's internal data)
    SignalIn prevFast;
    float prevViewToWorld[9] = {};
    float prevTanHalfX = 1.0f, prevTanHalfY = 1.0f;
    float cameraDelta[3] = {};  // this camera's position minus the previous one's
    float maxFrames = 30.0f, maxFastFrames = 6.0f;
    float disocclusion = 0.01f;
    float fireflyScale = 2.0f;
    bool virtualMotion = true;
    SignalOut4 out;
    float* outFrames = nullptr;
    SignalOut outFast;
};

struct ReblurHistoryFixArgs {
    ReblurView view;
    bool specular = false;
    SignalIn4 in;
    const float* frames = nullptr;  // null: no pixel has a history (0 frames)
    SignalIn fast;                  // null: no anti-lag clamp, unless fastIsInputLuma
    // The fast history is the input's own luma (a frame without history, where the temporal
    // pass, which would have written it so, does not run).
    bool fastIsInputLuma = false;
    SignalOut4 out;
    float fixFrames = 3.0f, stride = 14.0f;
    float lobeFraction2 = 0.0225f;
    float planeDistance = 0.02f;
};

SSRT_DECLARE_KERNEL(void, reblurFrontEndTile, (const ReblurFrontEndArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, reblurSpatialTile, (const ReblurSpatialArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, reblurTemporalTile, (const ReblurTemporalArgs& args, int tile))
SSRT_DECLARE_KERNEL(void, reblurHistoryFixTile, (const ReblurHistoryFixArgs& args, int tile))

}  // namespace ssrt
