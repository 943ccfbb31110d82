// DenoiseSettings' field table (core/fields.h): the one list of the denoiser's settings, their
// ranges and help. None shapes the reference.
#pragma once

#include "core/fields.h"
#include "denoise/denoise_settings.h"

namespace ssrt {

inline constexpr int kMaxDenoiseFrames = 63;  // REBLUR's limit (6 bits on the GPU)

inline constexpr unsigned kDenoiseUse = kFieldCli | kFieldShot;

inline constexpr std::array kDenoiseFields = {
    field<&DenoiseSettings::enabled>(
        "denoise", kDenoiseUse,
        "Denoise SSR and SSGI (REBLUR: pre-blur, temporal accumulation, history fix, blur, "
        "post-blur); off: the composite reads the traced signals as they are"),
    field<&DenoiseSettings::maxAccumulatedFrames>(
        "maxAccumulatedFrames", kDenoiseUse,
        "Frames the temporal accumulation averages at most (0: spatial filtering only)")
        .ints(0, kMaxDenoiseFrames),
    field<&DenoiseSettings::maxFastAccumulatedFrames>(
        "maxFastAccumulatedFrames", kDenoiseUse,
        "Frames of the fast history that clamps the slow one against lag (>= the above: off)")
        .ints(0, kMaxDenoiseFrames),
    field<&DenoiseSettings::historyFixFrames>(
        "historyFixFrames", kDenoiseUse,
        "Pixels with fewer frames of history get the history fix's wider reconstruction")
        .ints(0, 3),
    field<&DenoiseSettings::historyFixStride>(
        "historyFixStride", kDenoiseUse,
        "History fix: pixels between its taps for a pixel without history (shrinks with age)")
        .ints(1, 64),
    field<&DenoiseSettings::diffusePrepassRadius>("diffusePrepassRadius", kDenoiseUse,
                                                  "Pre-blur radius of the diffuse signal, pixels")
        .floats(0.0, false, 100.0),
    field<&DenoiseSettings::specularPrepassRadius>("specularPrepassRadius", kDenoiseUse,
                                                   "Pre-blur radius of the specular signal, pixels")
        .floats(0.0, false, 100.0),
    field<&DenoiseSettings::minBlurRadius>("minBlurRadius", kDenoiseUse,
                                           "Blur radius of a converged pixel, pixels")
        .floats(0.0, false, 100.0),
    field<&DenoiseSettings::maxBlurRadius>(
        "maxBlurRadius", kDenoiseUse,
        "Blur radius of a pixel without history, pixels (the post-blur doubles it)")
        .floats(0.0, false, 100.0),
    field<&DenoiseSettings::blurMaxFrames>(
        "blurMaxFrames", kDenoiseUse,
        "Pixels with this many frames of history or more skip the blur, keeping the post-blur "
        "(64: every pixel is blurred twice)")
        .ints(0, kMaxDenoiseFrames + 1),
    field<&DenoiseSettings::postBlurMaxFrames>(
        "postBlurMaxFrames", kDenoiseUse,
        "Pixels with this many frames of history or more whose signal is steady (luma near "
        "its fast history's) skip the post-blur as well (64: every pixel is post-blurred)")
        .ints(0, kMaxDenoiseFrames + 1),
    field<&DenoiseSettings::lobeAngleFraction>(
        "lobeAngleFraction", kDenoiseUse,
        "Share of the specular lobe's angle a neighbour's normal may differ by")
        .floats(0.0, true, 1.0),
    field<&DenoiseSettings::roughnessFraction>(
        "roughnessFraction", kDenoiseUse,
        "Share of the roughness a neighbour's roughness may differ by")
        .floats(0.0, true, 1.0),
    field<&DenoiseSettings::planeDistanceSensitivity>(
        "planeDistanceSensitivity", kDenoiseUse,
        "Distance from the pixel's plane a neighbour may lie at, as a fraction of the "
        "frustum's height at its depth")
        .floats(0.0, true, 1.0),
    field<&DenoiseSettings::minHitDistanceWeight>(
        "minHitDistanceWeight", kDenoiseUse,
        "Least weight of a neighbour whose hit distance differs")
        .floats(0.0, true, 0.2),
    field<&DenoiseSettings::disocclusionThreshold>(
        "disocclusionThreshold", kDenoiseUse,
        "Depth difference, as a fraction of the frustum's height, past which a history tap "
        "is occluded")
        .floats(0.0, true, 1.0),
    field<&DenoiseSettings::fireflyMinRelativeScale>(
        "fireflyMinRelativeScale", kDenoiseUse,
        "Firefly suppressor: the least multiple of the history's luma a new sample keeps")
        .floats(1.0, false, 3.0),
    field<&DenoiseSettings::hitDistanceA>(
        "hitDistanceA", kDenoiseUse,
        "Hit-distance normalisation (A + B z) lerp(1, C, 2^(D r^2)): A, in scene diagonals")
        .floats(0.0, true),
    field<&DenoiseSettings::hitDistanceB>("hitDistanceB", kDenoiseUse,
                                          "Hit-distance normalisation: B, per unit of depth")
        .floats(0.0, false),
    field<&DenoiseSettings::hitDistanceC>("hitDistanceC", kDenoiseUse,
                                          "Hit-distance normalisation: C (smooth surfaces' scale)")
        .floats(1.0, false),
    field<&DenoiseSettings::hitDistanceD>("hitDistanceD", kDenoiseUse,
                                          "Hit-distance normalisation: D (< 0)")
        .floats(-1000.0, false, 0.0, true),
    field<&DenoiseSettings::virtualMotion>(
        "virtualMotion", kDenoiseUse,
        "Specular history follows the reflection's virtual motion as well as the surface's"),
};
static_assert(fieldCount<DenoiseSettings>() == kDenoiseFields.size(),
              "a DenoiseSettings member is missing from kDenoiseFields");

}  // namespace ssrt
