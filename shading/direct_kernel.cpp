#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_vec.h"
#include "core/screen_lanes.h"
#include "core/signal_lanes.h"
#include "core/tiles.h"
#include "shading/direct_kernel.h"
#include "shading/direct_lanes.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;
using ILane = ln::IntOf<Lane>;

namespace {

// The planes a tile writes through its row buffers: colour RGB, display RGB, shadow.
constexpr int kDirectOutputs = 7;
enum Out { kColor = 0, kDisplay = 3, kShadow = 6 };

using shade::skyRadiance;
SSRT_INLINE V3 splat3(const float* v) { return shade::splat3<Lane>(v); }
using Surface = shade::Surface<Lane>;
using Parts = shade::Parts<Lane>;
using shade::srgbEncode;
using shade::tonemapAces;

// The chosen pixels' hit light of lane group x of row y into the half frame's planes: pixel
// (px, y) is half pixel (px / 2, y / 2)'s where halfSource says so (the frame's last column or
// row stands in for a block cut by an odd size).
void hitLightToHalf(const DirectArgs& a, int x, int y, const V3& light) {
    const auto chosen = [](int p, int offset, int size) {
        const int q = 2 * (p / 2) + offset;
        return (q < size ? q : size - 1) == p;
    };
    if (!chosen(y, a.halfOffsetY, a.height)) return;
    alignas(64) uint16_t v[3][kW];
    ln::storeF16(v[0], ln::clampedToF16(light.x));
    ln::storeF16(v[1], ln::clampedToF16(light.y));
    ln::storeF16(v[2], ln::clampedToF16(light.z));
    const std::size_t row = std::size_t(y / 2) * a.halfStride;
    for (int i = 0; i < kW && x + i < a.width; ++i) {
        const int px = x + i;
        if (!chosen(px, a.halfOffsetX, a.width)) continue;
        for (int c = 0; c < 3; ++c) a.hitLightHalf[c][row + std::size_t(px / 2)] = v[c][i];
    }
}

// The feedback (DirectArgs::prevDiffuse) for lane group x of row y, into the hit light just
// stored: hitLight += diffuse colour x occlusion x the previous frame's incoming diffuse light
// at the nearest pixel of the reprojected centre.
void addFeedback(const DirectArgs& a, int x, int y) {
    const std::size_t go = std::size_t(y) * a.g.stride + x;
    const std::size_t oo = std::size_t(y) * a.outStride + x;
    const Lane zero(0.0f);
    const auto surface = ln::load<Lane>(a.g.viewZ + go) > zero;
    if (!ln::any(surface)) return;
    const Lane cx = (Lane(float(x)) + ln::laneIndex<Lane>()) + Lane(0.5f);
    const Lane px = cx + ln::load<Lane>(a.g.motion[0] + go);
    const Lane py = Lane(float(y) + 0.5f) + ln::load<Lane>(a.g.motion[1] + go);
    const auto use = surface & (px >= zero) & (py >= zero) & (px < Lane(float(a.width))) &
                     (py < Lane(float(a.height)));
    const ILane j = screen::nearestIndex(px, py, a.width, a.height, a.outStride);
    Lane keep = Lane(1.0f) - ln::load<Lane>(a.g.metallic + go);
    if (a.occlusion) keep = keep * ln::load<Lane>(a.occlusion + go);
    const V3 albedo{ln::load<Lane>(a.g.albedo[0] + go), ln::load<Lane>(a.g.albedo[1] + go),
                    ln::load<Lane>(a.g.albedo[2] + go)};
    const V3 previous{ln::gather(a.prevDiffuse[0], j), ln::gather(a.prevDiffuse[1], j),
                      ln::gather(a.prevDiffuse[2], j)};
    const V3 reflected = albedo * keep * previous;
    const Lane add[3] = {reflected.x, reflected.y, reflected.z};
    for (int c = 0; c < 3; ++c) {
        const Lane lit = ln::loadSignal<Lane>(a.hitLight[c].in(), oo);
        ln::storeSignal(a.hitLight[c], oo, ln::select(use, lit + add[c], lit));
    }
}

// Shades lane group x of row y into out[plane] + (x - x0): a row buffer of the tile.
void shadeChunk(const DirectArgs& a, int x, int y, float* const* out, int x0) {
    const std::size_t go = std::size_t(y) * a.g.stride + x;
    const Lane viewZ = ln::load<Lane>(a.g.viewZ + go);
    const Lane px = Lane(float(x)) + ln::laneIndex<Lane>() + Lane(0.5f);
    const Lane ndcX = px * Lane(2.0f / float(a.width)) - Lane(1.0f);
    const Lane ndcY = Lane(1.0f) - Lane((float(y) + 0.5f) * (2.0f / float(a.height)));
    const V3 dirView{ndcX * Lane(a.tanHalfX), ndcY * Lane(a.tanHalfY), Lane(-1.0f)};
    const float* r = a.viewToWorld;
    const V3 dirWorld{(Lane(r[0]) * dirView.x + Lane(r[3]) * dirView.y) + Lane(r[6]) * dirView.z,
                      (Lane(r[1]) * dirView.x + Lane(r[4]) * dirView.y) + Lane(r[7]) * dirView.z,
                      (Lane(r[2]) * dirView.x + Lane(r[5]) * dirView.y) + Lane(r[8]) * dirView.z};
    const auto background = viewZ <= Lane(0.0f);
    V3 color{Lane(0.0f), Lane(0.0f), Lane(0.0f)};
    if (ln::any(background)) color = skyRadiance(a, ln::normalize(dirWorld));
    Lane visibility(1.0f);
    const Lane zero(0.0f);
    V3 sun = color, emission{zero, zero, zero}, envDiffuse = emission, specWeight = emission,
       envSpecular = emission, hitLight = emission;
    if (!ln::all(background)) {
        Surface s;
        s.p = splat3(a.camPos) + dirWorld * viewZ;
        s.n = {ln::load<Lane>(a.g.normal[0] + go), ln::load<Lane>(a.g.normal[1] + go),
               ln::load<Lane>(a.g.normal[2] + go)};
        s.albedo = {ln::load<Lane>(a.g.albedo[0] + go), ln::load<Lane>(a.g.albedo[1] + go),
                    ln::load<Lane>(a.g.albedo[2] + go)};
        s.metallic = ln::load<Lane>(a.g.metallic + go);
        s.roughness = ln::load<Lane>(a.g.roughness + go);
        const V3 toCam = ln::normalize(dirWorld);
        s.view = {Lane(0.0f) - toCam.x, Lane(0.0f) - toCam.y, Lane(0.0f) - toCam.z};
        const Lane vis = shade::shadowMapVisibility(a, s);
        Parts parts = shade::shadeSurface(a, s, vis);
        if (a.occlusion) shade::occludeIndirect(parts, ln::load<Lane>(a.occlusion + go));
        V3 lit = (parts.sun + parts.envDiffuse) + parts.specWeight * parts.envSpecular;
        // Emission when any material emits: the texture pass's per-pixel plane, or by material
        // id (a scalar gather).
        if (a.anyEmissive) {
            V3 e;
            if (a.emissivePlane[0]) {
                e = {ln::load<Lane>(a.emissivePlane[0] + go),
                     ln::load<Lane>(a.emissivePlane[1] + go),
                     ln::load<Lane>(a.emissivePlane[2] + go)};
            } else {
                alignas(64) float mat[kW], em[3][kW];
                ln::store(mat, ln::load<Lane>(a.g.materialId + go));
                for (int l = 0; l < kW; ++l)
                    for (int c = 0; c < 3; ++c)
                        em[c][l] = mat[l] >= 0.0f ? a.emissive[3 * int(mat[l]) + c] : 0.0f;
                e = {ln::load<Lane>(em[0]), ln::load<Lane>(em[1]), ln::load<Lane>(em[2])};
            }
            lit = lit + e;
            emission = ln::select(background, emission, e);
        }
        if (a.hitLight[0] || a.hitLightHalf[0]) {
            V3 light = shade::lambertSunLight(a, s.n, s.albedo, s.metallic, vis);
            if (a.anyEmissive) light = light + emission;
            hitLight = ln::select(background, hitLight, light);
        }
        color = ln::select(background, color, lit);
        visibility = ln::select(background, visibility, vis);
        sun = ln::select(background, sun, parts.sun);
        envDiffuse = ln::select(background, envDiffuse, parts.envDiffuse);
        specWeight = ln::select(background, specWeight, parts.specWeight);
        envSpecular = ln::select(background, envSpecular, parts.envSpecular);
    }
    // The optional parts, straight into their planes (scene-linear, before the exposure).
    const std::size_t oo = std::size_t(y) * a.outStride + x;
    const auto put = [&](const SignalOut* dst, const V3& v) {
        if (!dst[0]) return;
        ln::storeSignal(dst[0], oo, v.x);
        ln::storeSignal(dst[1], oo, v.y);
        ln::storeSignal(dst[2], oo, v.z);
    };
    put(a.direct, sun);
    put(a.emission, emission);
    put(a.envDiffuse, envDiffuse);
    put(a.envSpecular, envSpecular);
    put(a.specWeight, specWeight);
    put(a.hitLight, hitLight);
    if (a.prevDiffuse[0]) addFeedback(a, x, y);
    if (a.hitLightHalf[0]) hitLightToHalf(a, x, y, hitLight);
    const int o = x - x0;
    const Lane rgb[3] = {color.x * Lane(a.exposure), color.y * Lane(a.exposure),
                         color.z * Lane(a.exposure)};
    for (int c = 0; c < 3; ++c) ln::store(out[kColor + c] + o, rgb[c]);
    if (out[kDisplay])
        for (int c = 0; c < 3; ++c)
            ln::store(out[kDisplay + c] + o, srgbEncode(tonemapAces(rgb[c])));
    ln::store(out[kShadow] + o, visibility);
}

}  // namespace

