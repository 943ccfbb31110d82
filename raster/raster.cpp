#include "raster/raster.h"

#include <chrono>

#include "core/tiles.h"
#include "raster/binning.h"
#include "raster/tile_raster_kernel.h"

namespace ssrt {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

VisibilityBuffer rasterize(const Scene& scene, const TransformedVertices& vertices,
                           const RasterView& view, const RasterOptions& options, RasterStats& stats,
                           RasterTimes* times) {
    VisibilityBuffer vb;
    rasterize(scene, vertices, view, options, vb, stats, times);
    return vb;
}

void rasterize(const Scene& scene, const TransformedVertices& vertices, const RasterView& view,
               const RasterOptions& options, VisibilityBuffer& vb, RasterStats& stats,
               RasterTimes* times) {
    const auto t0 = std::chrono::steady_clock::now();
    const TileGrid grid(view.width, view.height);
    SetupChunks chunks = setupTriangles(scene, vertices, view, options.threads);
    for (const RasterStats& s : chunks.stats) stats += s;
    const std::vector<AlphaTriangle> alpha = std::move(chunks.alpha);
    const AlphaTestArgs alphaArgs{alpha.data(), &scene};
    Bins bins = binTriangles(std::move(chunks), grid, options.threads);
    stats.binEntries += bins.items.size();
    if (times) times->geometryMs += msSince(t0);

    const auto t1 = std::chrono::steady_clock::now();
    vb.depth.ensureSize(view.width, view.height);
    if (options.writeIds) vb.ids.ensureSize(view.width, view.height);
    else vb.ids = PlaneU32();
    const TileRasterArgs args{bins.triangles.data(),
                              bins.start.data(),
                              bins.items.data(),
                              view.width,
                              view.height,
                              grid.tilesX,
                              options.clearDepth,
                              vb.depth.row(0),
                              options.writeIds ? vb.ids.row(0) : nullptr,
                              vb.depth.stride(),
                              options.writeIds ? vb.ids.stride() : 0,
                              alpha.empty() ? nullptr : &alphaArgs};
    // Counters per tile, summed in tile order afterwards.
    std::vector<RasterStats> tileStats(grid.count());
    const auto kernel = SSRT_DISPATCH(options.isa, rasterTile);
    parallelForTiles(grid.count(), options.threads,
                     [&](int tile) { kernel(args, tile, tileStats[tile]); });
    for (const RasterStats& s : tileStats) stats += s;
    if (times) times->rasterMs += msSince(t1);
}

}  // namespace ssrt
