// The field tables (core/fields.h) of RenderSettings, TraceSettings and SsrResolveSettings
// (MarchSettings' is trace/march_fields.h): the one list of every setting, its range, default
// (the struct's), help text and where it appears. They generate the CLI flags
// (cli/options.cpp), the shot file's "render" keys (cli/shot_settings.cpp), validate()
// (settings.cpp), the reference cache key (truth/reference_key.cpp) and --help.
#pragma once

#include "core/fields.h"
#include "denoise/denoise_fields.h"
#include "renderer/settings.h"
#include "shading/direct_kernel.h"
#include "trace/march_fields.h"

namespace ssrt {

inline constexpr unsigned kCliShot = kFieldCli | kFieldShot;

inline constexpr std::array kResolveFields = {
    field<&SsrResolveSettings::mode>("ssrResolve", kCliShot,
                                     "SSR resolve: reuse (3x3 neighbours' hits, ratio estimator) "
                                     "or mip (colour pyramid at mip = roughness x max mip)")
        .choices(2, [](int i) { return resolveModeName(SsrResolveMode(i)); })
        .withTypeName("MODE"),
    field<&SsrResolveSettings::radiance>(
        "hitRadiance", kCliShot,
        "Radiance at a hit: current (this frame's direct light) or reprojected (the previous "
        "frame's final colour through the motion vectors; a sequence's first frame uses current)")
        .choices(2, [](int i) { return hitRadianceName(HitRadiance(i)); })
        .withTypeName("SOURCE"),
    field<&SsrResolveSettings::bilinear>(
        "hitBilinear", kCliShot, "Read the colour at a hit bilinearly (off: the nearest pixel)"),
    field<&SsrResolveSettings::edgeFadeLength>(
        "edgeFadeLength", kCliShot,
        "Fraction of the frame (per axis) over which SSR hits fade out toward its edges (screen "
        "tracing: mixed and world tracing keep every hit, which is certain)")
        .floats(0.0, true, 0.5),
    field<&SsrResolveSettings::roughnessFadeStart>(
        "roughnessFadeStart", kCliShot, "Perceptual roughness where SSR starts to fade out")
        .floats(0.0, false, 1.0),
    field<&SsrResolveSettings::roughnessFadeEnd>(
        "roughnessFadeEnd", kCliShot,
        "Perceptual roughness where SSR is gone (<= the start: a step there)")
        .floats(0.0, false, 1.0),
};
static_assert(fieldCount<SsrResolveSettings>() == kResolveFields.size(),
              "an SsrResolveSettings member is missing from kResolveFields");

// TraceSettings' own members (march and resolve follow in kTraceFields).
inline constexpr std::array kTraceOwnFields = {
    field<&TraceSettings::ssr>(
        "ssr", kCliShot,
        "Screen-space reflections (off: the environment's split-sum light stands in)"),
    field<&TraceSettings::ssgi>(
        "ssgi", kCliShot,
        "Screen-space one-bounce diffuse (off: the environment's irradiance stands in)"),
    field<&TraceSettings::ssrMethod>("ssrMethod", kCliShot | kFieldKey,
                                     "How SSR rays sample the GGX lobe")
        .choices(5, [](int i) { return ssrMethodName(SsrMethod(i)); }),
    field<&TraceSettings::marcher>("marcher", kCliShot,
                                   "Depth-buffer marcher for SSR and SSGI rays")
        .choices(3, [](int i) { return marcherName(Marcher(i)); }),
    field<&TraceSettings::ssrSpp>("ssrSpp", kCliShot, "SSR rays per pixel")
        .ints(1, TraceSettings::kMaxSpp),
    field<&TraceSettings::ssgiSpp>("ssgiSpp", kCliShot, "SSGI rays per pixel")
        .ints(1, TraceSettings::kMaxSpp),
    field<&TraceSettings::traceHidden>(
        "traceHidden", kCliShot,
        "Trace rays also where the composite hides what they find: SSR where the roughness fade "
        "does (perceptual roughness >= 0.7), SSGI on metals (no diffuse colour). The image is "
        "the same at those pixels; the counters and hit planes then cover them too. By default "
        "they get no ray"),
    field<&TraceSettings::ssgiFeedback>(
        "ssgiFeedback", kCliShot,
        "Multi-bounce diffuse: SSGI hits also reflect the previous frame's incoming diffuse "
        "light (reprojected), so each frame of a sequence adds a bounce (a sequence's first "
        "frame, or one after a reset, has one)"),
    field<&TraceSettings::ssrLayout>(
        "ssrLayout", kCliShot,
        "Which pixels get SSR rays: full (every one), checkerboard (half, alternating per frame, "
        "opposite to SSGI's); the others are reconstructed from their traced neighbours")
        .choices(2, [](int i) { return traceLayoutName(TraceLayout(i)); })
        .withTypeName("LAYOUT"),
    field<&TraceSettings::ssrTrace>(
        "ssrTrace", kCliShot,
        "How SSR's rays are answered: screen (the march), mixed (the march where it proves its "
        "hit, world rays through Embree for the rest) or world (every ray through Embree)")
        .choices(kTraceModeCount, [](int i) { return traceModeName(TraceMode(i)); })
        .withTypeName("MODE"),
    field<&TraceSettings::ssgiTrace>(
        "ssgiTrace", kCliShot,
        "How SSGI's rays are answered: screen (the march), mixed (the march where it proves its "
        "hit, world rays through Embree for the rest) or world (every ray through Embree)")
        .choices(kTraceModeCount, [](int i) { return traceModeName(TraceMode(i)); })
        .withTypeName("MODE"),
    field<&TraceSettings::ssrSparseFrames>(
        "ssrSparseFrames", kCliShot,
        "SSR checkerboard thinned: a pixel with this many frames of denoised specular history "
        "or more gets a ray every fourth frame instead of every second, its 2x2 block keeping "
        "one traced pixel a frame (64: never)")
        .ints(1, TraceSettings::kSparseOff),
    field<&TraceSettings::ssgiLayout>(
        "ssgiLayout", kCliShot,
        "Which pixels get SSGI rays: full, checkerboard (half, alternating per frame, opposite "
        "to SSR's) or half (one per 2x2 block, rotating per frame, marched on a half-resolution "
        "depth buffer); the others are reconstructed from the traced ones")
        .choices(3, [](int i) { return traceLayoutName(TraceLayout(i)); })
        .withTypeName("LAYOUT"),
};
// Every member is in the table, march, resolve and denoise through their own tables.
static_assert(fieldCount<TraceSettings>() == kTraceOwnFields.size() + 3,
              "a TraceSettings member is missing from kTraceOwnFields");

// Every tracing setting, as fields of TraceSettings.
inline constexpr auto kTraceFields =
    concatFields(kTraceOwnFields, nestedFields<&TraceSettings::march, kMarchFields>(),
                 nestedFields<&TraceSettings::resolve, kResolveFields>(),
                 nestedFields<&TraceSettings::denoise, kDenoiseFields>());

// RenderSettings' own members (trace follows in kRenderFields).
inline constexpr std::array kRenderOwnFields = {
    field<&RenderSettings::width>("width", kCliShot | kFieldKey, "Image width in pixels")
        .ints(1, kMaxImageSize),
    field<&RenderSettings::height>("height", kCliShot | kFieldKey, "Image height in pixels")
        .ints(1, kMaxImageSize),
    field<&RenderSettings::threads>("threads", kFieldCli, "Worker threads; 0 = every core")
        .ints(0, 256)
        .withFlag("-j,--threads"),
    field<&RenderSettings::shadowMapSize>("shadowMapSize", kCliShot | kFieldKey,
                                          "Shadow map texels per side")
        .ints(16, kMaxImageSize),
    field<&RenderSettings::shadowBias>(
        "shadowBias", kCliShot | kFieldKey,
        "Shadow depth tolerance off the receiver's plane, in shadow-map texels of depth")
        .floats(0.0, false),
    field<&RenderSettings::shadowSlopeBias>(
        "shadowSlopeBias", kCliShot | kFieldKey,
        "Extra shadow depth tolerance per unit of tan(angle to the light), in texels")
        .floats(0.0, false),
    field<&RenderSettings::pcfRadius>("pcfRadius", kCliShot | kFieldKey,
                                      "Shadow PCF kernel radius r: (2r+1)^2 texels")
        .ints(0, kMaxPcfRadius),
    field<&RenderSettings::exposure>("exposure", kCliShot | kFieldKey,
                                     "Scale on linear radiance before the tone map")
        .floats(0.0, true),
    field<&RenderSettings::idPlanes>("idPlanes", kCliShot,
                                     "The instanceId and triangleId planes (EXR layers)"),
    field<&RenderSettings::gbufferPlanes>(
        "gbufferPlanes", kCliShot,
        "The G-buffer and material planes (EXR layers); off, they are freed once read"),
    field<&RenderSettings::tracePlanes>(
        "tracePlanes", kCliShot,
        "The traced and denoised planes (EXR layers), the debug planes among them; off, they "
        "are freed once read"),
    field<&RenderSettings::debugPlanes>(
        "debugPlanes", kCliShot,
        "The planes made only to be looked at (EXR layers): march steps, the undenoised and "
        "the denoised full-resolution SSGI when the diffuse is denoised at half resolution, "
        "SSGI's full-resolution hit light when it traces at half, and with the denoiser on "
        "SSR's and SSGI's own planes, history lengths"),
};
// Every member is in the table but two: isa (a run-time choice of kernels, "auto" or
// $SSRT_ISA, parsed by core/isa.h) and trace (its own table).
static_assert(fieldCount<RenderSettings>() == kRenderOwnFields.size() + 2,
              "a RenderSettings member is missing from kRenderOwnFields");

// Every setting, as fields of RenderSettings: its own, then the tracing ones.
inline constexpr auto kRenderFields =
    concatFields(kRenderOwnFields, nestedFields<&RenderSettings::trace, kTraceFields>());

}  // namespace ssrt
