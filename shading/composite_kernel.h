// The composite kernel, one copy per ISA (shading/composite_kernel.cpp); the formula is in
// shading/composite.h.
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "core/float_planes.h"
#include "core/gbuffer_view.h"

namespace ssrt {

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
// Every plane has one size and one stride, ssgi's aside.
struct CompositeArgs {
    int width, height, tilesX;
    std::size_t stride;
    // The direct pass's parts, f32 or f16 (core/float_planes.h)
    SignalIn direct[3];
    SignalIn emission[3];  // null: none
    SignalIn envDiffuse[3];
    SignalIn envSpecular[3];
    SignalIn specWeight[3];
    const float* ssgi[3];  // null: SSGI off
    // ssgi's planes may be a tile's (the renderer's upsample run tile by tile into them): their
    // own stride, and their element (0, 0) the frame's pixel (ssgiX0, ssgiY0).
    std::size_t ssgiStride;
    int ssgiX0, ssgiY0;
    GBufferView g;             // viewZ, albedo, metallic (SSGI on only)
    const float* occlusion;    // null: none (SSGI on only)
    const float* ssrColor[3];  // null: SSR off
    const float* specular[3];  // null: from ssrColor, ssrOpacity and envSpecular
    const float* ssrOpacity;
    float exposure;
    float* color[3];
    float* display[3];
};

SSRT_DECLARE_KERNEL(void, compositeTile, (const CompositeArgs& args, int tile))

}  // namespace ssrt
