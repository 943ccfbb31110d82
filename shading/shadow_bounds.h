// Conservative bounds of the shadow map's depth per block of texels, for the early-out of
// shade::shadowVisibility (shading/direct_lanes.h): where the bounds prove that none of a
// pixel's PCF taps is an occluder, or that all are, its answer (1 or 0) is known without them.
#pragma once

#include <cstddef>
#include <vector>

namespace ssrt {

// Texels per side of a block: the footprint's bounds are read once per pixel, one block's.
inline constexpr int kShadowBlock = 8;

struct ShadowBounds {
    int blocks = 0;  // per side: ceil(size / kShadowBlock)
    // Per block, row-major, its lowest then highest depth over every texel that a tap of a
    // pixel in the block reads: the block widened by the PCF radius on each side and clipped
    // to the map, as the taps are clamped to its edge. NaN (both) where such a texel is NaN.
    std::vector<float> loHi;
};

// The bounds of the size x size map (row stride `stride`) for PCF radius `radius`, on
// `threads` threads (0 = all cores). Made once per frame: it reads the map once, and the
// 2 radius rows that neighbouring block rows share once more each, and writes 8 bytes per
// block (1/32 of the map's bytes).
void buildShadowBounds(const float* map, std::size_t stride, int size, int radius, int threads,
                       ShadowBounds& out);

}  // namespace ssrt
