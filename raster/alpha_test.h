// Alpha-tested triangles in the rasterizer: the cut-outs of scenes/material_alpha.h in the
// visibility pass and the shadow map. Set-up (raster/geometry.cpp) gives each triangle of a
// MASK or BLEND material with a base colour texture a slot here and marks its
// TriangleSetup::primId; the tile kernel rasterizes it as any other, then asks
// alphaTestPixels which of the pixels that passed the depth test it may write. Opaque
// triangles never reach this code, and a pass without alpha-tested triangles takes the
// kernel's loop as it was.
//
// Plain structs only: this header is read by the per-ISA kernels.
#pragma once

#include <cstdint>

namespace ssrt {

struct Scene;

// TriangleSetup::primId of an alpha-tested triangle: this bit and the triangle's slot in
// AlphaTestArgs::triangles, which holds its global id. A pass with alpha-tested triangles
// keeps every global id below 2^31 (setupTriangles checks), so no opaque id has the bit.
inline constexpr uint32_t kAlphaTestedBit = 0x80000000u;

// The UV at a pixel, perspective-correct, as the ratio of planes over the pixel indices
// (x, y), sampled at the pixel's centre (2D homogeneous interpolation: Olano and Greer 1997,
// "Triangle Scan Conversion using 2D Homogeneous Coordinates"):
//   uv = (U, V) / Q,  P(x, y) = (p[0] + p[1] x) + p[2] y  for P in U, V, Q.
// Solved in double from the unclipped triangle's clip-space vertices, so every piece that
// clipping cuts from it reads the same planes; in an orthographic view Q is constant.
struct AlphaTriangle {
    double u[3], v[3], q[3];
    uint32_t primId;    // the global triangle id
    uint32_t material;  // Scene::materials index
};

// The pass's alpha-tested triangles, by slot.
struct AlphaTestArgs {
    const AlphaTriangle* triangles;
    const Scene* scene;
};

// Of the pixels in `bits` (bit l: pixel first + l, row-major, of the 8x8 block whose top-left
// pixel is (blockX, blockY)), those the triangle in `slot` draws: alpha at the pixel's UV
// passes its material's cutoff. Scalar code compiled once, so the same bits on every ISA.
uint64_t alphaTestPixels(const AlphaTestArgs& args, uint32_t slot, int blockX, int blockY,
                         int first, uint64_t bits);

}  // namespace ssrt
