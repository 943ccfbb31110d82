#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/lane_vec.h"
#include "core/tiles.h"
#include "shading/brdf.h"
#include "shading/direct_kernel.h"
#include "shading/direct_lanes.h"
#include "shading/irradiance_sh.h"
#include "shading/multiscatter.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;

namespace {

constexpr int kW = int(ln::kWidth<Lane>);

using shade::envRadiance;
using shade::skyRadiance;
SSRT_INLINE V3 splat3(const float* v) { return shade::splat3<Lane>(v); }
SSRT_INLINE V3 mix3(V3 a, V3 b, Lane t) { return shade::mix3(a, b, t); }

// The prefiltered sky LD(r, roughness): linear between the two levels around roughness *
// (levels - 1), bilinear in each. Lanes may need different levels, so each level that any
// lane needs is read for all lanes and weighted by zero where it is not needed (x + 0 * y is
// x for finite y: the same bits as reading only the two levels, as the scalar copy does).
SSRT_INLINE V3 envPrefiltered(const DirectArgs& a, V3 r, Lane roughness) {
    const int n = a.envLevelCount;
    const Lane f = ln::saturate(roughness) * Lane(float(n - 1));
    const Lane i0 = ln::min(ln::floor(f), Lane(float(n - 2)));
    const Lane t = f - i0;
    Lane u, v;
    env::directionToUv(r, u, v);
    V3 sum{Lane(0.0f), Lane(0.0f), Lane(0.0f)};
    for (int k = 0; k < n; ++k) {
        const Lane lk = Lane(float(k));
        const Lane w =
            ln::select(i0 == lk, Lane(1.0f) - t, ln::select(i0 + Lane(1.0f) == lk, t, Lane(0.0f)));
        if (!ln::any(w > Lane(0.0f))) continue;
        sum = sum + env::sampleBilinear(a.envLevel[k], u, v) * w;
    }
    return sum * Lane(a.envIntensity);
}

// Fraction of PCF taps that see the light. Taps are clamped to the map's edge; points
// outside the map are lit (nothing there casts a shadow).
SSRT_INLINE Lane shadowVisibility(const DirectArgs& a, V3 p, Lane bias) {
    using ILane = ln::IntOf<Lane>;
    const float* m = a.lightViewProj;
    const Lane cx = ((Lane(m[0]) * p.x + Lane(m[4]) * p.y) + Lane(m[8]) * p.z) + Lane(m[12]);
    const Lane cy = ((Lane(m[1]) * p.x + Lane(m[5]) * p.y) + Lane(m[9]) * p.z) + Lane(m[13]);
    const Lane cz = ((Lane(m[2]) * p.x + Lane(m[6]) * p.y) + Lane(m[10]) * p.z) + Lane(m[14]);
    const Lane s(float(a.shadowSize));
    const Lane u = ln::floor((cx * Lane(0.5f) + Lane(0.5f)) * s);
    const Lane v = ln::floor((Lane(0.5f) - cy * Lane(0.5f)) * s);
    const Lane key = (Lane(0.5f) - Lane(0.5f) * cz) + bias;
    const auto inMap = (u >= Lane(0.0f)) & (v >= Lane(0.0f)) & (u < s) & (v < s);
    if (!ln::any(inMap)) return Lane(1.0f);
    const Lane last(float(a.shadowSize - 1));
    const int r = a.pcfRadius;
    Lane lit(0.0f);
    for (int dy = -r; dy <= r; ++dy) {
        const ILane row = ln::toIntTrunc(ln::clamp(v + Lane(float(dy)), Lane(0.0f), last)) *
                          ILane(int32_t(a.shadowStride));
        for (int dx = -r; dx <= r; ++dx) {
            const ILane col = ln::toIntTrunc(ln::clamp(u + Lane(float(dx)), Lane(0.0f), last));
            const Lane depth = ln::gather(a.shadow, row + col);
            lit = lit + ln::select(key >= depth, Lane(1.0f), Lane(0.0f));
        }
    }
    const Lane taps(float((2 * r + 1) * (2 * r + 1)));
    return ln::select(inMap, lit / taps, Lane(1.0f));
}

// Karis 2014, "Physically Based Shading on Mobile": analytic fit of the split-sum
// environment BRDF, scale and bias on F0. (Stands in until the DFG table of shading/.)
SSRT_INLINE void envBrdfApprox(Lane NoV, Lane roughness, Lane& scale, Lane& bias) {
    const Lane rx = roughness * Lane(-1.0f) + Lane(1.0f);
    const Lane ry = roughness * Lane(-0.0275f) + Lane(0.0425f);
    const Lane rz = roughness * Lane(-0.572f) + Lane(1.04f);
    const Lane rw = roughness * Lane(0.022f) + Lane(-0.04f);
    const Lane a004 = ln::min(rx * rx, ln::exp2(Lane(-9.28f) * NoV)) * rx + ry;
    scale = a004 * Lane(-1.04f) + rz;
    bias = a004 * Lane(1.04f) + rw;
}

using shade::srgbEncode;
using shade::tonemapAces;

struct Surface {
    V3 p, n, albedo, view;  // view: unit, from the surface towards the camera
    Lane metallic, roughness;
};

// The parts of a surface's colour (DirectArgs::direct etc.), emission aside.
struct Parts {
    V3 sun, envDiffuse, specWeight, envSpecular;
    V3 compensation;  // Kulla-Conty factor of the specWeight part (1 without the tables)
};

SSRT_INLINE Parts shadeSurface(const DirectArgs& a, const Surface& s, Lane& visibility) {
    using namespace ssrt::brdf;
    const Lane zero(0.0f), one(1.0f);
    const V3 l = splat3(a.toLight);
    const Lane NoLraw = ln::dot(s.n, l);
    const Lane NoL = ln::saturate(NoLraw);
    const Lane NoV = ln::max(ln::dot(s.n, s.view), Lane(1e-4f));
    const V3 h = ln::normalize(s.view + l);
    const Lane NoH = ln::saturate(ln::dot(s.n, h));
    const Lane VoH = ln::saturate(ln::dot(s.view, h));
    const Lane alpha = roughnessToAlpha(s.roughness);
    // F0 = mix(0.04, baseColor, metallic)
    const V3 f0 = mix3(V3{Lane(0.04f), Lane(0.04f), Lane(0.04f)}, s.albedo, s.metallic);
    const Lane dv = D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha);
    const V3 spec{F_Schlick(VoH, f0.x, one) * dv, F_Schlick(VoH, f0.y, one) * dv,
                  F_Schlick(VoH, f0.z, one) * dv};
    const V3 diffuse = s.albedo * ((one - s.metallic) * Fd_Lambert<Lane>());
    // Slope-scaled bias: grows with tan(angle to the light), capped at grazing angles.
    const Lane cosL = ln::max(NoLraw, Lane(1e-3f));
    const Lane tanL = ln::min(ln::sqrt(ln::max(one - cosL * cosL, zero)) / cosL, Lane(10.0f));
    visibility = ln::select(NoLraw > zero,
                            shadowVisibility(a, s.p, Lane(a.biasConst) + Lane(a.biasSlope) * tanL),
                            zero);
    const V3 direct = (diffuse + spec) * splat3(a.lightRadiance) * (NoL * visibility);
    const V3 refl = s.n * (Lane(2.0f) * ln::dot(s.n, s.view)) - s.view;
    V3 irradiance, specSky;
    if (a.envLevelCount > 0) {
        // Equirect sky: irradiance / pi from the SH polynomial, the reflected sky from the
        // GGX-prefiltered levels (split sum, Karis 2013).
        irradiance = env::irradianceSh(a.envIrradiance, s.n) * Lane(a.envIntensity);
        specSky = envPrefiltered(a, refl, s.roughness);
    } else {
        // Analytic sky: irradiance blended by the normal's elevation, and the reflected sky
        // through the environment BRDF, blurred towards the sky's average as roughness grows.
        const V3 skyAvg =
            mix3(splat3(a.skyGround), mix3(splat3(a.skyHorizon), splat3(a.skyZenith), Lane(0.5f)),
                 Lane(0.5f));
        const V3 up = mix3(splat3(a.skyHorizon), splat3(a.skyZenith), Lane(0.5f));
        irradiance = mix3(splat3(a.skyGround), up, Lane(0.5f) + Lane(0.5f) * s.n.y);
        specSky = mix3(skyRadiance(a, refl), skyAvg, s.roughness);
    }
    Lane envScale, envBias;
    envBrdfApprox(NoV, s.roughness, envScale, envBias);
    // color = (sun + envDiffuse) + specWeight envSpecular, as shadeChunk sums it.
    V3 compensation{one, one, one};
    if (a.compensation) {
        // 1 + F0 (1 / E - 1), E the GGX directional albedo with F = 1 (see direct_kernel.h).
        const Lane e = ln::max(multiscatter::albedo(*a.compensation, NoV, s.roughness), Lane(1e-3f));
        const Lane lost = one / e - one;
        compensation = {one + f0.x * lost, one + f0.y * lost, one + f0.z * lost};
    }
    return {direct, irradiance * diffuse * Lane(ln::kPi), f0 * envScale + V3{envBias, envBias, envBias},
            specSky, compensation};
}

