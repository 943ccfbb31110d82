// The composite's planes and the kernel, one copy per ISA (shading/composite_kernel.cpp); the
// formula is in shading/composite.h.
#pragma once

#include <cstddef>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"
#include "core/plane_view.h"

namespace ssrt {

// The composite's planes, views of one size (ssgi's aside). The caller sets the views and the
// exposure; the Compositor checks them and sets the rest. Plain data only: this crosses into
// code compiled with other ISA flags.
struct CompositeArgs {
    // The direct pass's parts, scene-linear (before exposure): DirectArgs::direct etc.
    // (shading/direct_kernel.h)
    FloatView direct[3];
    FloatView emission[3];    // absent: no emission
    FloatView envDiffuse[3];  // read with SSGI off only
    FloatView envSpecular[3];
    FloatView specWeight[3];
    // SSGI (trace/ssgi.h): absent = off. With it on, the G-buffer's viewZ, albedo and metallic,
    // and the occlusion (GBuffer::occlusion; absent: none), which envDiffuse and
    // specWeight hold already (DirectArgs::occlusion).
    ViewF ssgi[3];
    GBufferView g;
    ViewF occlusion;
    // SSR (trace/ssr_resolve.h, SsrOutput::color and ::opacity): absent = off.
    ViewF ssrColor[3];
    ViewF ssrOpacity;
    // The incoming specular radiance as a whole (the denoiser's, denoise/denoise.h), in place
    // of ssr opacity + envSpecular (1 - opacity); absent: that blend.
    ViewF specular[3];
    float exposure = 1.0f;  // the renderer's exposure (RenderSettings::exposure)
    OutF color[3];          // linear, exposed
    OutF display[3];        // tone mapped, sRGB

    // Set by the Compositor: the size, the one stride of every view but ssgi's, and where
    // ssgi's element (0, 0) lies in the frame (its views may hold one tile: Compositor::tile).
    int width = 0, height = 0, tilesX = 0;
    std::size_t stride = 0;
    int ssgiX0 = 0, ssgiY0 = 0;
};

SSRT_DECLARE_KERNEL(void, compositeTile, (const CompositeArgs& args, int tile))

}  // namespace ssrt
