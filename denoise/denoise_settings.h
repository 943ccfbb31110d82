// The denoiser's settings: NVIDIA NRD's REBLUR (ReblurSettings, NRD v4.14) restated for ssrt,
// with its defaults. The seed that walks REBLUR pass by pass: shared/seeds/003. Each field's
// range and help live once, in denoise/denoise_fields.h.
#pragma once

namespace ssrt {

struct DenoiseSettings {
    bool enabled = true;  // off: the composite reads the traced signals as they are
    // Temporal accumulation: frames averaged at most (the history's length), and the fast
    // history's (REBLUR's maxAccumulatedFrameNum, maxFastAccumulatedFrameNum).
    int maxAccumulatedFrames = 30;
    int maxFastAccumulatedFrames = 6;
    // History fix: pixels younger than this many frames get a wider reconstruction
    // (historyFixFrameNum), with taps this many pixels apart at age 0 (historyFixBasePixelStride).
    int historyFixFrames = 3;
    int historyFixStride = 14;
    // Spatial radii in pixels (diffusePrepassBlurRadius, specularPrepassBlurRadius,
    // minBlurRadius, maxBlurRadius). No pre-blur by default (the default preset's, issue 18:
    // no error cost on cornell, a quarter of the denoiser's time); NRD's are 30 and 50.
    float diffusePrepassRadius = 0.0f;
    float specularPrepassRadius = 0.0f;
    float minBlurRadius = 1.0f;
    float maxBlurRadius = 30.0f;
    // Pixels with at least this many frames of history skip the blur and get the post-blur
    // only (ssrt's; NRD blurs every pixel twice): the history's own averaging has already
    // done the first pass's work (flicker rises: 0.0025 against 0.0017 on cornell). 64: every
    // pixel is blurred twice, as NRD.
    int blurMaxFrames = 4;
    // Pixels with at least this many frames of history whose signal did not change (the
    // pixel's luma near its fast history's: kSteadyLuma, denoise/spatial_kernel.cpp) skip the
    // post-blur too: the accumulation alone stands for both spatial passes there (ssrt's;
    // flicker rises 7-39 % on the built-in scenes at 8, so only the low preset). 64: every
    // pixel gets the post-blur, as NRD.
    int postBlurMaxFrames = 64;
    // Edge-stopping: the normal lobe fraction, the roughness fraction, the plane distance as
    // a fraction of the frustum's height at the pixel's depth, the floor of the hit-distance
    // weight (lobeAngleFraction, roughnessFraction, planeDistanceSensitivity,
    // minHitDistanceWeight).
    float lobeAngleFraction = 0.15f;
    float roughnessFraction = 0.15f;
    float planeDistanceSensitivity = 0.02f;
    float minHitDistanceWeight = 0.1f;
    // Reprojection: a history tap is occluded when its depth differs from the expected one
    // by more than this fraction of the frustum's height (CommonSettings::disocclusionThreshold).
    float disocclusionThreshold = 0.01f;
    // The firefly suppressor's least allowed ratio to the history's luma
    // (fireflySuppressorMinRelativeScale).
    float fireflyMinRelativeScale = 2.0f;
    // Hit-distance normalisation f(z, r) = (A + B z) lerp(1, C, 2^(D r^2)) (REBLUR's
    // hitDistanceParameters); A in scene bounding-box diagonals, where NRD has metres, so the
    // denoiser has no absolute length.
    float hitDistanceA = 0.25f;
    float hitDistanceB = 0.1f;
    float hitDistanceC = 20.0f;
    float hitDistanceD = -25.0f;
    // Specular history also follows the reflection's own motion (the virtual point behind the
    // mirror), not only the surface's (NRD's virtual motion).
    bool virtualMotion = true;

    void validate() const;  // throws std::invalid_argument naming the field
};

// The settings for a diffuse signal traced and denoised at half resolution (SSGI's
// TraceLayout::Half; renderer/trace_pass.cpp), from the frame's: radii in half pixels, the
// blur's a quarter of the full one's (half the reach in the scene) and a light pre-blur (1.5
// half pixels, where the full one has none). Chosen against the one-bounce reference at 640x360
// over 30 frames (issue 27): cornell relMSE at frames 1 and 30 0.0247 and 0.0238 with flicker
// 0.0023, against 0.0251, 0.0239 and 0.0025 denoising at full resolution; without the pre-blur
// the flicker rose 5 %, with the full reach relMSE rose 8 %.
DenoiseSettings halfResolutionDiffuse(const DenoiseSettings& full);

}  // namespace ssrt