// Shades lane group x of row y into out[plane] + (x - x0): a row buffer of the tile.
void shadeChunk(const DirectArgs& a, int x, int y, float* const* out, int x0) {
    const std::size_t go = std::size_t(y) * a.gStride + x;
    const Lane viewZ = ln::load<Lane>(a.g[0] + go);
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
       envSpecular = emission;
    if (!ln::all(background)) {
        Surface s;
        s.p = splat3(a.camPos) + dirWorld * viewZ;
        s.n = {ln::load<Lane>(a.g[1] + go), ln::load<Lane>(a.g[2] + go), ln::load<Lane>(a.g[3] + go)};
        s.albedo = {ln::load<Lane>(a.g[4] + go), ln::load<Lane>(a.g[5] + go),
                    ln::load<Lane>(a.g[6] + go)};
        s.metallic = ln::load<Lane>(a.g[7] + go);
        s.roughness = ln::load<Lane>(a.g[8] + go);
        const V3 toCam = ln::normalize(dirWorld);
        s.view = {Lane(0.0f) - toCam.x, Lane(0.0f) - toCam.y, Lane(0.0f) - toCam.z};
        Lane vis;
        const Parts parts = shadeSurface(a, s, vis);
        V3 lit = (parts.sun + parts.envDiffuse) + parts.specWeight * parts.envSpecular;
        // Emission by material id (a scalar gather), when any material emits.
        if (a.anyEmissive) {
            alignas(64) float mat[kW], em[3][kW];
            ln::store(mat, ln::load<Lane>(a.g[9] + go));
            for (int l = 0; l < kW; ++l)
                for (int c = 0; c < 3; ++c)
                    em[c][l] = mat[l] >= 0.0f ? a.emissive[3 * int(mat[l]) + c] : 0.0f;
            const V3 e{ln::load<Lane>(em[0]), ln::load<Lane>(em[1]), ln::load<Lane>(em[2])};
            lit = lit + e;
            emission = ln::select(background, emission, e);
        }
        color = ln::select(background, color, lit);
        visibility = ln::select(background, visibility, vis);
        sun = ln::select(background, sun, parts.sun);
        envDiffuse = ln::select(background, envDiffuse, parts.envDiffuse);
        specWeight = ln::select(background, specWeight, parts.specWeight * parts.compensation);
        envSpecular = ln::select(background, envSpecular, parts.envSpecular);
    }
    // The optional parts, straight into their planes (scene-linear, before the exposure).
    const std::size_t oo = std::size_t(y) * a.outStride + x;
    const auto put = [&](float* const* dst, const V3& v) {
        if (!dst[0]) return;
        ln::store(dst[0] + oo, v.x);
        ln::store(dst[1] + oo, v.y);
        ln::store(dst[2] + oo, v.z);
    };
    put(a.direct, sun);
    put(a.emission, emission);
    put(a.envDiffuse, envDiffuse);
    put(a.envSpecular, envSpecular);
    put(a.specWeight, specWeight);
    const int o = x - x0;
    const Lane rgb[3] = {color.x * Lane(a.exposure), color.y * Lane(a.exposure),
                         color.z * Lane(a.exposure)};
    for (int c = 0; c < 3; ++c) {
        ln::store(out[c] + o, rgb[c]);
        ln::store(out[3 + c] + o, srgbEncode(tonemapAces(rgb[c])));
    }
    ln::store(out[6] + o, visibility);
}

}  // namespace

void shadeTile(const DirectArgs& args, int tile) {
    const int tx = tile % args.tilesX, ty = tile / args.tilesX;
    const int x0 = tx * kTileSize, y0 = ty * kTileSize;
    const int x1 = std::min(args.width, x0 + kTileSize), y1 = std::min(args.height, y0 + kTileSize);
    // Row buffer, streamed out in whole cache lines (see raster/resolve_kernel.cpp); lane
    // groups past the right edge land in the rows' 64-byte padding.
    alignas(64) float rowBuf[7][kTileSize];
    float* bufPtr[7];
    for (int p = 0; p < 7; ++p) bufPtr[p] = rowBuf[p];
    const int span = (x1 - x0 + kW - 1) / kW * kW;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; x += kW) shadeChunk(args, x, y, bufPtr, x0);
        for (int p = 0; p < 7; ++p) {
            float* dst = args.out[p] + std::size_t(y) * args.outStride + x0;
            for (int i = 0; i < span; i += kW) ln::storeStream(dst + i, ln::load<Lane>(rowBuf[p] + i));
        }
    }
    ln::streamFence();
}

}  // namespace ssrt::SSRT_ISA_NS
