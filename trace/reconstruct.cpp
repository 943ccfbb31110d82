#include "trace/reconstruct.h"

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/plane_view.h"
#include "core/tiles.h"
#include "trace/reconstruct_kernel.h"

namespace ssrt {

namespace {

constexpr std::string_view kReconstructPass = "reconstruction";

// The names of a signal's planes in messages, in ReconstructPlane's order.
using PlaneNames = std::string_view[kRecN];
constexpr PlaneNames kOutputNames = {"output.R",       "output.G",   "output.B",
                                     "output.opacity", "output.hit", "output.hitDistance",
                                     "output.steps"},
                     kHalfNames = {"half.R",   "half.G",           "half.B",    "half.opacity",
                                   "half.hit", "half.hitDistance", "half.steps"};

// The first rows of `s`'s planes (null where absent; colour needs all three channels), each
// checked to w x h; their stride (`stride` where none is given).
template <class P>
std::size_t takePlanes(const ReconstructPlanesOf<P>& s, int w, int h, const PlaneNames& names,
                       const float* (&to)[kRecN], std::size_t stride) {
    P* const all[kRecN] = {s.color[0], s.color[1],    s.color[2], s.opacity,
                           s.hit,      s.hitDistance, s.steps};
    const bool color = s.color[0] || s.color[1] || s.color[2];
    for (int k = 0; k < kRecN; ++k) {
        to[k] = nullptr;
        if (!all[k] && !(k < 3 && color)) continue;
        const ViewF v = all[k] ? viewOf(*all[k], names[k]) : ViewF{nullptr, 0, 0, 0, names[k]};
        stride = requireViews(kReconstructPass, w, h, {v});
        to[k] = v.data;
    }
    return stride;
}

// The arguments both share: guides and camera.
ReconstructArgs guideArgs(const ReconstructGuides& g) {
    const int w = g.camera.width, h = g.camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("reconstruction: empty camera");
    ReconstructArgs a{};
    a.width = w;
    a.height = h;
    a.tilesX = TileGrid(w, h).tilesX;
    requireGBuffer(kReconstructPass, g.g, kGViewZ | kGNormal, w, h);
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

// The checkerboard's tiles in parallel. The fill writes in place and reads each cut pixel's
// eight neighbours, up to one pixel into the next tiles, corners included: it runs in four
// colours of tiles ((tx & 1) + 2 (ty & 1)), so that no tile is written while a neighbouring
// one reads it. (What it reads there is traced pixels, never written; the colours keep the
// loads of the lanes it drops race-free.)
uint64_t runCheckerboard(Isa isa, const ReconstructArgs& a, int threads) {
    const TileGrid grid(a.width, a.height);
    std::vector<uint64_t> filled(std::size_t(grid.count()), 0);
    const auto kernel = SSRT_DISPATCH(isa, reconstructTile);
    for (int colour = 0; colour < 4; ++colour) {
        std::vector<int> tiles;
        for (int t = 0; t < grid.count(); ++t)
            if (((t % grid.tilesX) & 1) + 2 * ((t / grid.tilesX) & 1) == colour) tiles.push_back(t);
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
    a.half = false;
    const ViewF pdfView = viewOf(pdf, "ray.pdf");
    std::size_t stride = requireViews(kReconstructPass, a.width, a.height, {pdfView});
    a.pdf = pdfView.data;
    if (out.steps) throw std::invalid_argument("fillCheckerboard: steps are not filled");
    const float* in[kRecN];
    stride = takePlanes(ReconstructSource{{out.color[0], out.color[1], out.color[2]},
                                          out.opacity,
                                          out.hit,
                                          out.hitDistance,
                                          nullptr},
                        a.width, a.height, kOutputNames, in, stride);
    for (int k = 0; k < kRecN; ++k) {
        a.in[k] = in[k];
        a.out[k] = const_cast<float*>(in[k]);  // the same planes: filled in place
    }
    a.srcWidth = a.width;
    a.srcHeight = a.height;
    a.srcStride = stride;
    a.outStride = stride;
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
    const ViewF pdf = viewOf(halfPdf, "half.ray.pdf");
    const std::size_t stride = requireViews(kReconstructPass, a.srcWidth, a.srcHeight, {pdf});
    a.pdf = pdf.data;
    a.srcStride = takePlanes(in, a.srcWidth, a.srcHeight, kHalfNames, a.in, stride);
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
    ReconstructArgs a = args_;
    const float* o[kRecN];
    a.outStride = takePlanes(out, w, h, kOutputNames, o, 0);
    for (int k = 0; k < kRecN; ++k) a.out[k] = const_cast<float*>(o[k]);
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
