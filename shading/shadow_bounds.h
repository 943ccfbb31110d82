// Bounds of the shadow map's depth per block of texels, for the early-out of
// shade::shadowVisibility (shading/direct_lanes.h): where the bounds prove that none of a
// pixel's PCF taps is an occluder, or that all are, its answer (1 or 0) is known without them.
#pragma once

#include <cstddef>
#include <vector>

#include "core/dispatch.h"

namespace ssrt {

// Texels per side of a block: a pixel reads its own block's bounds (one per pixel).
inline constexpr int kShadowBlock = 8;

// Per block, a plane through its depths and how far they stray from it, so that a receiver
// tilted as the map's surface is (whose taps' depths rise with its own plane) is still
// decided: for every texel (x, y) that a tap of a pixel in block (bx, by) may read (the
// block widened by the PCF radius on each side, within the map),
//   lo <= depth(x, y) - (du X + dv Y) <= hi,  X = x - (kShadowBlock bx + kShadowBlock / 2),
// Y likewise, in exact arithmetic (the rounding of the build is added to lo and hi). NaN lo
// and hi where such a texel is NaN or infinite.
struct ShadowBlockBounds {
    float lo, hi, du, dv;
};

struct ShadowBounds {
    int blocks = 0;                        // per side: ceil(size / kShadowBlock)
    std::vector<ShadowBlockBounds> block;  // row-major
};

// The bounds of the size x size map (row stride `stride`) for PCF radius `radius`, by the
// given ISA's kernel (every ISA makes the same bits) on `threads` threads (0 = all cores).
// Made once per frame: it reads the map once, and the 2 radius rows that neighbouring block
// rows share once more each, and writes 16 bytes per block (1/16 of the map's bytes). For the
// default 2048^2 map and radius 1: 33.5M instructions (callgrind, AVX2), 1.8 to 3.2 ms on 2
// shared cores (AVX-512); the direct pass at 1920x1080, this included, took 3 to 6 ms less.
void buildShadowBounds(const float* map, std::size_t stride, int size, int radius, Isa isa,
                       int threads, ShadowBounds& out);

// One block row `by` of `out`'s blocks (ShadowBounds::block, row by), per ISA; `work` holds
// shadowBoundsWork(size) floats.
SSRT_DECLARE_KERNEL(void, boundShadowBlockRow,
                    (const float* map, std::size_t stride, int size, int radius, int by,
                     float* work, ShadowBlockBounds* out))
inline std::size_t shadowBoundsWork(int size) {
    return 5 * std::size_t(size) + 2 * std::size_t((size + kShadowBlock - 1) / kShadowBlock);
}

}  // namespace ssrt
