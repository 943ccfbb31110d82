// The composite: the direct pass's parts (DirectArgs::direct etc., shading/direct_kernel.h)
// with the screen-space indirect light, then the tone map of `display`. Per pixel
//   diffuse  = SSGI on:  albedo (1 - metallic) ssgi   (replaces envDiffuse; 0 on background)
//                        times the occlusion where there is one (envDiffuse has it already)
//              SSGI off: envDiffuse
//   specular = SSR on:   specWeight (ssr opacity + envSpecular (1 - opacity))
//              or specWeight specular, where the denoiser hands the blend as a whole
//              (specWeight holds Kulla-Conty's multiple scattering, as `color` does)
//              SSR off:  specWeight envSpecular
//   color    = (((direct + diffuse) + specular) + emission) exposure
//   display  = sRGB(ACES(color))
// With both off this is the direct pass's own sum, in its order: from f32 parts `color` and
// `display` equal the direct kernel's to the bit (tests/shading/composite_test.cpp); from the
// renderer's f16 parts, to their rounding.
#pragma once

#include "core/float_planes.h"
#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/tiles.h"
#include "shading/composite_kernel.h"

namespace ssrt {

// All planes of one size; scene-linear (before exposure) like the direct pass's parts, which
// may be f32 or f16 (FloatPlane).
struct CompositeInputs {
    FloatPlane direct[3] = {};       // DirectArgs::direct
    FloatPlane emission[3] = {};     // DirectArgs::emission (null: no emission)
    FloatPlane envDiffuse[3] = {};   // DirectArgs::envDiffuse (may be null with SSGI on)
    FloatPlane envSpecular[3] = {};  // DirectArgs::envSpecular
    FloatPlane specWeight[3] = {};   // DirectArgs::specWeight
    // SSGI (trace/ssgi.h): null = off. With it on, the G-buffer's viewZ, albedo and metallic.
    const PlaneF* ssgi[3] = {};
    GBufferView g;
    // MaterialPlanes::occlusion (null: none), read with SSGI on; envDiffuse and specWeight
    // hold it already (DirectArgs::occlusion).
    const PlaneF* occlusion = nullptr;
    // SSR (trace/ssr_resolve.h, SsrOutput::color and ::opacity): null = off.
    const PlaneF* ssrColor[3] = {};
    const PlaneF* ssrOpacity = nullptr;
    // The incoming specular radiance as a whole (the denoiser's, denoise/denoise.h), in place
    // of ssr opacity + envSpecular (1 - opacity); null: that blend.
    const PlaneF* specular[3] = {};
    float exposure = 1.0f;  // the renderer's exposure (RenderSettings::exposure)
};

// Writes color[3] (linear, exposed) and display[3] (tone mapped, sRGB), ensured to the
// inputs' size. Throws std::invalid_argument on a missing or mis-sized plane.
void composite(Isa isa, const CompositeInputs& inputs, PlaneF color[3], PlaneF display[3],
               int threads);

// The same, checked and set up once, then run tile by tile: over the frame by composite(), or
// one tile at a time after what makes its SSGI planes for that tile alone (the renderer's
// upsample of the half-resolution diffuse, trace/reconstruct.h).
class Compositor {
public:
    // composite()'s arguments less threads; `tileSsgi`: inputs.ssgi is not given (its planes
    // come with each tile).
    Compositor(Isa isa, const CompositeInputs& inputs, PlaneF color[3], PlaneF display[3],
               bool tileSsgi = false);
    const TileGrid& grid() const { return grid_; }
    // Tile `tile`, with the frame's SSGI planes (or, given, `ssgi` holding at least the tile
    // from its corner).
    void tile(int tile, const PlaneF* const ssgi[3] = nullptr, int x0 = 0, int y0 = 0) const;

private:
    CompositeArgs args_{};
    TileGrid grid_;
    bool tileSsgi_ = false;
    decltype(&isa_scalar::compositeTile) kernel_ = nullptr;
};

}  // namespace ssrt
