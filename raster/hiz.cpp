#include "raster/hiz.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "core/tiles.h"

namespace ssrt {

int hiZLevelCount(int width, int height) {
    int levels = 1;
    while (width > 1 || height > 1) {
        width = std::max(1, (width + 1) / 2);
        height = std::max(1, (height + 1) / 2);
        ++levels;
    }
    return levels;
}

namespace {

constexpr int kRowsPerTask = 16;

// Level 0: viewZ with background (not > 0) as +infinity.
void copyLevel0(const PlaneF& viewZ, PlaneF& minZ, int threads) {
    const int w = viewZ.width(), h = viewZ.height();
    const float inf = std::numeric_limits<float>::infinity();
    parallelFor((h + kRowsPerTask - 1) / kRowsPerTask, threads, [&](int task) {
        const int y1 = std::min(h, (task + 1) * kRowsPerTask);
        for (int y = task * kRowsPerTask; y < y1; ++y) {
            const float* src = viewZ.row(y);
            float* lo = minZ.row(y);
            for (int x = 0; x < w; ++x) lo[x] = src[x] > 0.0f ? src[x] : inf;
        }
    });
}

// Level k from level k-1: the min over the (up to) 2x2 cells below.
void reduceLevel(const PlaneF& srcMin, PlaneF& minZ, int threads) {
    const int pw = srcMin.width(), ph = srcMin.height();
    const int w = minZ.width(), h = minZ.height();
    parallelFor((h + kRowsPerTask - 1) / kRowsPerTask, threads, [&](int task) {
        const int y1 = std::min(h, (task + 1) * kRowsPerTask);
        for (int y = task * kRowsPerTask; y < y1; ++y) {
            const int sy0 = std::min(2 * y, ph - 1), sy1 = std::min(2 * y + 1, ph - 1);
            const float* a0 = srcMin.row(sy0);
            const float* a1 = srcMin.row(sy1);
            float* lo = minZ.row(y);
            for (int x = 0; x < w; ++x) {
                const int sx0 = std::min(2 * x, pw - 1), sx1 = std::min(2 * x + 1, pw - 1);
                lo[x] = std::min(std::min(a0[sx0], a0[sx1]), std::min(a1[sx0], a1[sx1]));
            }
        }
    });
}

}  // namespace

// HiZPyramid::invMinPacked is built once per pyramid here (marchRays used to pack its own
// copy every call: twice a frame, an 11 MB allocation each at 1080p).
bool packInverseMin(const std::vector<PlaneF>& minZ, HiZPacked& packed,
                    std::vector<std::size_t>& offset, int threads) {
    offset.assign(minZ.size(), 0);
    std::size_t total = 0;
    for (std::size_t L = 0; L < minZ.size(); ++L) {
        offset[L] = total;
        total += std::size_t(hiZPackedPitch(minZ[L].width())) *
                 std::size_t(hiZPackedTiles(minZ[L].height())) * kHiZPackedTileSize;
    }
    if (total >= kHiZMaxPacked) {
        packed.clear();
        offset.clear();
        return false;
    }
    packed.resize(total);
    // One job per row of tiles of every level (level 0 alone is three quarters of the work).
    std::vector<int> firstRow(minZ.size() + 1, 0);
    for (std::size_t L = 0; L < minZ.size(); ++L)
        firstRow[L + 1] = firstRow[L] + hiZPackedTiles(minZ[L].height());
    parallelFor(firstRow.back(), threads, [&](int job) {
        const std::size_t L = std::size_t(std::upper_bound(firstRow.begin(), firstRow.end(), job) -
                                          firstRow.begin() - 1);
        const PlaneF& p = minZ[L];
        const int w = p.width(), h = p.height(), tilesX = hiZPackedPitch(w);
        const int ty = job - firstRow[L];
        float* out =
            packed.data() + offset[L] + std::size_t(ty) * std::size_t(tilesX) * kHiZPackedTileSize;
        for (int r = 0; r < kHiZPackedTile; ++r) {
            const int y = ty * kHiZPackedTile + r;
            float* dst = out + std::size_t(r * kHiZPackedTile);
            if (y >= h) {
                for (int tx = 0; tx < tilesX; ++tx)
                    std::fill_n(dst + std::size_t(tx) * kHiZPackedTileSize, kHiZPackedTile, 0.0f);
                continue;
            }
            const float* src = p.row(y);
            const int whole = w / kHiZPackedTile;  // tiles with no padding column
            for (int tx = 0; tx < whole; ++tx)
                for (int i = 0; i < kHiZPackedTile; ++i)
                    dst[std::size_t(tx) * kHiZPackedTileSize + std::size_t(i)] =
                        1.0f / src[tx * kHiZPackedTile + i];
            for (int x = whole * kHiZPackedTile; x < tilesX * kHiZPackedTile; ++x)
                dst[std::size_t(x / kHiZPackedTile) * kHiZPackedTileSize +
                    std::size_t(x % kHiZPackedTile)] =
                    x < w ? 1.0f / src[x] : 0.0f;  // padding: background
        }
    });
    return true;
}

void buildHiZ(const PlaneF& viewZ, HiZPyramid& pyramid, int threads) {
    if (viewZ.empty()) throw std::invalid_argument("buildHiZ: viewZ is empty");
    const int levels = hiZLevelCount(viewZ.width(), viewZ.height());
    pyramid.minZ.resize(std::size_t(levels));
    int w = viewZ.width(), h = viewZ.height();
    for (int k = 0; k < levels; ++k) {
        pyramid.minZ[std::size_t(k)].ensureSize(w, h);
        w = std::max(1, (w + 1) / 2);
        h = std::max(1, (h + 1) / 2);
    }
    copyLevel0(viewZ, pyramid.minZ[0], threads);
    for (std::size_t k = 1; k < std::size_t(levels); ++k)
        reduceLevel(pyramid.minZ[k - 1], pyramid.minZ[k], threads);
    packInverseMin(pyramid.minZ, pyramid.invMinPacked, pyramid.packedOffset, threads);
}

}  // namespace ssrt
