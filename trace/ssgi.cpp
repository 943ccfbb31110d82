#include "trace/ssgi.h"

#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/plane_view.h"
#include "core/tiles.h"
#include "trace/ssgi_kernel.h"

namespace ssrt {

namespace {

constexpr std::string_view kResolve = "resolveSsgi";

}  // namespace

SsgiResolver::SsgiResolver(Isa isa, const SsgiArgs& in, PlaneF out[3], int sample, int sampleCount,
                           PlaneF* pdfCopy)
    : args_(in), grid_(in.camera.width, in.camera.height) {
    const int w = in.camera.width, h = in.camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("resolveSsgi: empty camera");
    if (sampleCount < 1 || sample < 0 || sample >= sampleCount)
        throw std::invalid_argument("resolveSsgi: sample must be in [0, sampleCount)");
    if (!in.lighting) throw std::invalid_argument("resolveSsgi: lighting (DirectArgs) missing");
    for (int c = 0; c < 3; ++c) out[c].ensureSize(w, h);
    SsgiArgs& a = args_;
    a.width = w;
    a.height = h;
    a.tilesX = grid_.tilesX;
    const bool hitLight = a.hitLight[0] || a.hitLight[1] || a.hitLight[2];
    requireGBuffer(kResolve, a.g, kGViewZ | (hitLight ? 0 : kGNormal | kGAlbedo | kGMetallic), w,
                   h);
    const OutF o[3] = {outputOf(out[0], "output.R"), outputOf(out[1], "output.G"),
                       outputOf(out[2], "output.B")};
    a.stride = requireViews(kResolve, w, h, {o[0], o[1], o[2]});
    if (hitLight) requireViews(kResolve, w, h, {a.hitLight[0], a.hitLight[1], a.hitLight[2]});
    else if (a.emission[0] || a.emission[1] || a.emission[2])
        requireViews(kResolve, w, h, {a.shadow, a.emission[0], a.emission[1], a.emission[2]});
    else requireViews(kResolve, w, h, {a.shadow});
    a.light = *in.lighting;
    // The camera's rotation is the one rays are turned to world with.
    for (int i = 0; i < 9; ++i) a.light.viewToWorld[i] = in.camera.viewToWorld[i];
    for (int c = 0; c < 3; ++c) a.out[c] = o[c].data;
    if (pdfCopy) {
        pdfCopy->ensureSize(w, h);
        const OutF copy = outputOf(*pdfCopy, "ray.pdf");
        requireViews(kResolve, w, h, {copy});
        a.copyPdf = copy.data;
    }
    a.sample = sample;
    a.sampleCount = sampleCount;
    kernel_ = SSRT_DISPATCH(isa, ssgiTile);
}

void SsgiResolver::tile(int tile, const RayBatch& rays, const MarchResult& march,
                        std::span<const WorldLit> lit) const {
    const TileRect r = grid_.rect(tile);
    const BatchCorner c = rays.corner;
    if (!sameCornerHolds(rays, march, r))
        throw std::invalid_argument("resolveSsgi: the batches do not hold the tile");
    SsgiArgs a = args_;
    const ViewF dx = viewOf(rays.dx, "ray.dx"), dy = viewOf(rays.dy, "ray.dy"),
                dz = viewOf(rays.dz, "ray.dz"), pdf = viewOf(rays.pdf, "ray.pdf"),
                hit = viewOf(march.hit, "march.hit"), hitX = viewOf(march.hitX, "march.hitX"),
                hitY = viewOf(march.hitY, "march.hitY");
    a.rayStride = requireViews(kResolve, rays.pdf.width(), rays.pdf.height(),
                               {dx, dy, dz, pdf, hit, hitX, hitY});
    a.rayDir[0] = dx.data, a.rayDir[1] = dy.data, a.rayDir[2] = dz.data;
    a.pdf = pdf.data;
    a.hit = hit.data;
    a.hitX = hitX.data;
    a.hitY = hitY.data;
    a.rayX0 = c.x0;
    a.rayY0 = c.y0;
    a.lit = lit.data();
    a.litCount = int(lit.size());
    if (kernel_(a, tile) != a.litCount)
        throw std::logic_error("resolveSsgi: a lit world hit outside its tile, or out of order");
}

void resolveSsgi(Isa isa, const SsgiArgs& in, const RayBatch& rays, const MarchResult& march,
                 PlaneF out[3], int sample, int sampleCount, int threads,
                 std::span<const WorldLit> lit) {
    const SsgiResolver resolver(isa, in, out, sample, sampleCount);
    // The frame's batches, of the frame's size.
    requireViews(kResolve, in.camera.width, in.camera.height,
                 {viewOf(rays.pdf, "ray.pdf"), viewOf(march.hit, "march.hit")});
    // Each tile's lit hits (the frame's row order keeps each tile's in its row order).
    const TileGrid& grid = resolver.grid();
    std::vector<std::vector<WorldLit>> byTile(lit.empty() ? 0 : std::size_t(grid.count()));
    for (const WorldLit& l : lit)
        byTile[std::size_t(grid.tilesX * (l.y / kTileSize) + l.x / kTileSize)].push_back(l);
    parallelForTiles(grid.count(), threads, [&](int t) {
        resolver.tile(t, rays, march,
                      byTile.empty() ? std::span<const WorldLit>() : byTile[std::size_t(t)]);
    });
}

}  // namespace ssrt
