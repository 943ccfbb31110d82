// The tile shape of the packed Hi-Z copy (HiZPyramid::invMinPacked, raster/hiz.h), alone so
// that the per-ISA marcher kernels can check it without the pyramid's header: each level in
// 4x4 tiles of 16 floats, one 64-byte cache line each.
#pragma once

#include <cstddef>

namespace ssrt {

inline constexpr int kHiZPackedTile = 4;
inline constexpr std::size_t kHiZPackedTileSize = std::size_t(kHiZPackedTile * kHiZPackedTile);

}  // namespace ssrt
