#include "trace/ssgi.h"

#include <stdexcept>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "trace/ssgi_kernel.h"

namespace ssrt {

namespace {

template <class T>
void feedback(Isa isa, const SsgiFeedbackInputs& in, Plane<T> hitLight[3], int threads) {
    const int w = hitLight[0].width(), h = hitLight[0].height();
    if (w <= 0 || h <= 0) throw std::invalid_argument("addSsgiFeedback: empty hitLight");
    const TileGrid grid(w, h);
    SsgiFeedbackArgs a{};
    a.width = w;
    a.height = h;
    a.tilesX = grid.tilesX;
    requireGBuffer("addSsgiFeedback", in.g, kGViewZ | kGAlbedo | kGMetallic | kGMotion, w, h);
    a.g = in.g;
    PlaneCheck need("addSsgiFeedback", w, h);
    for (int c = 0; c < 3; ++c) {
        a.prevDiffuse[c] = need(in.prevDiffuse[c], "previous diffuse radiance");
        a.hitLight[c] = need.output(hitLight[c], "hitLight");
    }
    if (in.occlusion) a.occlusion = need(in.occlusion, "occlusion");
    a.stride = need.stride();
    const auto tileFn = SSRT_DISPATCH(isa, ssgiFeedbackTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { tileFn(a, tile); });
}

}  // namespace

void addSsgiFeedback(Isa isa, const SsgiFeedbackInputs& in, PlaneU16 hitLight[3], int threads) {
    feedback(isa, in, hitLight, threads);
}
void addSsgiFeedback(Isa isa, const SsgiFeedbackInputs& in, PlaneF hitLight[3], int threads) {
    feedback(isa, in, hitLight, threads);
}

SsgiResolver::SsgiResolver(Isa isa, const SsgiInputs& in, PlaneF out[3], int sample,
                           int sampleCount, PlaneF* pdfCopy)
    : grid_(in.camera.width, in.camera.height) {
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
    PlaneCheck need("resolveSsgi", w, h);
    const bool hitLight = in.hitLight[0] || in.hitLight[1] || in.hitLight[2];
    requireGBuffer("resolveSsgi", in.g, kGViewZ | (hitLight ? 0 : kGNormal | kGAlbedo | kGMetallic),
                   w, h);
    a.g = in.g;
    if (hitLight) {
        for (int c = 0; c < 3; ++c) a.hitLight[c] = need(in.hitLight[c], "hitLight");
    } else {
        a.shadow = need(in.shadow, "shadow");
        if (in.emission[0] || in.emission[1] || in.emission[2])
            for (int c = 0; c < 3; ++c) a.emission[c] = need(in.emission[c], "emission");
    }
    a.lighting = *in.lighting;
    // The camera's rotation is the one rays are turned to world with.
    for (int i = 0; i < 9; ++i) a.lighting.viewToWorld[i] = in.camera.viewToWorld[i];
    for (int c = 0; c < 3; ++c) a.out[c] = need.output(out[c], "output");
    if (pdfCopy) {
        pdfCopy->ensureSize(w, h);
        a.copyPdf = need.output(*pdfCopy, "pdf copy");
    }
    a.stride = need.stride();
    a.sample = sample;
    a.sampleCount = sampleCount;
    kernel_ = SSRT_DISPATCH(isa, ssgiTile);
}

void SsgiResolver::tile(int tile, const RayBatch& rays, const MarchResult& march) const {
    const TileRect r = grid_.rect(tile);
    const BatchCorner c = rays.corner;
    const int bw = rays.pdf.width(), bh = rays.pdf.height();
    if (!sameCornerHolds(rays, march, r))
        throw std::invalid_argument("resolveSsgi: the batches do not hold the tile");
    SsgiArgs a = args_;
    PlaneCheck need("resolveSsgi", bw, bh);
    const PlaneF* const dirs[3] = {&rays.dx, &rays.dy, &rays.dz};
    for (int k = 0; k < 3; ++k) a.rayDir[k] = need(dirs[k], "ray direction");
    a.pdf = need(&rays.pdf, "ray pdf");
    a.hit = need(&march.hit, "march hit");
    a.hitX = need(&march.hitX, "march hitX");
    a.hitY = need(&march.hitY, "march hitY");
    a.rayStride = need.stride();
    a.rayX0 = c.x0;
    a.rayY0 = c.y0;
    kernel_(a, tile);
}

void resolveSsgi(Isa isa, const SsgiInputs& in, const RayBatch& rays, const MarchResult& march,
                 PlaneF out[3], int sample, int sampleCount, int threads) {
    const SsgiResolver resolver(isa, in, out, sample, sampleCount);
    PlaneCheck need("resolveSsgi", in.camera.width, in.camera.height);  // the frame's batches
    need(&rays.pdf, "ray pdf");
    need(&march.hit, "march hit");
    parallelForTiles(resolver.grid().count(), threads,
                     [&](int t) { resolver.tile(t, rays, march); });
}

}  // namespace ssrt
