// The per-tile rasterizer kernel, one copy per ISA (raster/tile_raster_kernel.cpp).
#pragma once

#include <cstdint>

#include "core/dispatch.h"
#include "raster/alpha_test.h"
#include "raster/raster_stats.h"
#include "raster/setup.h"

namespace ssrt {

// Plain pointers only: this crosses into code compiled with other ISA flags.
struct TileRasterArgs {
    const TriangleSetup* triangles;
    const uint32_t* binStart;
    const uint32_t* binItems;
    int width, height, tilesX;
    float clearDepth;
    float* depth;                       // plane rows
    uint32_t* ids;                      // nullptr for depth-only
    std::size_t depthStride, idStride;  // elements per row
    // The pass's alpha-tested triangles (TriangleSetup::primId with kAlphaTestedBit), or null
    // when it has none: then no triangle's id is looked at.
    const AlphaTestArgs* alpha;
};

SSRT_DECLARE_KERNEL(void, rasterTile, (const TileRasterArgs& args, int tile, RasterStats& stats))

}  // namespace ssrt
