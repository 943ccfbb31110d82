#include "trace/ray_gen.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/tiles.h"

namespace ssrt {

std::string_view ssrMethodName(SsrMethod m) {
    switch (m) {
        case SsrMethod::Mirror: return "mirror";
        case SsrMethod::GgxNdf: return "ggx_ndf";
        case SsrMethod::VndfEllipsoid: return "vndf_ellipsoid";
        case SsrMethod::VndfSphericalCaps: return "vndf_spherical_caps";
        case SsrMethod::VndfBounded: return "vndf_bounded";
    }
    return "?";
}

std::optional<SsrMethod> parseSsrMethod(std::string_view name) {
    for (SsrMethod m : kAllSsrMethods)
        if (ssrMethodName(m) == name) return m;
    return std::nullopt;
}

void RayGenStats::add(const RayGenStats& o) {
    pixels += o.pixels;
    rays += o.rays;
    belowSurface += o.belowSurface;
    background += o.background;
    hidden += o.hidden;
    cut += o.cut;
    sparse += o.sparse;
}

RayGenerator::RayGenerator(Isa isa, RayGenLobe lobe, uint32_t frame, uint32_t sample, uint32_t dim,
                           const TraceCamera& camera, const GBufferView& g, float maxRoughness,
                           bool onlyDiffuse, RayGenCheckerboard checkerboard)
    : grid_(camera.width, camera.height) {
    if (std::isnan(maxRoughness))
        throw std::invalid_argument("ray generation: maxRoughness is NaN");
    if (camera.width <= 0 || camera.height <= 0)
        throw std::invalid_argument("ray generation: the camera has no pixels");
    const bool sparse = checkerboard.on && checkerboard.historyFrames.data;
    const GBufferPlanes need = kGViewZ | kGNormal |
                               (lobe != RayGenLobe::Diffuse ? kGRoughness : 0) |
                               (onlyDiffuse ? kGAlbedo | kGMetallic : 0) | (sparse ? kGMotion : 0);
    requireGBuffer("ray generation", g, need, camera.width, camera.height);
    const std::size_t historyStride =
        sparse ? requireViews("ray generation", camera.width, camera.height,
                              {checkerboard.historyFrames})
               : 0;
    RayGenArgs& a = args_;
    a.lobe = lobe;
    a.g = g;
    a.width = camera.width;
    a.height = camera.height;
    a.tilesX = grid_.tilesX;
    a.tanHalfX = camera.tanHalfX;
    a.tanHalfY = camera.tanHalfY;
    a.originX = camera.pointX;
    a.originY = camera.pointY;
    std::copy_n(camera.viewToWorld, 9, a.viewToWorld);
    a.frame = frame;
    a.sample = sample;
    a.dim = dim;
    a.maxRoughness = maxRoughness;
    a.checkerboard = checkerboard.on;
    a.checkerPhase = checkerboard.phase & 1u;
    a.cutPdf = kPdfLayoutCut;
    a.historyFrames = sparse ? checkerboard.historyFrames.data : nullptr;
    a.historyStride = historyStride;
    a.sparseMin = checkerboard.sparseMin;
    a.noDiffuseColour = onlyDiffuse;
    kernel_ = SSRT_DISPATCH(isa, generateRaysTile);
}

RayGenerator RayGenerator::specular(Isa isa, SsrMethod method, uint32_t frame, uint32_t sample,
                                    const TraceCamera& camera, const GBufferView& g,
                                    float maxRoughness, RayGenCheckerboard checkerboard) {
    return {isa,
            RayGenLobe(int(method)),
            frame,
            sample,
            kRayGenSpecularDim,
            camera,
            g,
            maxRoughness,
            false,
            checkerboard};
}

RayGenerator RayGenerator::diffuse(Isa isa, uint32_t frame, uint32_t sample,
                                   const TraceCamera& camera, const GBufferView& g, DiffuseCut cut,
                                   RayGenCheckerboard checkerboard) {
    return {isa,
            RayGenLobe::Diffuse,
            frame,
            sample,
            kRayGenDiffuseDim,
            camera,
            g,
            std::numeric_limits<float>::infinity(),
            cut == DiffuseCut::NoDiffuseColour,
            checkerboard};
}

RayGenStats RayGenerator::tile(int tile, RayBatch& rays) const {
    const TileRect r = grid_.rect(tile);
    const BatchCorner c = rays.corner;
    if (!holdsTile(c, rays.ox.width(), rays.ox.height(), r))
        throw std::invalid_argument("ray generation: the batch does not hold the tile");
    RayGenArgs a = args_;
    PlaneF* origin[3] = {&rays.ox, &rays.oy, &rays.oz};
    PlaneF* dir[3] = {&rays.dx, &rays.dy, &rays.dz};
    for (int i = 0; i < 3; ++i) {
        a.origin[i] = origin[i]->row(0);
        a.dir[i] = dir[i]->row(0);
    }
    a.pdf = rays.pdf.row(0);
    a.outStride = rays.ox.stride();
    a.outX0 = c.x0;
    a.outY0 = c.y0;
    // A frame's batch is read by the next pass, long after: past the cache.
    a.stream = rays.ox.width() == a.width && rays.ox.height() == a.height;
    RayGenCounts n{};
    kernel_(a, tile, n);
    return {n.pixels, n.rays, n.belowSurface, n.background, n.hidden, n.cut, n.sparse};
}

RayGenStats RayGenerator::frame(RayBatch& rays, int threads) const {
    rays.ensureSize(args_.width, args_.height);
    rays.corner = {};
    std::vector<RayGenStats> counts(std::size_t(grid_.count()));
    parallelForTiles(grid_.count(), threads,
                     [&](int t) { counts[std::size_t(t)] = tile(t, rays); });
    RayGenStats stats;
    for (const RayGenStats& c : counts) stats.add(c);
    return stats;
}

RayGenStats generateSpecularRays(Isa isa, SsrMethod method, uint32_t frame, uint32_t sample,
                                 const TraceCamera& camera, const GBufferView& g, RayBatch& rays,
                                 int threads, float maxRoughness, RayGenCheckerboard checkerboard) {
    return RayGenerator::specular(isa, method, frame, sample, camera, g, maxRoughness, checkerboard)
        .frame(rays, threads);
}

RayGenStats generateDiffuseRays(Isa isa, uint32_t frame, uint32_t sample, const TraceCamera& camera,
                                const GBufferView& g, RayBatch& rays, int threads, DiffuseCut cut,
                                RayGenCheckerboard checkerboard) {
    return RayGenerator::diffuse(isa, frame, sample, camera, g, cut, checkerboard)
        .frame(rays, threads);
}

}  // namespace ssrt
