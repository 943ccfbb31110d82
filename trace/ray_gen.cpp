#include "trace/ray_gen.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "trace/ray_gen_kernel.h"

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
}

namespace {

// Set-up shared by both passes: checks, arguments, the tile loop, counters in tile order.
RayGenStats run(Isa isa, RayGenLobe lobe, uint32_t frame, uint32_t sample, uint32_t dim,
                const TraceCamera& camera, const RayGenGBuffer& g, RayBatch& rays, int threads,
                float maxRoughness, bool onlyDiffuse, RayGenCheckerboard checkerboard) {
    if (std::isnan(maxRoughness))
        throw std::invalid_argument("ray generation: maxRoughness is NaN");
    if (camera.width <= 0 || camera.height <= 0)
        throw std::invalid_argument("ray generation: the camera has no pixels");
    PlaneCheck need("ray generation", camera.width, camera.height);
    need(g.viewZ, "viewZ");
    need(g.normal[0], "normal.X");
    need(g.normal[1], "normal.Y");
    need(g.normal[2], "normal.Z");
    if (lobe != RayGenLobe::Diffuse) need(g.roughness, "roughness");
    if (onlyDiffuse) {
        need(g.albedo[0], "albedo.R");
        need(g.albedo[1], "albedo.G");
        need(g.albedo[2], "albedo.B");
        need(g.metallic, "metallic");
    }
    const std::size_t gStride = need.stride();
    rays.ensureSize(camera.width, camera.height);

    RayGenArgs a{};
    a.lobe = lobe;
    a.g[0] = g.viewZ->row(0);
    for (int i = 0; i < 3; ++i) a.g[1 + i] = g.normal[i]->row(0);
    a.g[4] = lobe != RayGenLobe::Diffuse ? g.roughness->row(0) : nullptr;
    a.gStride = gStride;
    PlaneF* out[7] = {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.pdf};
    for (int i = 0; i < 7; ++i) a.out[i] = out[i]->row(0);
    a.outStride = rays.ox.stride();
    const TileGrid grid(camera.width, camera.height);
    a.width = camera.width;
    a.height = camera.height;
    a.tilesX = grid.tilesX;
    a.tanHalfX = camera.tanHalfX;
    a.tanHalfY = camera.tanHalfY;
    std::copy_n(camera.viewToWorld, 9, a.viewToWorld);
    a.frame = frame;
    a.sample = sample;
    a.dim = dim;
    a.maxRoughness = maxRoughness;
    a.checkerboard = checkerboard.on;
    a.checkerPhase = checkerboard.phase & 1u;
    a.cutPdf = kPdfLayoutCut;
    if (onlyDiffuse) {
        for (int c = 0; c < 3; ++c) a.diffuse[c] = g.albedo[c]->row(0);
        a.diffuse[3] = g.metallic->row(0);
    }

    std::vector<RayGenCounts> counts(std::size_t(grid.count()));
    auto* kernel = SSRT_DISPATCH(isa, generateRaysTile);
    parallelForTiles(grid.count(), threads,
                     [&](int tile) { kernel(a, tile, counts[std::size_t(tile)]); });
    RayGenStats stats;
    for (const RayGenCounts& c : counts)
        stats.add({c.pixels, c.rays, c.belowSurface, c.background, c.hidden, c.cut});
    return stats;
}

}  // namespace

RayGenStats generateSpecularRays(Isa isa, SsrMethod method, uint32_t frame, uint32_t sample,
                                 const TraceCamera& camera, const RayGenGBuffer& g, RayBatch& rays,
                                 int threads, float maxRoughness, RayGenCheckerboard checkerboard) {
    return run(isa, RayGenLobe(int(method)), frame, sample, kRayGenSpecularDim, camera, g, rays,
               threads, maxRoughness, false, checkerboard);
}

RayGenStats generateDiffuseRays(Isa isa, uint32_t frame, uint32_t sample, const TraceCamera& camera,
                                const RayGenGBuffer& g, RayBatch& rays, int threads, DiffuseCut cut,
                                RayGenCheckerboard checkerboard) {
    return run(isa, RayGenLobe::Diffuse, frame, sample, kRayGenDiffuseDim, camera, g, rays, threads,
               std::numeric_limits<float>::infinity(), cut == DiffuseCut::NoDiffuseColour,
               checkerboard);
}

}  // namespace ssrt
