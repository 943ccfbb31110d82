// A screen-space triangle ready for the tile kernel, and the fixed-point budget it lives in.
//
// Vertices are snapped to 24.8 fixed point (8 sub-pixel bits). Pixel centres sit at
// (px * 256 + 128, py * 256 + 128). An edge function E(x, y) = a x + b y + c is exact in
// 64 bits; a pixel is inside when E' = E + bias >= 0 for all three edges, where bias is 0
// for top and left edges and -1 otherwise (the top-left rule, D3D10 convention).
//
// Budget: the guard band keeps |x|, |y| <= kMaxCoord = 2^22 sub-pixel units, so
//   |a|, |b| <= 2^23,  |c| <= 2^46,  |E| at any pixel centre < 2^48   (int64: fine)
// Inside an 8x8 block the kernel tests K = floor(E'(corner) / 256) + a i + b j, i, j in
// [0, 7]: since E' at a pixel centre is E'(corner) + 256 (a i + b j) exactly, E' >= 0 if and
// only if K >= 0. K needs |a i + b j| <= 14 * 2^23 < 2^27 plus a clamped corner value
// (|K0| <= 2^30), which fits int32: the per-pixel work is 32-bit SIMD.
#pragma once

#include <cstdint>

namespace ssrt {

inline constexpr int kSubPixelBits = 8;
inline constexpr int kSubPixel = 1 << kSubPixelBits;
inline constexpr int kBlockSize = 8;       // pixels per side of a raster block
inline constexpr int kGuardBandPx = 8192;  // pixels beyond each side of an 8192-pixel screen
inline constexpr int64_t kMaxCoord = int64_t(1) << 22;
inline constexpr int32_t kMaxK0 = int32_t(1) << 30;

static_assert(int64_t(8192 + kGuardBandPx) * kSubPixel <= kMaxCoord,
              "guard band and largest screen must fit the 2^22 sub-pixel budget");
static_assert(2 * kMaxCoord * (kBlockSize - 1) * 2 < (int64_t(1) << 31) - kMaxK0,
              "in-block increments plus the clamped corner value must fit int32");

struct TriangleSetup {
    int32_t a[3], b[3];              // edge coefficients (sub-pixel units)
    int64_t c[3];                    // constant terms, top-left bias folded in
    int32_t minX, minY, maxX, maxY;  // inclusive pixel bounds, clipped to the screen
    float zBase;                     // depth key at the centre of pixel (minX, minY)
    float zdx, zdy;                  // depth key per pixel step in x and y
    uint32_t primId;                 // global triangle index (instance order, then triangle order)
};

}  // namespace ssrt
