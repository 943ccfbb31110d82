#include "shading/prefiltered_env.h"

#include <algorithm>
#include <cassert>
#include <cstdint>

#include "core/tiles.h"
#include "shading/brdf.h"
#include "shading/energy_tables.h"
#include "shading/multiscatter.h"
#include "shading/sampling.h"

namespace ssrt {

namespace {

namespace ln = ssrt::lanes;
using V3f = ln::V3<float>;

// Van der Corput radical inverse in base 2: the second Hammersley coordinate.
float radicalInverse2(uint32_t k) {
    k = (k << 16) | (k >> 16);
    k = ((k & 0x55555555u) << 1) | ((k & 0xaaaaaaaau) >> 1);
    k = ((k & 0x33333333u) << 2) | ((k & 0xccccccccu) >> 2);
    k = ((k & 0x0f0f0f0fu) << 4) | ((k & 0xf0f0f0f0u) >> 4);
    k = ((k & 0x00ff00ffu) << 8) | ((k & 0xff00ff00u) >> 8);
    return float(k >> 8) * (1.0f / 16777216.0f);
}

// One GGX sample in the local frame of N = V = R (normal on +z): the reflected direction,
// its cosine N.l (the estimator's weight) and the source mip it reads.
struct LobeSample {
    V3f l;
    float weight;
    float lod;
};

// The sample set of one roughness level, the same for every texel (N = V = R makes the lobe
// a function of R alone, so only its orientation changes from texel to texel).
//
// Filtered importance sampling (Krivanek and Colbert 2008, "Real-time Shading with Filtered
// Importance Sampling", eq. 11-13): sample k stands for a solid angle
//   Omega_s = 1 / (N pdf(l_k)),
// and reads the mip whose texels cover about that much,
//   lod = 0.5 log2(Omega_s / Omega_p) + 1,   Omega_p = 4 pi / (w h),
// w h the size of the source's level 0 (its mean texel solid angle), + 1 their bias towards
// blur. With h drawn from D(h) (N.h) and l = reflect(V, h), pdf(l) = D(h) (N.h) / (4 V.h),
// which is D(h) / 4 when N = V.
std::vector<LobeSample> lobeSamples(float roughness, int count, int srcW, int srcH, bool filtered) {
    const float alpha = brdf::roughnessToAlpha(roughness);
    const float omegaP = 4.0f * ln::kPi / (float(srcW) * float(srcH));
    std::vector<LobeSample> out;
    out.reserve(count);
    for (int k = 0; k < count; ++k) {
        const float u1 = (float(k) + 0.5f) / float(count), u2 = radicalInverse2(uint32_t(k));
        const V3f h = sampling::sampleGgxNdf(alpha, alpha, u1, u2);
        const V3f l = sampling::reflect(V3f{0.0f, 0.0f, 1.0f}, h);
        if (!(l.z > 0.0f)) continue;
        const float pdf = brdf::D_GGX(h.z, alpha) * 0.25f;
        const float omegaS = 1.0f / (float(count) * pdf);
        const float lod = 0.5f * ln::log2(omegaS / omegaP) + 1.0f;
        out.push_back({l, l.z, filtered ? std::max(lod, 0.0f) : 0.0f});
    }
    return out;
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited": t, b with (t, b, n) right-handed.
void orthonormalBasis(V3f n, V3f& t, V3f& b) {
    const float s = n.z >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (s + n.z);
    const float c = n.x * n.y * a;
    t = {1.0f + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

// LD at direction r: the N.l-weighted mean of the environment over the rotated sample set.
Rgb prefilterTexel(const Environment& env, const std::vector<LobeSample>& lobe, V3f r) {
    V3f t, b;
    orthonormalBasis(r, t, b);
    double sum[3] = {0.0, 0.0, 0.0}, weight = 0.0;
    for (const LobeSample& s : lobe) {
        const V3f l = (t * s.l.x + b * s.l.y) + r * s.l.z;
        const Rgb c = env.radianceLod(l, s.lod);
        sum[0] += double(c.r) * s.weight;
        sum[1] += double(c.g) * s.weight;
        sum[2] += double(c.b) * s.weight;
        weight += s.weight;
    }
    if (!(weight > 0.0)) return env.radiance(r);
    return {float(sum[0] / weight), float(sum[1] / weight), float(sum[2] / weight)};
}

}  // namespace

EquirectImage prefilterLevel(const Environment& env, float roughness, int width, int height,
                             const PrefilterSettings& s) {
    assert(!env.isConstant() && width > 0 && height > 0 && s.samples > 0);
    const EquirectImage& src = env.mip(0);
    const std::vector<LobeSample> lobe =
        lobeSamples(roughness, s.samples, src.width, src.height, s.filtered);
    std::vector<float> rgb(std::size_t(3) * width * height);
    // One task per row; every texel depends only on its own direction, so the thread count
    // and the order of the rows cannot change a bit.
    parallelFor(height, s.threads, [&](int y) {
        const float v = (float(y) + 0.5f) / float(height);
        for (int x = 0; x < width; ++x) {
            const float u = (float(x) + 0.5f) / float(width);
            const Rgb c = prefilterTexel(env, lobe, env::uvToDirection(u, v));
            float* p = rgb.data() + (std::size_t(y) * width + x) * 3;
            p[0] = c.r, p[1] = c.g, p[2] = c.b;
        }
    });
    return EquirectImage(width, height, std::move(rgb));
}

// Level 0 (r = 0, a mirror: the lobe is a delta) is the source itself; level i > 0 is
// prefiltered at max(minWidth, min(source width, maxWidth) >> i) x half that.
PrefilteredEnvironment::PrefilteredEnvironment(const Environment& env, const PrefilterSettings& s) {
    color_ = env.constantColor();
    if (env.isConstant()) return;
    assert(s.levels >= 2);
    levels_.push_back(env.mip(0));
    const int base = std::min(env.mip(0).width, s.maxWidth);
    for (int i = 1; i < s.levels; ++i) {
        const int w = std::max(s.minWidth, base >> i), h = std::max(1, w / 2);
        const float r = float(i) / float(s.levels - 1);
        levels_.push_back(prefilterLevel(env, r, w, h, s));
    }
}

// Trilinear: bilinear in the two levels around roughness * (levels - 1), linear between.
Rgb PrefilteredEnvironment::lookup(lanes::V3<float> r, float roughness) const {
    if (isConstant()) return color_;
    const int n = levelCount();
    const float f = std::clamp(roughness, 0.0f, 1.0f) * float(n - 1);
    const int i0 = std::min(int(f), n - 2);
    const float t = f - float(i0);
    float u, v;
    env::directionToUv(r, u, v);
    const V3f a = env::sampleBilinear(levels_[i0].view(), u, v);
    const V3f b = env::sampleBilinear(levels_[i0 + 1].view(), u, v);
    return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t};
}

// The DFG table read through multiscatter's bilinear lookup (it indexes by sqrt(N.V)).
DfgTerms dfgTerms(float NoV, float roughness) {
    const EnergyTables& t = energyTables();
    return {multiscatter::lookup2d(t.dfgA.data(), NoV, roughness),
            multiscatter::lookup2d(t.dfgB.data(), NoV, roughness)};
}

Rgb splitSum(Rgb ld, Rgb f0, Rgb f90, DfgTerms dfg) {
    return {ld.r * (f0.r * dfg.a + f90.r * dfg.b), ld.g * (f0.g * dfg.a + f90.g * dfg.b),
            ld.b * (f0.b * dfg.a + f90.b * dfg.b)};
}

Rgb splitSumSpecular(const PrefilteredEnvironment& env, lanes::V3<float> r, float NoV,
                     float roughness, Rgb f0, Rgb f90) {
    return splitSum(env.lookup(r, roughness), f0, f90, dfgTerms(NoV, roughness));
}

}  // namespace ssrt
