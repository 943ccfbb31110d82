#include "trace/reconstruct.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "trace/reconstruct_kernel.h"

namespace ssrt {

namespace {

template <class P>
void planes(const ReconstructPlanesOf<P>& s, PlaneCheck& need, const char* what,
            const float* (&to)[kRecN]) {
    P* const all[kRecN] = {s.color[0], s.color[1],    s.color[2], s.opacity,
                           s.hit,      s.hitDistance, s.steps};
    const bool color = s.color[0] || s.color[1] || s.color[2];
    for (int k = 0; k < kRecN; ++k) {
        to[k] = nullptr;
        if (all[k] || (k < 3 && color)) to[k] = need(all[k], what);
    }
}

// The arguments both share: guides and camera.
ReconstructArgs guideArgs(const ReconstructGuides& g) {
    const int w = g.camera.width, h = g.camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("reconstruction: empty camera");
    ReconstructArgs a{};
    a.width = w;
    a.height = h;
    a.tilesX = TileGrid(w, h).tilesX;
    requireGBuffer("reconstruction", g.g, kGViewZ | kGNormal, w, h);
    a.g = g.g;
    a.scaleX = 2.0f * g.camera.tanHalfX / float(w);
    a.scaleY = 2.0f * g.camera.tanHalfY / float(h);
    a.tanHalfX = g.camera.tanHalfX;
    a.tanHalfY = g.camera.tanHalfY;
    for (int i = 0; i < 9; ++i) a.viewToWorld[i] = g.camera.viewToWorld[i];
    a.invTolerance = 1.0f / kReconstructPlaneTolerance;
    a.cutMark = kPdfLayoutCut;
    a.stride = g.g.stride;
    return a;
}

// The checkerboard's tiles in parallel. The fill writes in place and reads each cut pixel's edge
// neighbours, up to one pixel into the next tile: it runs in two colours of tiles ((tx + ty)
// & 1), so that no tile is written while an edge neighbour reads it. (What it reads there is
// traced pixels, never written; the colours keep the loads of the lanes it drops race-free.)
uint64_t runCheckerboard(Isa isa, const ReconstructArgs& a, int threads) {
    const TileGrid grid(a.width, a.height);
    std::vector<uint64_t> filled(std::size_t(grid.count()), 0);
    const auto kernel = SSRT_DISPATCH(isa, reconstructTile);
    for (int colour = 0; colour < 2; ++colour) {
        std::vector<int> tiles;
        for (int t = 0; t < grid.count(); ++t)
            if (((t % grid.tilesX + t / grid.tilesX) & 1) == colour) tiles.push_back(t);
        parallelForTiles(int(tiles.size()), threads, [&](int i) {
            const int tile = tiles[std::size_t(i)];
            kernel(a, tile, filled[std::size_t(tile)]);
        });
    }
    uint64_t total = 0;
    for (uint64_t n : filled) total += n;
    return total;
}

}  // namespace

uint64_t fillCheckerboard(Isa isa, const ReconstructGuides& g, const PlaneF& pdf,
                          const ReconstructPlanes& out, int threads) {
    ReconstructArgs a = guideArgs(g);
    PlaneCheck need("reconstruction", a.width, a.height);
    a.half = false;
    a.pdf = need(pdf, "ray pdf");
    if (out.steps) throw std::invalid_argument("fillCheckerboard: steps are not filled");
    const float* in[kRecN];
    planes(ReconstructSource{{out.color[0], out.color[1], out.color[2]},
                             out.opacity,
                             out.hit,
                             out.hitDistance,
                             nullptr},
           need, "output", in);
    for (int k = 0; k < kRecN; ++k) {
        a.in[k] = in[k];
        a.out[k] = const_cast<float*>(in[k]);  // the same planes: filled in place
    }
    a.srcWidth = a.width;
    a.srcHeight = a.height;
    a.srcStride = need.stride();
    a.outStride = need.stride();
    return runCheckerboard(isa, a, threads);
}

HalfUpsampler::HalfUpsampler(Isa isa, const ReconstructGuides& g, PixelOffset offset,
                             const PlaneF& halfPdf, const ReconstructSource& in) {
    ReconstructArgs& a = args_;
    a = guideArgs(g);
    grid_ = TileGrid(a.width, a.height);
    a.half = true;
    a.offsetX = offset.x & 1;
    a.offsetY = offset.y & 1;
    a.srcWidth = (a.width + 1) / 2;
    a.srcHeight = (a.height + 1) / 2;
    PlaneCheck needHalf("reconstruction", a.srcWidth, a.srcHeight);
    a.pdf = needHalf(halfPdf, "half-resolution ray pdf");
    planes(in, needHalf, "half-resolution input", a.in);
    a.srcStride = needHalf.stride();
    kernel_ = SSRT_DISPATCH(isa, reconstructTile);
}

uint64_t HalfUpsampler::tile(int tile, const ReconstructPlanes& out, int x0, int y0) const {
    // The outputs' size: the frame's, or a tile's from (x0, y0) (one with the frame's size at
    // corner 0 is the frame's either way).
    const TileRect r = grid_.rect(tile);
    const PlaneF* any = nullptr;
    for (const PlaneF* p : {out.color[0], out.opacity, out.hit, out.hitDistance, out.steps})
        if (!any) any = p;
    if (!any) throw std::invalid_argument("reconstruction: no output");
    const int w = any->width(), h = any->height();
    if (!holdsTile({x0, y0}, w, h, r))
        throw std::invalid_argument("reconstruction: the outputs do not hold the tile");
    PlaneCheck need("reconstruction", w, h);
    ReconstructArgs a = args_;
    const float* o[kRecN];
    planes(out, need, "output", o);
    for (int k = 0; k < kRecN; ++k) a.out[k] = const_cast<float*>(o[k]);
    a.outStride = need.stride();
    a.outX0 = x0;
    a.outY0 = y0;
    // (An input without an output is not read; an output without an input is written 0,
    // opacity 1.)
    uint64_t filled = 0;
    kernel_(a, tile, filled);
    return filled;
}

uint64_t upsampleHalf(Isa isa, const ReconstructGuides& g, PixelOffset offset,
                      const PlaneF& halfPdf, const ReconstructSource& in,
                      const ReconstructPlanes& out, int threads) {
    const HalfUpsampler up(isa, g, offset, halfPdf, in);
    const int w = g.camera.width, h = g.camera.height;
    for (PlaneF* p : {out.color[0], out.color[1], out.color[2], out.opacity, out.hit,
                      out.hitDistance, out.steps})
        if (p) p->ensureSize(w, h);
    std::vector<uint64_t> filled(std::size_t(up.grid().count()), 0);
    parallelForTiles(up.grid().count(), threads,
                     [&](int t) { filled[std::size_t(t)] = up.tile(t, out); });
    uint64_t total = 0;
    for (uint64_t n : filled) total += n;
    return total;
}

}  // namespace ssrt
