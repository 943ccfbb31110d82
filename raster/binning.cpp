#include "raster/binning.h"

#include <algorithm>

namespace ssrt {

namespace {

// Tiles touched by a triangle's pixel bounds.
struct TileSpan {
    int tx0, ty0, tx1, ty1;  // inclusive
};

TileSpan tileSpan(const TriangleSetup& t) {
    return {t.minX / kTileSize, t.minY / kTileSize, t.maxX / kTileSize, t.maxY / kTileSize};
}

}  // namespace

Bins binTriangles(SetupChunks&& chunks, const TileGrid& grid, int threads) {
    Bins bins;
    const int tiles = grid.count();
    const int chunkCount = int(chunks.chunks.size());
    // Flatten the chunks in order: global index = chunk offset + index in chunk.
    std::vector<uint32_t> chunkOffset(chunkCount + 1, 0);
    for (int c = 0; c < chunkCount; ++c)
        chunkOffset[c + 1] = chunkOffset[c] + uint32_t(chunks.chunks[c].size());
    bins.triangles.resize(chunkOffset[chunkCount]);

    // Pass 1, per chunk: count entries per tile (chunk-major table).
    std::vector<uint32_t> counts(std::size_t(chunkCount) * tiles, 0);
    parallelFor(chunkCount, threads, [&](int c) {
        const auto& tris = chunks.chunks[c];
        std::copy(tris.begin(), tris.end(), bins.triangles.begin() + chunkOffset[c]);
        uint32_t* row = counts.data() + std::size_t(c) * tiles;
        for (const TriangleSetup& t : tris) {
            const TileSpan s = tileSpan(t);
            for (int ty = s.ty0; ty <= s.ty1; ++ty)
                for (int tx = s.tx0; tx <= s.tx1; ++tx) ++row[ty * grid.tilesX + tx];
        }
    });
    // Prefix sums in (tile, chunk) order: tile t's items are its chunks' items in order.
    std::vector<uint32_t> cursor(std::size_t(chunkCount) * tiles);
    bins.start.assign(tiles + 1, 0);
    uint32_t total = 0;
    for (int t = 0; t < tiles; ++t) {
        bins.start[t] = total;
        for (int c = 0; c < chunkCount; ++c) {
            cursor[std::size_t(c) * tiles + t] = total;
            total += counts[std::size_t(c) * tiles + t];
        }
    }
    bins.start[tiles] = total;
    bins.items.resize(total);
    // Pass 2, per chunk: write each triangle's index at its tiles' cursors.
    parallelFor(chunkCount, threads, [&](int c) {
        uint32_t* cur = cursor.data() + std::size_t(c) * tiles;
        const auto& tris = chunks.chunks[c];
        for (uint32_t i = 0; i < tris.size(); ++i) {
            const TileSpan s = tileSpan(tris[i]);
            for (int ty = s.ty0; ty <= s.ty1; ++ty)
                for (int tx = s.tx0; tx <= s.tx1; ++tx)
                    bins.items[cur[ty * grid.tilesX + tx]++] = chunkOffset[c] + i;
        }
    });
    return bins;
}

}  // namespace ssrt
