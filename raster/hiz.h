// The Hi-Z pyramid: the min view depth over power-of-two footprints, for the Hi-Z marcher
// (trace/march_hiz_kernel.cpp). (A max pyramid was built beside it and never read: issue 27
// removed it, 5 B a pixel and a third of the build.)
//
// Convention: depths are positive view Z as in the G-buffer, and background (viewZ 0, or
// anything not > 0) is +infinity: a ray is never behind the background.
// Level 0 is a copy of viewZ with that substitution; level k has size
// (max(1, ceil(w_{k-1} / 2)), max(1, ceil(h_{k-1} / 2))) and cell (x, y) holds the min
// of cells (2x..2x+1, 2y..2y+1) of level k-1 that exist (the last column/row of an odd size
// covers the single leftover texel). So cell (x, y) of level k covers level-0 pixels
// [x 2^k, min((x + 1) 2^k, w)) x [y 2^k, min((y + 1) 2^k, h)); the last level is 1x1.
#pragma once

#include <vector>

#include "core/image.h"
#include "core/plane_memory.h"
#include "raster/hiz_layout.h"

namespace ssrt {

// The packed 1/minZ copy: 64-byte aligned, so that each 4x4 tile is one cache line.
using HiZPacked = std::vector<float, PlaneMemoryAllocator<float>>;

// The packed copy's layout: each level in 4x4 tiles of 16 floats (row-major within a tile,
// tiles row-major), its height rounded up to whole tiles and its rows of tiles to a power of
// two tiles (hiZPackedPitch; padding 0, background); level L starts at packedOffset[L], a
// multiple of 16. A ray that moves a few pixels in any direction stays in one cache line more
// often than with rows (vertical steps cross a line every row there), and the power-of-two
// pitch makes a texel's index shifts and adds (the marcher's multiply was on the path to
// every depth gather). The padding tiles are written, never read.
// Tiles across a level of width `size` (or down one of height `size`).
inline constexpr int hiZPackedTiles(int size) {
    return (size + kHiZPackedTile - 1) / kHiZPackedTile;
}
// Tiles in a packed row of tiles of a level of width `size`: hiZPackedTiles rounded up to a
// power of two, 2^hiZPackedPitchLog2.
inline constexpr int hiZPackedPitchLog2(int size) {
    int log2 = 0;
    while ((1 << log2) < hiZPackedTiles(size)) ++log2;
    return log2;
}
inline constexpr int hiZPackedPitch(int size) { return 1 << hiZPackedPitchLog2(size); }
// Index of texel (x, y) of a level within its packed copy; pitch = hiZPackedPitch(width).
inline constexpr std::size_t hiZPackedIndex(int x, int y, int pitch) {
    return (std::size_t(y / kHiZPackedTile) * std::size_t(pitch) +
            std::size_t(x / kHiZPackedTile)) *
               kHiZPackedTileSize +
           std::size_t((y % kHiZPackedTile) * kHiZPackedTile + x % kHiZPackedTile);
}

struct HiZPyramid {
    std::vector<PlaneF> minZ;  // [level], level 0 = full resolution
    // Every level of minZ packed for a hardware gather (the Hi-Z marcher's reads): level after
    // level in 4x4 tiles (hiZPackedIndex), as 1 / minZ (background 0); level L starts at
    // packedOffset[L]. Empty when the whole would reach 2^24 elements (the marcher indexes it
    // with exact floats) or when the pyramid was not made by buildHiZ; code that changes
    // minZ after buildHiZ must clear it (marchRays then packs its own copy).
    HiZPacked invMinPacked;
    std::vector<std::size_t> packedOffset;
    int levels() const { return int(minZ.size()); }
};

// Builds every level from the G-buffer's viewZ, and the packed 1/minZ copy; reuses the
// planes when the sizes match. Rows of a level are cut across `threads` workers (0 = every
// core); the min is exact, so the result does not depend on the thread count.
void buildHiZ(const PlaneF& viewZ, HiZPyramid& pyramid, int threads);

// The packed copy's size limit (elements), and the packing itself: minZ levels into `packed`
// and `offset` as HiZPyramid::invMinPacked and packedOffset; false (both emptied) when the
// whole would reach the limit.
inline constexpr std::size_t kHiZMaxPacked = std::size_t(1) << 24;
bool packInverseMin(const std::vector<PlaneF>& minZ, HiZPacked& packed,
                    std::vector<std::size_t>& offset, int threads);

// Number of levels for a w x h image: down to 1x1.
int hiZLevelCount(int width, int height);

}  // namespace ssrt
