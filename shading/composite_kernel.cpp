#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_vec.h"
#include "core/signal_lanes.h"
#include "core/tiles.h"
#include "shading/composite_kernel.h"
#include "shading/direct_lanes.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;

namespace {

SSRT_INLINE V3 load3(const float* const* p, std::size_t o) {
    return {ln::load<Lane>(p[0] + o), ln::load<Lane>(p[1] + o), ln::load<Lane>(p[2] + o)};
}
SSRT_INLINE V3 load3(const ViewF* p, std::size_t o) {
    return {ln::load<Lane>(p[0].data + o), ln::load<Lane>(p[1].data + o),
            ln::load<Lane>(p[2].data + o)};
}
SSRT_INLINE V3 load3(const FloatView* p, std::size_t o) {
    return {ln::loadSignal<Lane>(p[0].in(), o), ln::loadSignal<Lane>(p[1].in(), o),
            ln::loadSignal<Lane>(p[2].in(), o)};
}

void compositeChunk(const CompositeArgs& a, int x, int y) {
    const std::size_t o = std::size_t(y) * a.stride + x;
    const Lane zero(0.0f), one(1.0f);
    // Diffuse: SSGI times the diffuse colour, or the sky's irradiance term.
    V3 diffuse;
    if (a.ssgi[0].data) {
        const Lane metallic = ln::load<Lane>(a.g.metallic + o);
        const V3 colour = load3(a.g.albedo, o) * (one - metallic);
        const auto background = ln::load<Lane>(a.g.viewZ + o) <= zero;
        const std::size_t so =
            std::size_t(y - a.ssgiY0) * a.ssgi[0].stride + std::size_t(x - a.ssgiX0);
        V3 bounce = colour * load3(a.ssgi, so);
        if (a.occlusion.data) bounce = bounce * ln::load<Lane>(a.occlusion.data + o);
        diffuse = ln::select(background, V3{zero, zero, zero}, bounce);
    } else {
        diffuse = load3(a.envDiffuse, o);
    }
    // Specular: the split-sum factor times SSR blended over the prefiltered sky.
    V3 incoming = load3(a.envSpecular, o);
    if (a.specular[0].data) {
        incoming = load3(a.specular, o);  // the denoiser's (denoise/denoise.h)
    } else if (a.ssrColor[0].data) {
        const Lane opacity = ln::load<Lane>(a.ssrOpacity.data + o);
        incoming = load3(a.ssrColor, o) * opacity + incoming * (one - opacity);
    }
    // The direct pass's order: ((direct + diffuse) + specular) + emission.
    V3 sum = (load3(a.direct, o) + diffuse) + load3(a.specWeight, o) * incoming;
    if (a.emission[0].f32.data || a.emission[0].f16.data) sum = sum + load3(a.emission, o);
    const Lane e(a.exposure);
    const Lane rgb[3] = {sum.x * e, sum.y * e, sum.z * e};
    for (int c = 0; c < 3; ++c) {
        ln::store(a.color[c].data + o, rgb[c]);
        ln::store(a.display[c].data + o, shade::displayEncode(rgb[c]));
    }
}

}  // namespace

void compositeTile(const CompositeArgs& args, int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, args.tilesX, args.width, args.height);
    for (int y = y0; y < y1; ++y) {
        // The direct pass's f16 parts: the row two below fetched ahead (prefetchRowF16).
        if (y + 2 < y1) {
            const std::size_t ahead = std::size_t(y + 2) * args.stride;
            for (const FloatView* part :
                 {args.direct, args.emission, args.envDiffuse, args.envSpecular, args.specWeight}) {
                const SignalIn rows[3] = {part[0].in(), part[1].in(), part[2].in()};
                ln::prefetchRowF16(rows, 3, ahead, x0, x1);
            }
        }
        for (int x = x0; x < x1; x += kW) compositeChunk(args, x, y);
    }
}

}  // namespace ssrt::SSRT_ISA_NS
