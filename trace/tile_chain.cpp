#include "trace/tile_chain.h"

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/image.h"
#include "core/profile.h"

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
    double ms[5] = {};  // rays, march, consume, finish, answer
};

}  // namespace

TileChainStats runTileChain(const TileChain& chain, int threads) {
    const TileGrid& grid = chain.rays.grid();
    const TileGrid& marchGrid = chain.march.grid();
    if (marchGrid.width != grid.width || marchGrid.height != grid.height)
        throw std::invalid_argument("runTileChain: the stages' frames differ");
    std::vector<TileResult> tiles(std::size_t(grid.count()));
    // The profile's slices of each tile's stages, named after the pass's scope as `--stats`
    // names its lines ("ssr rays", "ssr march", "ssr resolve": core/profile.h).
    ProfileSink* const sink = profileSink();
    const std::string pass(profileScopeName());
    const std::string stage[4] = {pass + " rays", pass + " march", pass + " resolve",
                                  pass + " world"};
    const auto record = [&](int i, Clock::time_point a, Clock::time_point b) {
        if (sink) sink->slice(stage[i], std::this_thread::get_id(), a, b);
    };
    const auto runChain = [&](int tile) {
        thread_local TileBatches b;
        const TileRect r = grid.rect(tile);
        b.rays.corner = b.march.corner = {r.x0, r.y0};
        TileResult& out = tiles[std::size_t(tile)];
        const Clock::time_point a = Clock::now();
        out.rays = chain.rays.tile(tile, b.rays);
        const Clock::time_point m = Clock::now();
        out.march = chain.march.tile(tile, b.rays, b.march);
        const Clock::time_point h = Clock::now();
        if (chain.answer) chain.answer(tile, b.rays, b.march);
        const Clock::time_point w = Clock::now();
        chain.consume(tile, b.rays, b.march);
        const Clock::time_point e = Clock::now();
        out.ms[0] = msBetween(a, m), out.ms[1] = msBetween(m, h), out.ms[4] = msBetween(h, w);
        out.ms[2] = msBetween(w, e);
        record(0, a, m), record(1, m, h), record(2, w, e);
        if (chain.answer) record(3, h, w);
    };
    const Clock::time_point t0 = Clock::now();
    if (!chain.finish) {
        parallelForTiles(grid.count(), threads, runChain);
    } else {
        // Step k: row k's chains and, in the same loop, row k - 2's finish, which reads rows
        // k - 3 .. k - 1, all completed by earlier steps (row k, being written, is the ring's
        // fourth).
        const int tx = grid.tilesX;
        for (int k = 0; k < grid.tilesY + 2; ++k) {
            const int chains = k < grid.tilesY ? tx : 0, finishes = k >= 2 ? tx : 0;
            parallelFor(chains + finishes, threads, [&](int i) {
                if (i < chains) return runChain(k * tx + i);
                const int tile = (k - 2) * tx + (i - chains);
                const Clock::time_point a = Clock::now();
                chain.finish(tile);
                const Clock::time_point b = Clock::now();
                tiles[std::size_t(tile)].ms[3] = msBetween(a, b);
                record(2, a, b);
            });
        }
    }
    const double wall = msBetween(t0, Clock::now());
    TileChainStats s;
    double busy[5] = {};
    for (const TileResult& t : tiles) {
        s.rays.add(t.rays);
        s.march.add(t.march);
        for (int i = 0; i < 5; ++i) busy[i] += t.ms[i];
    }
    // The loop's wall time, shared out by the threads' time in each stage.
    const double sum = busy[0] + busy[1] + busy[2] + busy[3] + busy[4];
    const double k = sum > 0.0 ? wall / sum : 0.0;
    s.raysMs = busy[0] * k, s.marchMs = busy[1] * k, s.consumeMs = busy[2] * k;
    s.finishMs = busy[3] * k, s.answerMs = busy[4] * k;
    return s;
}

}  // namespace ssrt
