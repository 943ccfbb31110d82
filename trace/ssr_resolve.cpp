#include "trace/ssr_resolve.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/plane_view.h"
#include "core/tiles.h"
#include "trace/ssr_resolve_kernel.h"

namespace ssrt {

std::string_view resolveModeName(SsrResolveMode mode) {
    return mode == SsrResolveMode::Mip ? "mip" : "reuse";
}

std::string_view hitRadianceName(HitRadiance radiance) {
    return radiance == HitRadiance::Current ? "current" : "reprojected";
}

void SsrOutput::ensureSize(int width, int height, int scratchRows, bool reuse) {
    for (PlaneF& p : color) p.ensureSize(width, height);
    opacity.ensureSize(width, height);
    for (PlaneF& p : hitRadiance) p.ensureSize(width, scratchRows);
    hitFade.ensureSize(width, scratchRows);
    if (reuse)
        for (PlaneF& p : hitTarget) p.ensureSize(width, scratchRows);
}

namespace {

constexpr std::string_view kResolvePass = "resolveSsr";

// The view of one of the output's planes, by its table's name.
OutF outputIn(SsrOutput& out, PlaneF& p) {
    std::string_view name;
    out.forEachPlane([&](std::string_view n, const PlaneF& q) {
        if (&q == &p) name = n;
    });
    return outputOf(p, name);
}

}  // namespace

SsrResolver::SsrResolver(Isa isa, const SsrResolveSettings& settings, const SsrResolveArgs& in,
                         SsrOutput& out, int sample, int sampleCount, RayBatch& frameRays,
                         MarchResult& frameMarch, int scratchRows)
    : args_(in),
      grid_(in.camera.width, in.camera.height),
      frameRays_(&frameRays),
      frameMarch_(&frameMarch) {
    const int w = in.camera.width, h = in.camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("resolveSsr: empty camera");
    if (sampleCount < 1 || sample < 0 || sample >= sampleCount)
        throw std::invalid_argument("resolveSsr: sample must be in [0, sampleCount)");
    if (scratchRows != 0 && (scratchRows < 0 || scratchRows % kTileSize != 0))
        throw std::invalid_argument("resolveSsr: scratch rows must be whole tile rows");
    // (A ring at least the frame's height is the frame's.)
    const int rows = scratchRows == 0 ? h : std::min(scratchRows, h);
    const bool reuse = settings.mode == SsrResolveMode::Reuse;
    out.ensureSize(w, h, rows, reuse);
    SsrResolveArgs& a = args_;
    a.scratchRows = scratchRows == 0 || scratchRows >= h ? h : scratchRows;
    a.width = w;
    a.height = h;
    a.tilesX = grid_.tilesX;
    a.tanHalfX = in.camera.tanHalfX;
    a.tanHalfY = in.camera.tanHalfY;
    std::copy_n(in.camera.viewToWorld, 9, a.viewToWorld);
    a.reuse = reuse;
    a.mip = settings.mode == SsrResolveMode::Mip;
    a.reproject = settings.radiance == HitRadiance::Reprojected;
    requireGBuffer(kResolvePass, a.g,
                   kGViewZ | kGRoughness | (a.reuse ? kGNormal : 0) | (a.reproject ? kGMotion : 0),
                   w, h);
    a.bilinear = settings.bilinear;
    if (a.mip) {
        const ColorPyramid* pyr = in.pyramid;
        if (!pyr || pyr->levelCount() < 1 || pyr->levelCount() > SsrResolveArgs::kMaxLevels)
            throw std::invalid_argument("resolveSsr: Mip mode needs a colour pyramid");
        a.levelCount = pyr->levelCount();
        for (int l = 0; l < a.levelCount; ++l) {
            const auto& lv = pyr->levels[std::size_t(l)];
            for (int c = 0; c < 3; ++c) {
                if (lv[c].empty() || lv[c].width() != lv[0].width() ||
                    lv[c].height() != lv[0].height())
                    throw std::invalid_argument("resolveSsr: malformed colour pyramid");
                a.level[l][c] = lv[c].row(0);
            }
            a.levelStride[l] = lv[0].stride();
            a.levelWidth[l] = lv[0].width();
            a.levelHeight[l] = lv[0].height();
        }
        if (a.levelWidth[0] != w || a.levelHeight[0] != h)
            throw std::invalid_argument("resolveSsr: colour pyramid not of the frame's size");
    } else {
        const ViewF* src = a.reproject ? a.prevColor : a.color;
        requireViews(kResolvePass, w, h, {src[0], src[1], src[2]});
        for (int c = 0; c < 3; ++c) a.source[c] = src[c].data;
    }
    a.edgeFadeScale = settings.edgeFadeLength > 0.0f ? 1.0f / settings.edgeFadeLength : 0.0f;
    a.roughnessFadeEnd = settings.roughnessFadeEnd;
    const float span = settings.roughnessFadeEnd - settings.roughnessFadeStart;
    a.roughnessFadeScale = span > 0.0f ? 1.0f / span : 1.0e30f;
    // The outputs, and what pass 2 reads around each pixel (the hits only for the reuse).
    frameRays.corner = {};
    frameRays.pdf.ensureSize(w, h);
    const OutF color[3] = {outputIn(out, out.color[0]), outputIn(out, out.color[1]),
                           outputIn(out, out.color[2])};
    const OutF opacity = outputIn(out, out.opacity), pdf = outputOf(frameRays.pdf, "ray.pdf");
    // (The scratch planes have the frame's width, so its stride.)
    a.stride = requireViews(kResolvePass, w, h, {color[0], color[1], color[2], opacity, pdf});
    const OutF radiance[3] = {outputIn(out, out.hitRadiance[0]), outputIn(out, out.hitRadiance[1]),
                              outputIn(out, out.hitRadiance[2])};
    const OutF fade = outputIn(out, out.hitFade);
    requireViews(kResolvePass, w, rows, {radiance[0], radiance[1], radiance[2], fade});
    for (int c = 0; c < 3; ++c) {
        a.hitRadiance[c] = radiance[c].data;
        a.outColor[c] = color[c].data;
    }
    a.hitFade = fade.data;
    a.outOpacity = opacity.data;
    a.framePdf = pdfTarget_ = pdf.data;
    if (a.reuse) {
        frameMarch.corner = {};
        frameMarch.hit.ensureSize(w, rows);
        const OutF target[3] = {outputIn(out, out.hitTarget[0]), outputIn(out, out.hitTarget[1]),
                                outputIn(out, out.hitTarget[2])};
        const OutF hit = outputOf(frameMarch.hit, "march.hit");
        requireViews(kResolvePass, w, rows, {target[0], target[1], target[2], hit});
        for (int c = 0; c < 3; ++c) a.hitTarget[c] = target[c].data;
        a.frameHit = hitTarget_ = hit.data;
    }
    a.sample = sample;
    a.sampleCount = sampleCount;
    hitKernel_ = SSRT_DISPATCH(isa, ssrHitTile);
    resolveKernel_ = SSRT_DISPATCH(isa, ssrResolveTile);
}

void SsrResolver::hitTile(int tile, const RayBatch& rays, const MarchResult& march) const {
    const TileRect r = grid_.rect(tile);
    const BatchCorner c = rays.corner;
    if (!sameCornerHolds(rays, march, r))
        throw std::invalid_argument("resolveSsr: the batches do not hold the tile");
    SsrResolveArgs a = args_;
    const ViewF dx = viewOf(rays.dx, "ray.dx"), dy = viewOf(rays.dy, "ray.dy"),
                dz = viewOf(rays.dz, "ray.dz"), pdf = viewOf(rays.pdf, "ray.pdf"),
                hit = viewOf(march.hit, "march.hit"), hitX = viewOf(march.hitX, "march.hitX"),
                hitY = viewOf(march.hitY, "march.hitY"), hitZ = viewOf(march.hitZ, "march.hitZ");
    a.rayStride = requireViews(kResolvePass, rays.pdf.width(), rays.pdf.height(),
                               {dx, dy, dz, pdf, hit, hitX, hitY, hitZ});
    a.rayDir[0] = dx.data, a.rayDir[1] = dy.data, a.rayDir[2] = dz.data;
    a.pdf = pdf.data;
    a.hit = hit.data;
    a.hitPos[0] = hitX.data, a.hitPos[1] = hitY.data, a.hitPos[2] = hitZ.data;
    a.rayX0 = c.x0;
    a.rayY0 = c.y0;
    // A tile's batch: its pdf and hits go to the frame's, for pass 2.
    if (&rays != frameRays_) a.copyPdf = pdfTarget_;
    if (&march != frameMarch_) a.copyHit = hitTarget_;
    hitKernel_(a, tile);
}

void SsrResolver::setHit(int x, int y, glm::vec3 radiance, float fade, glm::vec3 target) const {
    const std::size_t so = std::size_t(y % args_.scratchRows) * args_.stride + std::size_t(x);
    for (int c = 0; c < 3; ++c) args_.hitRadiance[c][so] = radiance[c];
    args_.hitFade[so] = fade;
    if (args_.reuse)
        for (int c = 0; c < 3; ++c) args_.hitTarget[c][so] = target[c];
}

void SsrResolver::resolveTile(int tile) const { resolveKernel_(args_, tile); }

void SsrResolver::resolveFrame(int threads) const {
    if (args_.scratchRows != args_.height)
        throw std::logic_error("resolveSsr: a ring's scratch is resolved tile row by tile row");
    parallelForTiles(grid_.count(), threads, [&](int t) { resolveKernel_(args_, t); });
}

void resolveSsr(Isa isa, const SsrResolveSettings& settings, const SsrResolveArgs& in,
                const RayBatch& rays, const MarchResult& march, SsrOutput& out, int sample,
                int sampleCount, int threads) {
    // The frame's batches, of the frame's size: only read (pass 1 copies nothing into its own
    // input, and the resolver's sizing of the two planes pass 2 reads keeps them).
    requireViews(kResolvePass, in.camera.width, in.camera.height,
                 {viewOf(rays.pdf, "ray.pdf"), viewOf(march.hit, "march.hit")});
    RayBatch& frameRays = const_cast<RayBatch&>(rays);
    MarchResult& frameMarch = const_cast<MarchResult&>(march);
    const SsrResolver resolver(isa, settings, in, out, sample, sampleCount, frameRays, frameMarch);
    // Pass 1 (own hits) over every tile before pass 2 reads the neighbours'.
    parallelForTiles(resolver.grid().count(), threads,
                     [&](int t) { resolver.hitTile(t, rays, march); });
    resolver.resolveFrame(threads);
}

}  // namespace ssrt
