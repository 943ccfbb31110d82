#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_vec.h"
#include "core/screen_lanes.h"
#include "core/tiles.h"
#include "shading/brdf.h"
#include "trace/ssr_resolve_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;
using ILane = ln::IntOf<Lane>;

namespace {

// Caps one neighbour's weight so that sums of weight x radiance stay finite whatever the pdf.
constexpr float kMaxWeight = 1.0e20f;

// Trilinear read of the pyramid at level-0 position (x, y) and mip level `mip`: bilinear in
// the two levels around it, linear between. Lanes may need different levels, so each level
// some lane needs is read for all and weighted by 0 where it is not needed (x + 0 y = x for
// finite y: the scalar copy's bits). Lanes not `used` (no hit) read nothing of their own.
SSRT_INLINE V3 pyramidSample(const SsrResolveArgs& a, Lane x, Lane y, Lane mip,
                             ln::MaskOf<Lane> used) {
    const int n = a.levelCount;
    const Lane zero(0.0f);
    if (n == 1) {
        const auto b =
            screen::bilinearAt(x, y, a.levelWidth[0], a.levelHeight[0], a.levelStride[0]);
        return {screen::sample(a.level[0][0], b), screen::sample(a.level[0][1], b),
                screen::sample(a.level[0][2], b)};
    }
    const Lane f = ln::clamp(mip, zero, Lane(float(n - 1)));
    const Lane i0 = ln::min(ln::floor(f), Lane(float(n - 2)));
    const Lane t = f - i0;
    V3 sum{zero, zero, zero};
    for (int k = 0; k < n; ++k) {
        const Lane lk = Lane(float(k));
        const Lane w = ln::select(
            used, ln::select(i0 == lk, Lane(1.0f) - t, ln::select(i0 + Lane(1.0f) == lk, t, zero)),
            zero);
        if (!ln::any(w > zero)) continue;
        const float sx = float(a.levelWidth[k]) / float(a.width);
        const float sy = float(a.levelHeight[k]) / float(a.height);
        const auto b = screen::bilinearAt(x * Lane(sx), y * Lane(sy), a.levelWidth[k],
                                          a.levelHeight[k], a.levelStride[k]);
        const V3 s{screen::sample(a.level[k][0], b), screen::sample(a.level[k][1], b),
                   screen::sample(a.level[k][2], b)};
        sum = sum + s * w;
    }
    return sum;
}

// Where frame row y's pixel x lies in the scratch planes (SsrResolveArgs::scratchRows).
SSRT_INLINE std::size_t scratchAt(const SsrResolveArgs& a, int x, int y) {
    return std::size_t(y % a.scratchRows) * a.stride + std::size_t(x);
}

// One lane group of pass 1: the pixel's own hit radiance and fade.
void hitChunk(const SsrResolveArgs& a, int x, int y) {
    const std::size_t o = std::size_t(y) * a.stride + x, so = scratchAt(a, x, y);
    const std::size_t r = std::size_t(y - a.rayY0) * a.rayStride + std::size_t(x - a.rayX0);
    const Lane zero(0.0f), one(1.0f);
    const Lane pdf = loadAt(a.pdf, r), hit = loadAt(a.hit, r);
    if (a.copyPdf) ln::store(a.copyPdf + o, pdf);
    if (a.copyHit) ln::store(a.copyHit + so, hit);
    const Lane hx = loadAt(a.hitPos[0], r), hy = loadAt(a.hitPos[1], r);
    auto valid = (pdf > zero) & (hit > Lane(0.5f));
    V3 radiance{zero, zero, zero};
    Lane fade = zero;
    if (ln::any(valid)) {
        // Edge-of-screen fade on the hit's position in the current frame.
        const Lane u = hx * Lane(1.0f / float(a.width)), v = hy * Lane(1.0f / float(a.height));
        const Lane edge = ln::min(ln::min(u, one - u), ln::min(v, one - v));
        fade = a.edgeFadeScale > 0.0f ? ln::saturate(edge * Lane(a.edgeFadeScale)) : one;
        // Where to read: the hit, or where it was a frame ago.
        Lane px = hx, py = hy;
        if (a.reproject) {
            const ILane i = screen::nearestIndex(hx, hy, a.width, a.height, a.stride);
            px = hx + ln::gather(a.g.motion[0], i);
            py = hy + ln::gather(a.g.motion[1], i);
            valid = valid & (px >= zero) & (py >= zero) & (px < Lane(float(a.width))) &
                    (py < Lane(float(a.height)));
        }
        if (a.mip) {
            const Lane rough = ln::saturate(loadAt(a.g.roughness, o));
            radiance = pyramidSample(a, px, py, rough * Lane(float(a.levelCount - 1)), valid);
        } else if (a.bilinear) {
            const auto b = screen::bilinearAt(px, py, a.width, a.height, a.stride);
            radiance = {screen::sample(a.source[0], b), screen::sample(a.source[1], b),
                        screen::sample(a.source[2], b)};
        } else {
            const ILane i = screen::nearestIndex(px, py, a.width, a.height, a.stride);
            radiance = {ln::gather(a.source[0], i), ln::gather(a.source[1], i),
                        ln::gather(a.source[2], i)};
        }
        radiance = radiance * Lane(a.radianceScale);
        radiance = ln::select(valid, radiance, V3{zero, zero, zero});
        fade = ln::select(valid, fade, zero);
    }
    ln::store(a.hitRadiance[0] + so, radiance.x);
    ln::store(a.hitRadiance[1] + so, radiance.y);
    ln::store(a.hitRadiance[2] + so, radiance.z);
    ln::store(a.hitFade + so, fade);
    if (a.reuse) {
        // What the 3x3 reuse aims at: the hit point in view space, or the ray's direction for
        // a miss (computed once here instead of once per neighbour there).
        const V3 hitP = screen::viewPoint(hx, hy, loadAt(a.hitPos[2], r), a.width, a.height,
                                          a.tanHalfX, a.tanHalfY);
        const V3 dir{loadAt(a.rayDir[0], r), loadAt(a.rayDir[1], r), loadAt(a.rayDir[2], r)};
        const V3 target = ln::select(hit > Lane(0.5f), hitP, dir);
        ln::store(a.hitTarget[0] + so, target.x);
        ln::store(a.hitTarget[1] + so, target.y);
        ln::store(a.hitTarget[2] + so, target.z);
    }
}

// This pixel's side of the reuse weights, the same for all 9 neighbours.
struct ReusePixel {
    V3 p, n, view;
    brdf::GgxDV<Lane> dv;
};

struct ReuseSums {
    Lane w, wf;
    V3 wfl;
};

// One neighbour's ray weighted for this pixel; `at(plane, scratch)` reads the neighbour's value
// of a frame plane (the pdf) or of a scratch plane for every lane (a load where the neighbours
// are contiguous, else a clamped gather).
template <class At>
SSRT_INLINE void reuseNeighbour(const SsrResolveArgs& a, const ReusePixel& s,
                                ln::MaskOf<Lane> inFrame, At&& at, ReuseSums& sum) {
    const Lane zero(0.0f), one(1.0f);
    const Lane pdf = at(a.framePdf, false);
    const auto hasRay = inFrame & (pdf > zero);
    if (!ln::any(hasRay)) return;
    // Direction from this pixel to the neighbour's hit, or the neighbour's own for a miss.
    const V3 target{at(a.hitTarget[0], true), at(a.hitTarget[1], true), at(a.hitTarget[2], true)};
    const V3 toHit = ln::normalize(target - s.p);
    const V3 l = ln::select(at(a.frameHit, true) > Lane(0.5f), toHit, target);
    // This pixel's lobe towards l.
    const Lane NoLraw = ln::dot(s.n, l);
    const Lane NoL = ln::saturate(NoLraw);
    const V3 h = ln::normalize(s.view + l);
    const Lane NoH = ln::saturate(ln::dot(s.n, h));
    const Lane brdfCos = s.dv(NoH, NoL) * NoL;
    const auto ok = hasRay & (NoLraw > zero);
    const Lane w =
        ln::select(ok, ln::min(brdfCos / ln::select(ok, pdf, one), Lane(kMaxWeight)), zero);
    const Lane wf = w * at(a.hitFade, true);
    const V3 L{at(a.hitRadiance[0], true), at(a.hitRadiance[1], true), at(a.hitRadiance[2], true)};
    sum.w = sum.w + w;
    sum.wf = sum.wf + wf;
    sum.wfl = sum.wfl + L * wf;
}

// Whether some lane's 3x3 neighbourhood holds a ray (pdf > 0). Without one the reuse sums
// stay 0 and return colour 0, opacity 0: most rough or checkerboard-cut pixels, whose set-up
// (view point, normal, the GGX lobe's terms) is then skipped. At the frame's left and right
// edges it answers yes (the reuse's clamped reads decide there).
SSRT_INLINE bool anyNeighbourRay(const SsrResolveArgs& a, int x, int y) {
    if (x < 1 || x + 1 + kW > a.width) return true;
    const Lane zero(0.0f);
    // The pixel's own row first: where rays are dense the answer comes after one row.
    for (const int yy : {y, y - 1, y + 1}) {
        if (yy < 0 || yy >= a.height) continue;
        const std::size_t o = std::size_t(yy) * a.stride + std::size_t(x);
        if (ln::any((loadAt(a.framePdf, o - 1) > zero) | (loadAt(a.framePdf, o) > zero) |
                    (loadAt(a.framePdf, o + 1) > zero)))
            return true;
    }
    return false;
}

// Stachowiak 2015, "Stochastic Screen-Space Reflections": the 3x3 neighbours' hits, each
// weighted by this pixel's GGX lobe (D V n.l) over the neighbour ray's pdf; ratio estimator.
SSRT_INLINE void reuse(const SsrResolveArgs& a, int x, int y, Lane viewZ, Lane rough, V3& color,
                       Lane& opacity) {
    using namespace ssrt::brdf;
    const Lane zero(0.0f), one(1.0f);
    const std::size_t o = std::size_t(y) * a.stride + x;
    const Lane px = Lane(float(x)) + ln::laneIndex<Lane>();
    // This pixel: point, normal and view direction in view space.
    const V3 p = screen::viewPoint(px + Lane(0.5f), Lane(float(y) + 0.5f), viewZ, a.width, a.height,
                                   a.tanHalfX, a.tanHalfY);
    const V3 nWorld{loadAt(a.g.normal[0], o), loadAt(a.g.normal[1], o), loadAt(a.g.normal[2], o)};
    const V3 n = ln::normalize(screen::worldToView(a.viewToWorld, nWorld));
    const V3 view = ln::normalize(V3{zero - p.x, zero - p.y, zero - p.z});
    const Lane NoV = ln::max(ln::dot(n, view), Lane(1e-4f));
    const ReusePixel s{p, n, view, GgxDV<Lane>(NoV, roughnessToAlpha(rough))};
    ReuseSums sum{zero, zero, V3{zero, zero, zero}};
    for (int dy = -1; dy <= 1; ++dy) {
        const int yy = y + dy;
        if (yy < 0 || yy >= a.height) continue;
        for (int dx = -1; dx <= 1; ++dx) {
            if (x + dx >= 0 && x + dx + kW <= a.width) {
                // Every lane's neighbour is in the frame: they sit side by side in memory.
                const std::size_t on = std::size_t(yy) * a.stride + std::size_t(x + dx);
                const std::size_t sn = scratchAt(a, x + dx, yy);
                reuseNeighbour(
                    a, s, zero == zero,
                    [&](const float* plane, bool scratch) {
                        return loadAt(plane, scratch ? sn : on);
                    },
                    sum);
            } else {
                const Lane nx = px + Lane(float(dx));
                const auto inFrame = (nx >= zero) & (nx < Lane(float(a.width)));
                const ILane i =
                    screen::pixelIndex(nx, Lane(float(yy)), a.width, a.height, a.stride);
                const ILane si = screen::pixelIndex(nx, Lane(float(yy % a.scratchRows)), a.width,
                                                    a.scratchRows, a.stride);
                reuseNeighbour(
                    a, s, inFrame,
                    [&](const float* plane, bool scratch) {
                        return ln::gather(plane, scratch ? si : i);
                    },
                    sum);
            }
        }
    }
    const auto any = sum.wf > zero;
    const Lane den = ln::select(any, sum.wf, one);
    color = ln::select(any, V3{sum.wfl.x / den, sum.wfl.y / den, sum.wfl.z / den},
                       V3{zero, zero, zero});
    opacity =
        ln::select(sum.w > zero, ln::min(sum.wf / ln::select(sum.w > zero, sum.w, one), one), zero);
}

// One lane group of pass 2: combine, fade by roughness, accumulate the sample.
void resolveChunk(const SsrResolveArgs& a, int x, int y) {
    const std::size_t o = std::size_t(y) * a.stride + x;
    const Lane zero(0.0f);
    const Lane viewZ = loadAt(a.g.viewZ, o);
    const auto background = viewZ <= zero;
    const Lane rough = loadAt(a.g.roughness, o);
    V3 color{zero, zero, zero};
    Lane opacity = zero;
    if (!ln::all(background)) {
        if (a.reuse) {
            if (anyNeighbourRay(a, x, y)) reuse(a, x, y, viewZ, rough, color, opacity);
        } else {
            const std::size_t so = scratchAt(a, x, y);
            color = {loadAt(a.hitRadiance[0], so), loadAt(a.hitRadiance[1], so),
                     loadAt(a.hitRadiance[2], so)};
            opacity = loadAt(a.hitFade, so);
        }
        // HDRP's roughness (smoothness) fade.
        const Lane fadeR =
            ln::saturate((Lane(a.roughnessFadeEnd) - rough) * Lane(a.roughnessFadeScale));
        opacity = ln::select(background, zero, opacity * fadeR);
        color = ln::select(background, V3{zero, zero, zero}, color);
    }
    // Accumulate: one sample is stored as is; several as sums of color x opacity and opacity,
    // turned into the averages after the last.
    float* const* oc = a.outColor;
    if (a.sampleCount == 1) {
        ln::store(oc[0] + o, color.x);
        ln::store(oc[1] + o, color.y);
        ln::store(oc[2] + o, color.z);
        ln::store(a.outOpacity + o, opacity);
        return;
    }
    V3 sumC = color * opacity;
    Lane sumO = opacity;
    if (a.sample > 0) {
        sumC = sumC + V3{loadAt(oc[0], o), loadAt(oc[1], o), loadAt(oc[2], o)};
        sumO = sumO + loadAt(a.outOpacity, o);
    }
    if (a.sample == a.sampleCount - 1) {
        const auto any = sumO > zero;
        const Lane den = ln::select(any, sumO, Lane(1.0f));
        sumC = ln::select(any, V3{sumC.x / den, sumC.y / den, sumC.z / den}, V3{zero, zero, zero});
        sumO = sumO / Lane(float(a.sampleCount));
    }
    ln::store(oc[0] + o, sumC.x);
    ln::store(oc[1] + o, sumC.y);
    ln::store(oc[2] + o, sumC.z);
    ln::store(a.outOpacity + o, sumO);
}

template <class F>
SSRT_INLINE void forTile(const SsrResolveArgs& a, int tile, F&& f) {
    const auto [x0, y0, x1, y1] = tileRect(tile, a.tilesX, a.width, a.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) f(x, y);
}

}  // namespace

void ssrHitTile(const SsrResolveArgs& args, int tile) {
    forTile(args, tile, [&](int x, int y) { hitChunk(args, x, y); });
}

void ssrResolveTile(const SsrResolveArgs& args, int tile) {
    forTile(args, tile, [&](int x, int y) { resolveChunk(args, x, y); });
}

}  // namespace ssrt::SSRT_ISA_NS
