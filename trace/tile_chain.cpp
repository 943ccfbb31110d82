#include "trace/tile_chain.h"

#include <chrono>
#include <stdexcept>
#include <vector>

#include "core/image.h"

namespace ssrt {

namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// A thread's batches of one tile's size, kept for the process (zeroed once: the lanes past a
// frame's edge read what the last tile left, finite, as a frame's batch's padding does).
struct TileBatches {
    RayBatch rays;
    MarchResult march;
    TileBatches() {
        rays.forEachPlane([](std::string_view, PlaneF& p) { p = PlaneF(kTileSize, kTileSize); });
        march.forEachPlane([](std::string_view, PlaneF& p) { p = PlaneF(kTileSize, kTileSize); });
    }
};

// One tile's counters and its stages' times.
struct TileResult {
    RayGenStats rays;
    MarchStats march;
    double ms[3] = {};  // rays, march, consume
};

}  // namespace

TileChainStats runTileChain(const TileChain& chain, int threads) {
    const TileGrid& grid = chain.rays.grid();
    const TileGrid& marchGrid = chain.march.grid();
    if (marchGrid.width != grid.width || marchGrid.height != grid.height)
        throw std::invalid_argument("runTileChain: the stages' frames differ");
    std::vector<TileResult> tiles(std::size_t(grid.count()));
    const Clock::time_point t0 = Clock::now();
    parallelForTiles(grid.count(), threads, [&](int tile) {
        thread_local TileBatches b;
        const TileRect r = grid.rect(tile);
        b.rays.corner = b.march.corner = {r.x0, r.y0};
        TileResult& out = tiles[std::size_t(tile)];
        const Clock::time_point a = Clock::now();
        out.rays = chain.rays.tile(tile, b.rays);
        const Clock::time_point m = Clock::now();
        out.march = chain.march.tile(tile, b.rays, b.march);
        const Clock::time_point h = Clock::now();
        chain.consume(tile, b.rays, b.march);
        const Clock::time_point e = Clock::now();
        out.ms[0] = msBetween(a, m), out.ms[1] = msBetween(m, h), out.ms[2] = msBetween(h, e);
    });
    const double wall = msBetween(t0, Clock::now());
    TileChainStats s;
    double busy[3] = {};
    for (const TileResult& t : tiles) {
        s.rays.add(t.rays);
        s.march.add(t.march);
        for (int i = 0; i < 3; ++i) busy[i] += t.ms[i];
    }
    // The loop's wall time, shared out by the threads' time in each stage.
    const double sum = busy[0] + busy[1] + busy[2], k = sum > 0.0 ? wall / sum : 0.0;
    s.raysMs = busy[0] * k, s.marchMs = busy[1] * k, s.consumeMs = busy[2] * k;
    return s;
}

}  // namespace ssrt
