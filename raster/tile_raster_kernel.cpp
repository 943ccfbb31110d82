#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>
#include <cstring>

#include "core/lanes.h"
#include "core/tiles.h"
#include "raster/tile_raster_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using ILane = ln::IntOf<Lane>;

namespace {

constexpr int kBlockPixels = kBlockSize * kBlockSize;
constexpr int kChunks = kBlockPixels / kW;  // lane groups per 8x8 block
constexpr int kBlocksPerSide = kTileSize / kBlockSize;
constexpr uint32_t kNoPrimitiveId = 0xffffffffu;  // raster.h's kNoPrimitive
static_assert(kBlocksPerSide * kBlocksPerSide <= 64, "touched-block mask is 64 bits");
static_assert(kBlockPixels % kW == 0, "a block must hold whole lane groups");

// Lane l of a group covers block pixel (i0 + laneDI[l], j0 + laneDJ[l]), where group c
// starts at pixel c * kW in row-major block order (i0 = c*kW mod 8, j0 = c*kW / 8).
// Built at compile time: a kernel source must run no code before its ISA is chosen (a static
// initialiser compiled with AVX-512 flags would crash an older CPU at start-up).
struct LaneLayout {
    alignas(64) int32_t di[kW] = {};
    alignas(64) int32_t dj[kW] = {};
    alignas(64) float fdi[kW] = {};
    alignas(64) float fdj[kW] = {};
    alignas(64) int32_t bit[kW] = {};  // 1 << l: a lane mask from a bit mask
    constexpr LaneLayout() {
        for (int l = 0; l < kW; ++l) {
            di[l] = l % kBlockSize;
            dj[l] = l / kBlockSize;
            fdi[l] = float(di[l]);
            fdj[l] = float(dj[l]);
            bit[l] = int32_t(1) << l;
        }
    }
};
constexpr LaneLayout kLayout{};

struct TileBuffers {
    alignas(64) float depth[kTileSize * kTileSize];
    alignas(64) int32_t ids[kTileSize * kTileSize];
    uint64_t touched;  // bit b: block b has been cleared (and maybe written)
};

inline int popcount(uint64_t bits) { return __builtin_popcountll(bits); }

struct EdgeLanes {
    ILane offset[3];  // a * di + b * dj per lane
};

SSRT_INLINE EdgeLanes edgeLanes(const TriangleSetup& t) {
    EdgeLanes e;
    for (int k = 0; k < 3; ++k) {
        alignas(64) int32_t v[kW];
        for (int l = 0; l < kW; ++l) v[l] = t.a[k] * kLayout.di[l] + t.b[k] * kLayout.dj[l];
        e.offset[k] = ln::loadInt<Lane>(v);
    }
    return e;
}

// Block classification against one edge: -1 all outside, 1 all inside, 0 partial.
// Also returns K0 = floor(E'(first pixel centre) / 256), clamped (see raster/setup.h).
SSRT_INLINE int classifyEdge(const TriangleSetup& t, int k, int64_t sx, int64_t sy, int32_t& k0) {
    const int64_t e0 = int64_t(t.a[k]) * sx + int64_t(t.b[k]) * sy + t.c[k];
    const int64_t ex = int64_t(t.a[k]) * ((kBlockSize - 1) * kSubPixel);
    const int64_t ey = int64_t(t.b[k]) * ((kBlockSize - 1) * kSubPixel);
    const int64_t lo = e0 + std::min<int64_t>(ex, 0) + std::min<int64_t>(ey, 0);
    const int64_t hi = e0 + std::max<int64_t>(ex, 0) + std::max<int64_t>(ey, 0);
    k0 = int32_t(std::clamp<int64_t>(e0 >> kSubPixelBits, -kMaxK0, kMaxK0));
    return hi < 0 ? -1 : (lo >= 0 ? 1 : 0);
}

// kAlphaTested: t is an alpha-tested triangle (raster/alpha_test.h); the pixels that pass the
// depth test are then kept only where alphaTestPixels says so, before anything is written.
// Inlined, with the helpers above, into both of rasterTriangles' copies, as they were into
// their one caller before there were two: GCC put classifyEdge out of line once it had two
// callers, a call per edge and block, and the opaque raster ran 13 % more instructions
// (callgrind, bunny 960x540, AVX2) and about 1.5x the time on BM_RasterLarge.
template <bool kAlphaTested>
SSRT_INLINE void rasterBlock(const TileRasterArgs& args, const TriangleSetup& t,
                             const EdgeLanes& edges, int blockX, int blockY, float* depth,
                             int32_t* ids, RasterStats& stats) {
    const int64_t sx = int64_t(blockX) * kSubPixel + kSubPixel / 2;
    const int64_t sy = int64_t(blockY) * kSubPixel + kSubPixel / 2;
    int32_t k0[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
        const int c = classifyEdge(t, k, sx, sy, k0[k]);
        if (c < 0) {
            ++stats.blocksRejected;
            return;
        }
        inside &= c > 0;
    }
    ++(inside ? stats.blocksAccepted : stats.blocksPartial);
    const bool border = blockX + kBlockSize > args.width || blockY + kBlockSize > args.height;
    const Lane zBase(t.zBase), zdx(t.zdx), zdy(t.zdy);
    const Lane fdi = ln::load<Lane>(kLayout.fdi), fdj = ln::load<Lane>(kLayout.fdj);
    const uint32_t slot = t.primId & ~kAlphaTestedBit;  // kAlphaTested only
    const ILane prim(int32_t(kAlphaTested ? args.alpha->triangles[slot].primId : t.primId));
    // Only the lane groups that meet the triangle's pixel bounds (small triangles touch a
    // few rows of a block, not all eight).
    const int rowLo = std::max(t.minY - blockY, 0),
              rowHi = std::min(t.maxY - blockY, kBlockSize - 1);
    const int colLo = std::max(t.minX - blockX, 0),
              colHi = std::min(t.maxX - blockX, kBlockSize - 1);
    for (int c = 0; c < kChunks; ++c) {
        const int i0 = (c * kW) % kBlockSize, j0 = (c * kW) / kBlockSize;
        const int j1 = (c * kW + kW - 1) / kBlockSize,
                  i1 = kW >= kBlockSize ? kBlockSize - 1 : i0 + kW - 1;
        if (j1 < rowLo || j0 > rowHi || i1 < colLo || i0 > colHi) continue;
        const Lane px = Lane(float(blockX + i0)) + fdi;  // exact: small integers
        const Lane py = Lane(float(blockY + j0)) + fdj;
        auto valid = px == px;  // all true
        if (border) valid = (px < Lane(float(args.width))) & (py < Lane(float(args.height)));
        auto covered = valid;
        if (!inside) {
            ILane kk[3];
            for (int k = 0; k < 3; ++k)
                kk[k] = ILane(k0[k] + t.a[k] * i0 + t.b[k] * j0) + edges.offset[k];
            covered = valid & ln::toFloatMask((kk[0] | kk[1] | kk[2]) >= ILane(0));
        }
        const uint64_t coveredBits = ln::maskBits(covered);
        stats.pixelsTested += popcount(ln::maskBits(valid));
        if (!coveredBits) continue;
        stats.pixelsCovered += popcount(coveredBits);
        // Depth key at each pixel centre, the same expression on every ISA.
        const Lane z =
            (zBase + zdx * (px - Lane(float(t.minX)))) + zdy * (py - Lane(float(t.minY)));
        float* dp = depth + c * kW;
        const Lane zb = ln::load<Lane>(dp);
        auto pass = covered & (z > zb);
        uint64_t passBits = ln::maskBits(pass);
        if (!passBits) continue;
        if constexpr (kAlphaTested) {
            const uint64_t kept =
                alphaTestPixels(*args.alpha, slot, blockX, blockY, c * kW, passBits);
            stats.pixelsCutOut += popcount(passBits & ~kept);
            if (!kept) continue;
            const ILane bits = ILane(int32_t(kept)) & ln::loadInt<Lane>(kLayout.bit);
            pass = ln::toFloatMask(bits != ILane(0));
            passBits = kept;
        }
        stats.pixelsWritten += popcount(passBits);
        ln::store(dp, ln::select(pass, z, zb));
        if (ids) {
            int32_t* ip = ids + c * kW;
            ln::store(ip, ln::select(ln::toIntMask(pass), prim, ln::loadInt<Lane>(ip)));
        }
    }
}

// Copies one row to a plane in whole cache lines (streaming: no read for ownership). Bits
// are moved, never interpreted, so ids travel through float lanes unchanged.
void streamRow(float* dst, const float* src, int span) {
    for (int i = 0; i < span; i += kW) ln::storeStream(dst + i, ln::load<Lane>(src + i));
}

// Block-linear tile buffers to the planes' rows, gathered row by row into a line buffer;
// blocks no triangle touched give the clear values without reading the buffer. Lane groups
// past the right edge land in the rows' 64-byte padding.
void writeOut(const TileRasterArgs& args, const TileRect& r, const TileBuffers& buf) {
    alignas(64) float depthRow[kTileSize];
    alignas(64) uint32_t idRow[kTileSize];
    const int span = (r.x1 - r.x0 + kW - 1) / kW * kW;
    // What lands in the padding is defined too: the clear values.
    std::fill_n(depthRow, kTileSize, args.clearDepth);
    std::fill_n(idRow, kTileSize, kNoPrimitiveId);
    for (int y = r.y0; y < r.y1; ++y) {
        const int ly = y - r.y0;
        const int rowInBlock = (ly % kBlockSize) * kBlockSize;
        for (int bx = 0; bx * kBlockSize < r.x1 - r.x0; ++bx) {
            const int b = (ly / kBlockSize) * kBlocksPerSide + bx;
            float* d = depthRow + bx * kBlockSize;
            uint32_t* id = idRow + bx * kBlockSize;
            // (A depth-only pass, the shadow map's, neither keeps nor copies ids.)
            if (!(buf.touched >> b & 1)) {
                std::fill_n(d, kBlockSize, args.clearDepth);
                if (args.ids) std::fill_n(id, kBlockSize, kNoPrimitiveId);
            } else {
                std::memcpy(d, buf.depth + b * kBlockPixels + rowInBlock,
                            sizeof(float) * kBlockSize);
                if (args.ids)
                    std::memcpy(id, buf.ids + b * kBlockPixels + rowInBlock,
                                sizeof(float) * kBlockSize);
            }
        }
        streamRow(args.depth + std::size_t(y) * args.depthStride + r.x0, depthRow, span);
        if (args.ids)
            streamRow(reinterpret_cast<float*>(args.ids + std::size_t(y) * args.idStride + r.x0),
                      reinterpret_cast<const float*>(idRow), span);
    }
    ln::streamFence();
}

// The tile's triangles in bin order. kAnyAlphaTested: the pass has alpha-tested triangles,
// told apart by their id; without, the loop never looks at an id.
template <bool kAnyAlphaTested>
SSRT_INLINE void rasterTriangles(const TileRasterArgs& args, const TileRect& r, int tile,
                                 TileBuffers& buf, RasterStats& stats) {
    for (uint32_t n = args.binStart[tile]; n < args.binStart[tile + 1]; ++n) {
        const TriangleSetup& t = args.triangles[args.binItems[n]];
        const EdgeLanes edges = edgeLanes(t);
        const bool tested = kAnyAlphaTested && (t.primId & kAlphaTestedBit);
        // Blocks of this tile that the triangle's pixel bounds touch.
        const int bx0 = (std::max(t.minX, r.x0) - r.x0) / kBlockSize;
        const int by0 = (std::max(t.minY, r.y0) - r.y0) / kBlockSize;
        const int bx1 = (std::min(t.maxX, r.x1 - 1) - r.x0) / kBlockSize;
        const int by1 = (std::min(t.maxY, r.y1 - 1) - r.y0) / kBlockSize;
        for (int by = by0; by <= by1; ++by)
            for (int bx = bx0; bx <= bx1; ++bx) {
                const int b = by * kBlocksPerSide + bx;
                if (!(buf.touched >> b & 1)) {
                    buf.touched |= uint64_t(1) << b;
                    std::fill_n(buf.depth + b * kBlockPixels, kBlockPixels, args.clearDepth);
                    if (args.ids)
                        std::fill_n(buf.ids + b * kBlockPixels, kBlockPixels, int32_t(-1));
                }
                const int x = r.x0 + bx * kBlockSize, y = r.y0 + by * kBlockSize;
                int32_t* ids = args.ids ? buf.ids + b * kBlockPixels : nullptr;
                if (tested)
                    rasterBlock<true>(args, t, edges, x, y, buf.depth + b * kBlockPixels, ids,
                                      stats);
                else
                    rasterBlock<false>(args, t, edges, x, y, buf.depth + b * kBlockPixels, ids,
                                       stats);
            }
    }
}

}  // namespace

void rasterTile(const TileRasterArgs& args, int tile, RasterStats& stats) {
    const TileRect r = tileRect(tile, args.tilesX, args.width, args.height);
    static thread_local TileBuffers buf;
    buf.touched = 0;
    if (args.alpha) rasterTriangles<true>(args, r, tile, buf, stats);
    else rasterTriangles<false>(args, r, tile, buf, stats);
    writeOut(args, r, buf);
}

}  // namespace ssrt::SSRT_ISA_NS
