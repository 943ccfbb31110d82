#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_vec.h"
#include "core/screen_lanes.h"
#include "core/signal_lanes.h"
#include "core/tiles.h"
#include "shading/direct_lanes.h"
#include "trace/ssgi_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;
using ILane = ln::IntOf<Lane>;

namespace {

SSRT_INLINE V3 gather3(const float* const* planes, ILane i) {
    return {ln::gather(planes[0], i), ln::gather(planes[1], i), ln::gather(planes[2], i)};
}
SSRT_INLINE V3 gather3(const SignalIn* planes, ILane i) {
    const ln::Run run = ln::runOf(i);
    return {ln::gatherSignal<Lane>(planes[0], i, run), ln::gatherSignal<Lane>(planes[1], i, run),
            ln::gatherSignal<Lane>(planes[2], i, run)};
}

// The Lambert direct light leaving the pixels i (plus their emission) from the G-buffer.
// (The direct pass's hitLight planes hold the same light, f16 rounded: 3 gathers instead of 8
// to 11.)
SSRT_INLINE V3 gather3(const FloatView* planes, ILane i) {
    const SignalIn in[3] = {planes[0].in(), planes[1].in(), planes[2].in()};
    return gather3(in, i);
}

SSRT_INLINE V3 lambertAt(const SsgiArgs& a, ILane i) {
    const V3 lit =
        shade::lambertSunLight(a.light, gather3(a.g.normal, i), gather3(a.g.albedo, i),
                               ln::gather(a.g.metallic, i), ln::gather(a.shadow.data, i));
    return a.emission[0] ? lit + gather3(a.emission, i) : lit;
}

// The chunk's world hits no pixel shows (SsgiArgs::lit, from `next` on): their own light.
SSRT_INLINE V3 withWorldLit(const SsgiArgs& a, int x, int y, V3 radiance, int& next) {
    if (next >= a.litCount || a.lit[next].y != y || a.lit[next].x >= x + kW) return radiance;
    alignas(64) float c[3][kW];
    ln::store(c[0], radiance.x), ln::store(c[1], radiance.y), ln::store(c[2], radiance.z);
    for (; next < a.litCount && a.lit[next].y == y && a.lit[next].x < x + kW; ++next) {
        const WorldLit& l = a.lit[next];
        if (l.x < x) break;  // (out of order: the resolver counts what was not taken)
        for (int ch = 0; ch < 3; ++ch) c[ch][l.x - x] = l.radiance[ch];
    }
    return {ln::load<Lane>(c[0]), ln::load<Lane>(c[1]), ln::load<Lane>(c[2])};
}

void ssgiChunk(const SsgiArgs& a, int x, int y, int& next) {
    const std::size_t o = std::size_t(y) * a.stride + x;
    const std::size_t r = std::size_t(y - a.rayY0) * a.rayStride + std::size_t(x - a.rayX0);
    const Lane zero(0.0f);
    const Lane pdf = ln::load<Lane>(a.pdf + r);
    if (a.copyPdf) ln::store(a.copyPdf + o, pdf);
    const auto hasRay = pdf > zero;
    V3 radiance{zero, zero, zero};
    if (ln::any(hasRay)) {
        const auto hit = hasRay & (ln::load<Lane>(a.hit + r) > Lane(0.5f));
        // The hit pixel's G-buffer (nearest; clamped, so unused lanes read inside the frame).
        const ILane i = screen::nearestIndex(ln::load<Lane>(a.hitX + r), ln::load<Lane>(a.hitY + r),
                                             a.width, a.height, a.stride);
        const auto surface = hit & (ln::gather(a.g.viewZ, i) > zero);
        if (ln::any(surface))
            radiance = ln::select(surface, a.hitLight[0] ? gather3(a.hitLight, i) : lambertAt(a, i),
                                  radiance);
        // Misses: the sky along the ray, in world space.
        const auto miss = hasRay & !surface;
        if (ln::any(miss)) {
            const V3 d{ln::load<Lane>(a.rayDir[0] + r), ln::load<Lane>(a.rayDir[1] + r),
                       ln::load<Lane>(a.rayDir[2] + r)};
            const V3 dw = ln::normalize(screen::viewToWorld(a.light.viewToWorld, d));
            radiance = ln::select(miss, shade::skyRadiance(a.light, dw), radiance);
        }
        radiance = withWorldLit(a, x, y, radiance, next);
    }
    // Accumulate: the sum over samples, divided by the count after the last.
    V3 acc = radiance;
    if (a.sample > 0)
        acc = acc + V3{ln::load<Lane>(a.out[0] + o), ln::load<Lane>(a.out[1] + o),
                       ln::load<Lane>(a.out[2] + o)};
    if (a.sample == a.sampleCount - 1 && a.sampleCount > 1) {
        const Lane n(float(a.sampleCount));
        acc = {acc.x / n, acc.y / n, acc.z / n};
    }
    ln::store(a.out[0] + o, acc.x);
    ln::store(a.out[1] + o, acc.y);
    ln::store(a.out[2] + o, acc.z);
}

}  // namespace

int ssgiTile(const SsgiArgs& args, int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, args.tilesX, args.width, args.height);
    int next = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) ssgiChunk(args, x, y, next);
    return next;
}

}  // namespace ssrt::SSRT_ISA_NS