void shadeTile(const DirectArgs& args, int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, args.tilesX, args.width, args.height);
    // Row buffer, streamed out in whole cache lines (see raster/resolve_kernel.cpp); lane
    // groups past the right edge land in the rows' 64-byte padding.
    float* const planes[kDirectOutputs] = {args.color[0],   args.color[1],   args.color[2],
                                           args.display[0], args.display[1], args.display[2],
                                           args.shadow};
    alignas(64) float rowBuf[kDirectOutputs][kTileSize];
    float* bufPtr[kDirectOutputs];
    for (int p = 0; p < kDirectOutputs; ++p) bufPtr[p] = planes[p] ? rowBuf[p] : nullptr;
    const int span = (x1 - x0 + kW - 1) / kW * kW;
    for (int y = y0; y < y1; ++y) {
        // The f16 parts: the row two below fetched ahead (core/signal_lanes.h).
        if (y + 2 < y1) {
            const std::size_t ahead = std::size_t(y + 2) * args.outStride;
            for (const SignalOut* part : {args.direct, args.emission, args.envDiffuse,
                                          args.envSpecular, args.specWeight, args.hitLight})
                ln::prefetchRowF16(part, 3, ahead, x0, x1);
        }
        for (int x = x0; x < x1; x += kW) shadeChunk(args, x, y, bufPtr, x0);
        for (int p = 0; p < kDirectOutputs; ++p) {
            if (!bufPtr[p]) continue;
            float* dst = planes[p] + std::size_t(y) * args.outStride + x0;
            for (int i = 0; i < span; i += kW)
                ln::storeStream(dst + i, ln::load<Lane>(rowBuf[p] + i));
        }
    }
    ln::streamFence();
}

}  // namespace ssrt::SSRT_ISA_NS
