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

#include "core/isa.h"
#include "core/tiles.h"
#include "shading/composite_kernel.h"

namespace ssrt {

// Composites args' views (CompositeArgs, shading/composite_kernel.h) into its color and
// display views. Throws std::invalid_argument naming the plane when one it reads or writes is
// missing or of another size than direct's.
void composite(Isa isa, const CompositeArgs& args, int threads);

// The same, checked and set up once, then run tile by tile: over the frame by composite(), or
// one tile at a time after what makes its SSGI planes for that tile alone (the renderer's
// upsample of the half-resolution diffuse, trace/reconstruct.h).
class Compositor {
public:
    // composite()'s arguments less threads; `tileSsgi`: args.ssgi is not given (its planes
    // come with each tile).
    Compositor(Isa isa, const CompositeArgs& args, bool tileSsgi = false);
    const TileGrid& grid() const { return grid_; }
    // Tile `tile`, with the frame's SSGI planes (or, given, `ssgi`'s three views holding at
    // least the tile from its corner (x0, y0)).
    void tile(int tile, const ViewF* ssgi = nullptr, int x0 = 0, int y0 = 0) const;

private:
    CompositeArgs args_{};
    TileGrid grid_;
    bool tileSsgi_ = false;
    decltype(&isa_scalar::compositeTile) kernel_ = nullptr;
};

}  // namespace ssrt
