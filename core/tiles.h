// The frame cut into tiles, and a parallel loop over them whose result cannot depend on
// scheduling: each tile writes only its own pixels, and anything reduced across tiles is
// stored per tile and combined in tile order afterwards.
#pragma once

#include <functional>

namespace ssrt {

inline constexpr int kTileSize = 64;  // pixels; a multiple of the 8x8 raster block

struct TileRect {
    int x0, y0, x1, y1;  // half-open pixel rectangle [x0, x1) x [y0, y1)
};

// The pixels of tile `tile` (row-major, tilesX tiles a row) of a width x height image; the
// last column and row are cut at the image's edge. For kernels too: plain ints, no ISA-
// dependent code, and always inlined, so no per-ISA object emits a weak copy of it
// (tests/check_kernel_objects.sh; STYLE.md).
[[gnu::always_inline]] constexpr TileRect tileRect(int tile, int tilesX, int width, int height) {
    const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
    return {x0, y0, x0 + kTileSize < width ? x0 + kTileSize : width,
            y0 + kTileSize < height ? y0 + kTileSize : height};
}

// Where planes smaller than the frame lie in it: their element (0, 0) is the frame's pixel
// (x0, y0). A stage run on one tile writes or reads such planes of one tile's size
// (trace/trace_types.h's batches, the composite's tile of SSGI light).
struct BatchCorner {
    int x0 = 0, y0 = 0;
};

// Whether planes of width x height placed at corner `c` hold the tile `r`'s pixels.
[[gnu::always_inline]] constexpr bool holdsTile(BatchCorner c, int width, int height,
                                                const TileRect& r) {
    return r.x0 >= c.x0 && r.y0 >= c.y0 && r.x1 - c.x0 <= width && r.y1 - c.y0 <= height;
}

struct TileGrid {
    int width = 0, height = 0;  // image size in pixels
    int tilesX = 0, tilesY = 0;

    TileGrid() = default;
    TileGrid(int w, int h)
        : width(w),
          height(h),
          tilesX((w + kTileSize - 1) / kTileSize),
          tilesY((h + kTileSize - 1) / kTileSize) {}

    int count() const { return tilesX * tilesY; }
    TileRect rect(int tile) const;
};

// Runs fn(tile) for every tile index on `threads` worker threads (0 = all cores). With a
// profile sink on the calling thread, each index is a slice on its thread (core/profile.h).
void parallelForTiles(int tileCount, int threads, const std::function<void(int)>& fn);

// Same loop over any index range, for passes cut by something other than tiles.
void parallelFor(int count, int threads, const std::function<void(int)>& fn);

}  // namespace ssrt
