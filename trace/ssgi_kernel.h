// The SSGI resolve kernel, one copy per ISA (trace/ssgi_kernel.cpp); the method is in
// trace/ssgi.h.
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"
#include "shading/direct_kernel.h"

namespace ssrt {

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
// Every plane has the frame's size and one stride, the batch's aside.
struct SsgiArgs {
    int width, height, tilesX;
    std::size_t stride;
    GBufferView g;  // viewZ; normal, albedo, metallic without hitLight
    const float* shadow;
    SignalIn emission[3];  // all null: no emission (f32 or f16: core/float_planes.h)
    SignalIn hitLight[3];  // all null: computed from the planes above (SsgiInputs)
    // Rays and march: a batch's planes, with their own stride, whose element (0, 0) is the
    // frame's pixel (rayX0, rayY0) (trace/trace_types.h, BatchCorner).
    const float* rayDir[3];  // view space
    const float* pdf;
    const float* hit;
    const float* hitX;
    const float* hitY;
    std::size_t rayStride;
    int rayX0, rayY0;
    float* copyPdf;       // optional: the frame's plane the batch's pdf is copied to
    DirectArgs lighting;  // sun, sky and viewToWorld
    float* out[3];
    int sample, sampleCount;
};

SSRT_DECLARE_KERNEL(void, ssgiTile, (const SsgiArgs& args, int tile))

// addSsgiFeedback's (trace/ssgi.h), likewise plain: one size and stride for every plane.
struct SsgiFeedbackArgs {
    int width, height, tilesX;
    std::size_t stride;
    GBufferView g;           // viewZ, albedo, metallic, motion
    const float* occlusion;  // null: 1
    const float* prevDiffuse[3];
    SignalOut hitLight[3];  // read and written in place (f32 or f16)
};

SSRT_DECLARE_KERNEL(void, ssgiFeedbackTile, (const SsgiFeedbackArgs& args, int tile))

}  // namespace ssrt
