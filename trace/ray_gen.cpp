#include "trace/ray_gen.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

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

void checkPlane(const PlaneF* p, const char* what, const TraceCamera& cam, std::size_t& stride) {
    if (!p) throw std::invalid_argument(std::string("ray generation: no G-buffer plane ") + what);
    if (p->width() != cam.width || p->height() != cam.height)
        throw std::invalid_argument(std::string("ray generation: G-buffer plane ") + what + " is " +
                                    std::to_string(p->width()) + "x" + std::to_string(p->height()) +
                                    ", the camera " + std::to_string(cam.width) + "x" +
                                    std::to_string(cam.height));
    if (stride != 0 && p->stride() != stride)
        throw std::invalid_argument(std::string("ray generation: G-buffer plane ") + what +
                                    " has a different row stride");
    stride = p->stride();
}

// Set-up shared by both passes: checks, arguments, the tile loop, counters in tile order.
RayGenStats run(Isa isa, RayGenLobe lobe, uint32_t frame, uint32_t sample, uint32_t dim,
                const TraceCamera& camera, const RayGenGBuffer& g, RayBatch& rays, int threads,
                float maxRoughness, bool onlyDiffuse, RayGenCheckerboard checkerboard) {
    if (std::isnan(maxRoughness))
        throw std::invalid_argument("ray generation: maxRoughness is NaN");
    if (camera.width <= 0 || camera.height <= 0)
        throw std::invalid_argument("ray generation: the camera has no pixels");
    std::size_t gStride = 0;
    checkPlane(g.viewZ, "viewZ", camera, gStride);
    checkPlane(g.normal[0], "normal.X", camera, gStride);
    checkPlane(g.normal[1], "normal.Y", camera, gStride);
    checkPlane(g.normal[2], "normal.Z", camera, gStride);
    if (lobe != RayGenLobe::Diffuse) checkPlane(g.roughness, "roughness", camera, gStride);
    if (onlyDiffuse) {
        checkPlane(g.albedo[0], "albedo.R", camera, gStride);
        checkPlane(g.albedo[1], "albedo.G", camera, gStride);
        checkPlane(g.albedo[2], "albedo.B", camera, gStride);
        checkPlane(g.metallic, "metallic", camera, gStride);
    }
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
