// Reconstruction of the pixels a trace layout left without rays (trace/trace_layout.h), so
// that every full-resolution SSR and SSGI plane holds a plausible, finite value before the
// denoiser or the composite reads it.
//
// Both are joint-bilateral: a pixel p takes a weighted mean of traced samples s near it,
//   w(s) = w_space(s) w_plane(s) w_normal(s),
//   w_plane  = max(0, 1 - |n_p . (X_s - X_p)| / (kPlaneTolerance z_p)),
//   w_normal = max(0, n_p . n_s)^8,
// with X the view-space points and n the normals from the G-buffer, z_p the pixel's view
// depth. The plane term is NRD's depth test (REBLUR's checkerboard resolve in its pre-blur
// weighs the left and right neighbours by their view-depth relative difference,
// GetBilateralWeight) measured along p's normal, as REBLUR's blurs measure geometry: a
// neighbour on the same tilted floor has a large depth difference at grazing view but lies
// on the pixel's plane, one across a depth edge lies far from it. A sample is traced when
// its pdf is > 0 (a ray went out); pixels hidden by the composite or without a ray below
// the surface are not samples. When every weight vanishes the nearest traced sample (the
// largest w_space, then the smallest plane distance) stands in; with none, the pixel keeps
// zeros.
//
// - fillCheckerboard: in place, the pixels marked kPdfLayoutCut from their eight neighbours
//   (w_space 1) that were traced this frame: a checkerboard's edge ones, or, where it was
//   thinned (trace/trace_layout.h, sparseBlockPick), its block's pick on the diagonal. Traced
//   pixels are only read and cut ones only written, so the order of tiles cannot change a bit.
// - upsampleHalf: from the half-resolution frame's planes; a full-resolution pixel that is
//   its block's chosen pixel takes its half pixel's values as they are, the others the four
//   nearest half pixels at their chosen pixels' positions (w_space bilinear in those
//   positions: 1/2 or 1/4 each), guided by the full-resolution G-buffer at both ends.
//   Background pixels get zeros.
//
// Signals, per pixel (the fills are ratio estimates, as the resolves' means are):
//   colour      = sum w o c / sum w o  (o = opacity, for SSR; 1 for SSGI)
//   opacity     = sum w o / sum w
//   hit         = sum w h / sum w
//   hitDistance = sum w h d / sum w h  (0 without a hit)
//   steps       = the pixel's own march steps: 0 where it had no ray (the heat map says where
//                 work was done)
// A kernel over the lane type, one copy per ISA (trace/reconstruct_kernel.cpp), of
// correctly rounded operations only: the same bits on every ISA and thread count.
#pragma once

#include <cstdint>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/tiles.h"
#include "trace/reconstruct_kernel.h"
#include "trace/trace_layout.h"
#include "trace/trace_types.h"

namespace ssrt {

// Plane distance, relative to the pixel's depth, at which w_plane reaches 0.
inline constexpr float kReconstructPlaneTolerance = 0.02f;

// The full-resolution G-buffer the weights read.
struct ReconstructGuides {
    TraceCamera camera;  // width, height, tanHalf*, viewToWorld
    GBufferView g;       // viewZ, normal
};

// One signal's planes (full resolution as outputs; a half frame's as upsampleHalf's inputs).
// Null members are not touched; colour needs all three channels.
template <class P>
struct ReconstructPlanesOf {
    P* color[3] = {};
    P* opacity = nullptr;  // SSR: colour is weighted by it
    P* hit = nullptr;
    P* hitDistance = nullptr;
    P* steps = nullptr;  // upsampleHalf only: copied at chosen pixels, 0 elsewhere
};
using ReconstructPlanes = ReconstructPlanesOf<PlaneF>;
using ReconstructSource = ReconstructPlanesOf<const PlaneF>;

// Fills the pixels of `planes` whose `pdf` is kPdfLayoutCut. Throws std::invalid_argument on
// a missing guide or a plane not of the camera's size. Returns the pixels filled.
uint64_t fillCheckerboard(Isa isa, const ReconstructGuides& guides, const PlaneF& pdf,
                          const ReconstructPlanes& planes, int threads);

// Writes every pixel of `out` (planes ensured to the camera's size) from the half frame's
// `in` (its pdf: which half pixels are traced) for the chosen-pixel offset `offset`. Throws
// std::invalid_argument on missing or mis-sized planes. Returns the surface pixels blended
// (not chosen).
uint64_t upsampleHalf(Isa isa, const ReconstructGuides& guides, PixelOffset offset,
                      const PlaneF& halfPdf, const ReconstructSource& in,
                      const ReconstructPlanes& out, int threads);

// The same, checked and set up once, then run tile by tile: over the frame by upsampleHalf,
// or one tile at a time into a tile's planes for what reads it next in that tile (the
// renderer's composite). It points into the guides' and `in`'s planes: they outlive it.
class HalfUpsampler {
public:
    // upsampleHalf's arguments less the outputs and threads.
    HalfUpsampler(Isa isa, const ReconstructGuides& guides, PixelOffset offset,
                  const PlaneF& halfPdf, const ReconstructSource& in);
    const TileGrid& grid() const { return grid_; }
    // Tile `tile` into `out`: the frame's planes (corner (0, 0): ensured to the frame's size)
    // or planes holding at least the tile from the frame pixel (x0, y0). Returns the tile's
    // surface pixels blended.
    uint64_t tile(int tile, const ReconstructPlanes& out, int x0 = 0, int y0 = 0) const;

private:
    ReconstructArgs args_{};
    TileGrid grid_;
    decltype(&isa_scalar::reconstructTile) kernel_ = nullptr;
};

}  // namespace ssrt
