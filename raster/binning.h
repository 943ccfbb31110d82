// Binning: which set-up triangles touch which tile, in submission order.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tiles.h"
#include "raster/geometry.h"

namespace ssrt {

// Flat bins: the triangles of tile t are items[start[t] .. start[t + 1]), indices into
// `triangles`, in submission order.
struct Bins {
    std::vector<TriangleSetup> triangles;
    std::vector<uint32_t> start;
    std::vector<uint32_t> items;
};

Bins binTriangles(SetupChunks&& chunks, const TileGrid& grid, int threads);

}  // namespace ssrt
