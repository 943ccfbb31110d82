#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "core/signal_lanes.h"
#include "denoise/reblur_lanes.h"

// REBLUR's front end, one copy per ISA (denoise/reblur_lanes.h has what the passes share).

namespace ssrt::SSRT_ISA_NS {

namespace {

using namespace reblur_lanes;

// ---------------------------------------------------------------------------------------
// Front end (NRD's REBLUR_FrontEnd_PackRadianceAndNormHitDist with sanitize, and
// REBLUR_ClassifyTiles).

void frontEndChunk(const ReblurPassArgs& a, int x, int y, uint8_t& flags) {
    const ReblurFrame& v = a.frame;
    const std::size_t o = std::size_t(y) * v.stride + x;
    const Lane zero(0.0f), one(1.0f);
    const Lane z = loadAt(v.viewZ, o);
    const Mask surface = z > zero;
    // Lanes past the frame's right edge are not pixels.
    const Mask inFrame = (Lane(float(x)) + ln::laneIndex<Lane>()) < Lane(float(v.width));
    const DenoiseSignals& in = a.signals;
    if (in.hasDiffuse()) {
        const Lane colour =
            ln::max(ln::max(loadAt(a.frame.albedo[0], o), loadAt(a.frame.albedo[1], o)),
                    loadAt(a.frame.albedo[2], o)) *
            (one - loadAt(a.frame.metallic, o));
        const Mask has = surface & inFrame & (colour > zero);
        Lane noisy[4];
        for (int ch = 0; ch < 3; ++ch) noisy[ch] = sanitize(loadAt(in.diffuse[ch].data, o));
        noisy[3] = normalisedHit(v, loadAt(in.diffuseHitDistance.data, o), z, one);
        storeAt(a.noisyDiffuse, o, noisy);
        ln::store(a.signalZ[0] + o, ln::select(has, z, zero));
        if (ln::any(has)) flags |= kTileDiffuse;
    }
    if (in.hasSpecular()) {
        const Lane r = loadAt(v.roughness, o);
        const Mask has = surface & inFrame & (r < Lane(a.frame.specularMaxRoughness));
        const Lane opacity = ln::saturate(sanitize(loadAt(in.ssrOpacity.data, o)));
        Lane noisy[4];
        for (int ch = 0; ch < 3; ++ch) {
            const Lane ssr = sanitize(loadAt(in.ssr[ch].data, o));
            const Lane env = sanitize(loadAt(in.envSpecular[ch].in(), o));
            noisy[ch] = opacity * ssr + (one - opacity) * env;
        }
        noisy[3] = normalisedHit(v, loadAt(in.specularHitDistance.data, o), z, r);
        storeAt(a.noisySpecular, o, noisy);
        ln::store(a.signalZ[1] + o, ln::select(has, z, zero));
        if (ln::any(has)) flags |= kTileSpecular;
    }
}

}  // namespace

void reblurFrontEndTile(const ReblurPassArgs& a, int tile) {
    const ReblurFrame& v = a.frame;
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    uint8_t flags = 0;
    const DenoiseSignals& in = a.signals;
    const SignalIn env[3] = {in.envSpecular[0].in(), in.envSpecular[1].in(),
                             in.envSpecular[2].in()};
    for (int y = y0; y < y1; ++y) {
        // The direct pass's f16 envSpecular: the row two below fetched ahead (core/
        // signal_lanes.h, prefetchRowF16).
        if (in.hasSpecular() && y + 2 < y1)
            ln::prefetchRowF16(env, 3, std::size_t(y + 2) * v.stride, x0, x1);
        for (int x = x0; x < x1; x += kW) frontEndChunk(a, x, y, flags);
    }
    a.tiles[tile] = flags;
}

}  // namespace ssrt::SSRT_ISA_NS
