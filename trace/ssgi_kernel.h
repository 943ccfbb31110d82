// The SSGI resolve kernel, one copy per ISA (trace/ssgi_kernel.cpp); the method is in
// trace/ssgi.h.
#pragma once

#include <cstddef>

#include "core/camera.h"
#include "core/dispatch.h"
#include "core/float_planes.h"
#include "core/gbuffer_view.h"
#include "core/plane_view.h"
#include "shading/direct_kernel.h"
#include "trace/world_rays.h"

namespace ssrt {

// One SSGI sample's resolve: the caller sets the camera, the planes (views of the camera's
// size) and the lighting; SsgiResolver checks them and sets the rest. Plain data only: this
// crosses into code compiled with other ISA flags.
struct SsgiArgs {
    // The caller's.
    TraceCamera camera;          // width, height, viewToWorld (rays go to world for the sky)
    GBufferView g;               // viewZ; normal, albedo, metallic without hitLight
    ViewF shadow{};              // the direct pass's "shadow" (without hitLight)
    FloatView emission[3] = {};  // optional: DirectArgs::emission planes (absent: none)
    // Optional: DirectArgs::hitLight planes (f16 as the renderer's, or f32), L(x1 -> x0) of
    // every pixel (trace/ssgi.h), computed by the direct pass; when given, g's normal, albedo,
    // metallic, shadow and emission are not read (the same light, fewer gathers; f16 planes
    // hold it rounded to nearest even).
    FloatView hitLight[3] = {};
    // The sun (toLight, lightRadiance) and the sky (skyGradient, skyZenith/Horizon/Ground,
    // envLevel/envLevelCount/envIntensity) are read from the direct pass's arguments as the
    // renderer fills them; their plane pointers are not used.
    const DirectArgs* lighting = nullptr;
    // Set by the resolver: the camera's size, the planes' one stride, *lighting with the
    // camera's rotation (the one rays are turned to world with), the output.
    int width = 0, height = 0, tilesX = 0;
    std::size_t stride = 0;
    DirectArgs light{};
    float* copyPdf = nullptr;  // optional: the frame's plane the batch's pdf is copied to
    float* out[3] = {};
    int sample = 0, sampleCount = 0;
    // Set per tile: rays and march, a batch's planes, with their own stride, whose element
    // (0, 0) is the frame's pixel (rayX0, rayY0) (trace/trace_types.h, BatchCorner).
    const float* rayDir[3] = {};  // view space
    const float* pdf = nullptr;
    const float* hit = nullptr;
    const float* hitX = nullptr;
    const float* hitY = nullptr;
    std::size_t rayStride = 0;
    int rayX0 = 0, rayY0 = 0;
    // Optional, per tile: the tile's world hits no pixel shows (mixed and world tracing), in
    // row order, each inside the tile: their light replaces what the hit pixel would lend.
    const WorldLit* lit = nullptr;
    int litCount = 0;
};

// Returns how many of args.lit it took (all of them, where they are the tile's in row order).
SSRT_DECLARE_KERNEL(int, ssgiTile, (const SsgiArgs& args, int tile))

}  // namespace ssrt
