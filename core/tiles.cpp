#include "core/tiles.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>

namespace ssrt {

TileRect TileGrid::rect(int tile) const { return tileRect(tile, tilesX, width, height); }

void parallelFor(int count, int threads, const std::function<void(int)>& fn) {
    if (count <= 0) return;
    if (threads == 1) {
        for (int i = 0; i < count; ++i) fn(i);
        return;
    }
    auto body = [&] {
        // simple_partitioner with grain 1: every index is its own task; no index ever
        // sees state from another, so the order TBB picks cannot matter.
        tbb::parallel_for(
            tbb::blocked_range<int>(0, count, 1),
            [&](const tbb::blocked_range<int>& r) {
                for (int i = r.begin(); i != r.end(); ++i) fn(i);
            },
            tbb::simple_partitioner());
    };
    if (threads <= 0) {
        body();
    } else {
        tbb::task_arena arena(threads);
        arena.execute(body);
    }
}

void parallelForTiles(int tileCount, int threads, const std::function<void(int)>& fn) {
    parallelFor(tileCount, threads, fn);
}

}  // namespace ssrt
