// The early-out of shade::shadowVisibility (shading/direct_lanes.h): where the shadow map's
// block bounds (shading/shadow_bounds.h) decide a pixel, its answer must be the taps' own, bit
// for bit. On synthetic maps (a tilted receiver's plane, raised and sunken boxes, noise, a
// NaN), for receivers on, over and under the map's surface, tolerances at the very edges of
// the taps' gaps and every PCF radius, the answer with the bounds is compared with the answer
// without them (every lane reads its taps), in scalar and vector lanes; and the bounds must
// decide many lanes both ways, so the comparison is not vacuous; every ISA makes the same bounds.
#include "shading/shadow_bounds.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "core/isa.h"
#include "core/rng.h"
#include "shading/direct_lanes.h"

using namespace ssrt;
namespace ln = ssrt::lanes;

namespace {

constexpr int kSize = 70;  // texels per side: 9 blocks, the last one cut by the map's edge

struct Rng {
    uint32_t n = 0, salt;
    explicit Rng(uint32_t s) : salt(s) {}
    float operator()(float lo, float hi) { return lo + (hi - lo) * randomFloat(n++, salt, 0, 0); }
};

// The map: a tilted plane (depth key alpha per texel in u, beta in v), with boxes raised
// towards the light (occluders) and sunk away from it (absent taps), noise on a few texels
// and, in some maps, a NaN.
struct Map {
    float alpha, beta, base;
    std::vector<float> depth;

    float plane(float fu, float fv) const { return base + alpha * fu + beta * fv; }
};

Map makeMap(Rng& rng, bool withNaN) {
    Map m;
    m.alpha = rng(-2e-3f, 2e-3f);
    m.beta = rng(-2e-3f, 2e-3f);
    m.base = 0.5f;
    m.depth.resize(kSize * kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) m.depth[y * kSize + x] = m.plane(x + 0.5f, y + 0.5f);
    for (int box = 0; box < 6; ++box) {
        const int x0 = int(rng(0, kSize)), y0 = int(rng(0, kSize));
        const int w = 1 + int(rng(0, 20)), h = 1 + int(rng(0, 20));
        const float lift = box % 2 ? rng(1e-3f, 0.2f) : -rng(1e-3f, 0.2f);
        for (int y = y0; y < std::min(y0 + h, kSize); ++y)
            for (int x = x0; x < std::min(x0 + w, kSize); ++x) m.depth[y * kSize + x] += lift;
    }
    for (int i = 0; i < 20; ++i) m.depth[int(rng(0, kSize * kSize))] += rng(-3e-3f, 3e-3f);
    if (withNaN) m.depth[int(rng(0, kSize * kSize))] = std::numeric_limits<float>::quiet_NaN();
    return m;
}

// The light: clip = (x, y, -z), towards the light +z, so key = 1/2 + z/2 and the plane of a
// unit normal n has gu = -n.x / (size n.z), gv = n.y / (size n.z).
DirectArgs lightArgs(const Map& m, int radius) {
    DirectArgs a{};
    const float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1};
    std::copy_n(proj, 16, a.lightViewProj);
    a.toLight[2] = 1.0f;
    a.shadowMap = m.depth.data();
    a.shadowStride = kSize;
    a.shadowSize = kSize;
    a.pcfRadius = radius;
    return a;
}

// One lane's inputs to shadowVisibility, as shadowMapVisibility makes them.
struct Query {
    float p[3], n[3], cosL, tol, exactTol, tanL;
};

// A receiver: on the map's plane with its normal (gaps of rounding), or off it, or tilted, or
// anywhere; sometimes outside the map.
Query makeQuery(Rng& rng, const Map& m) {
    Query q;
    const float fu = rng(-3.0f, kSize + 3.0f), fv = rng(-3.0f, kSize + 3.0f);
    q.p[0] = fu * (2.0f / kSize) - 1.0f;
    q.p[1] = 1.0f - fv * (2.0f / kSize);
    const int kind = int(rng(0, 4));
    const float offset = kind == 0 ? 0.0f : kind == 1 ? rng(-2e-3f, 2e-3f) : rng(-0.3f, 0.3f);
    q.p[2] = 2.0f * (m.plane(fu, fv) + offset) - 1.0f;
    float n[3] = {-m.alpha * kSize, m.beta * kSize, 1.0f};
    if (kind >= 2) {
        const float tilt = kind == 2 ? 0.05f : 2.0f;
        n[0] += rng(-tilt, tilt), n[1] += rng(-tilt, tilt);
    }
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; ++i) q.n[i] = n[i] / len;
    q.cosL = std::max(q.n[2], shade::kShadowMinCos);
    q.tanL = std::sqrt(std::max(1.0f - q.cosL * q.cosL, 0.0f)) / q.cosL;
    q.exactTol = rng(0.0f, 1e-4f);
    q.tol = q.exactTol + rng(0.0f, 2e-3f) * q.tanL;
    return q;
}

// The extreme gaps of q's taps, as the taps compute them (shade::shadowTaps), NaN aside.
struct Gaps {
    float lo = INFINITY, hi = -INFINITY;
};
Gaps tapGaps(const DirectArgs& a, const Query& in) {
    const shade::ShadowPlane<float> q =
        shade::shadowPlane(a, ln::V3<float>{in.p[0], in.p[1], in.p[2]},
                           ln::V3<float>{in.n[0], in.n[1], in.n[2]}, in.cosL);
    Gaps g;
    const int r = a.pcfRadius, last = a.shadowSize - 1;
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const int x = std::clamp(int(q.u) + dx, 0, last),
                      y = std::clamp(int(q.v) + dy, 0, last);
            const float planeRow = q.gv * (q.dv0 + float(dy));
            const float gap =
                a.shadowMap[y * kSize + x] - (q.key + (q.gu * (q.du0 + float(dx)) + planeRow));
            if (gap < g.lo) g.lo = gap;
            if (gap > g.hi) g.hi = gap;
        }
    return g;
}

// The queries' answers on lane type L, kWidth<L> at a time (the last group padded).
template <class L>
std::vector<float> answers(const DirectArgs& a, const std::vector<Query>& qs) {
    constexpr std::size_t w = ln::kWidth<L>;
    std::vector<float> out(qs.size());
    for (std::size_t i = 0; i < qs.size(); i += w) {
        alignas(64) float f[12][w];
        for (std::size_t l = 0; l < w; ++l) {
            const Query& q = qs[std::min(i + l, qs.size() - 1)];
            const float v[12] = {q.p[0], q.p[1], q.p[2], q.n[0],     q.n[1], q.n[2],
                                 q.cosL, q.tol,  q.tanL, q.exactTol, 0.0f,   0.0f};
            for (int k = 0; k < 12; ++k) f[k][l] = v[k];
        }
        const auto ld = [&](int k) { return ln::load<L>(f[k]); };
        alignas(64) float r[w];
        ln::store(
            r, shade::shadowVisibility(a, ln::V3<L>{ld(0), ld(1), ld(2)},
                                       ln::V3<L>{ld(3), ld(4), ld(5)}, ld(6), ld(7), ld(9), ld(8)));
        for (std::size_t l = 0; l < w && i + l < qs.size(); ++l) out[i + l] = r[l];
    }
    return out;
}

bool sameBits(float x, float y) { return std::memcmp(&x, &y, sizeof x) == 0; }

}  // namespace

TEST_CASE("shading: the shadow map's bounds decide only what the PCF taps would answer") {
    using Vec = xsimd::batch<float>;
    for (int radius = 0; radius <= 8; ++radius) {
        CAPTURE(radius);
        int lit = 0, dark = 0, queries = 0, mismatches = 0;
        for (uint32_t map = 0; map < 6; ++map) {
            Rng rng(1000 * radius + map);
            const Map m = makeMap(rng, map == 5);
            DirectArgs a = lightArgs(m, radius);
            // The queries, each also with its tolerance at the edges of its taps' gaps: where
            // the largest gap is just (not) an occluder, the smallest just (not) above both.
            std::vector<Query> qs;
            for (int i = 0; i < 1500; ++i) {
                const Query q = makeQuery(rng, m);
                qs.push_back(q);
                const Gaps g = tapGaps(a, q);
                for (float tol : {g.hi, std::nextafter(g.hi, -INFINITY), g.lo,
                                  std::nextafter(g.lo, -INFINITY)}) {
                    Query e = q;
                    e.tol = tol;
                    e.exactTol = std::min(tol, q.exactTol);
                    qs.push_back(e);
                    e.exactTol = tol;
                    qs.push_back(e);
                }
            }
            const std::vector<float> taps = answers<float>(a, qs);
            // Every ISA's kernel makes the same bounds, bit for bit.
            ShadowBounds bounds;
            buildShadowBounds(m.depth.data(), kSize, kSize, radius, Isa::Scalar, 1, bounds);
            for (Isa isa : kAllIsas) {
                if (!isaSupported(isa)) continue;
                ShadowBounds other;
                buildShadowBounds(m.depth.data(), kSize, kSize, radius, isa, 2, other);
                CAPTURE(isaName(isa));
                CHECK(std::memcmp(other.block.data(), bounds.block.data(),
                                  bounds.block.size() * sizeof(ShadowBlockBounds)) == 0);
            }
            a.shadowBounds = &bounds.block.data()->lo;
            a.shadowBlocks = bounds.blocks;
            const std::vector<float> scalar = answers<float>(a, qs), vec = answers<Vec>(a, qs);
            for (std::size_t i = 0; i < qs.size(); ++i) {
                const Query& in = qs[i];
                const shade::ShadowPlane<float> q =
                    shade::shadowPlane(a, ln::V3<float>{in.p[0], in.p[1], in.p[2]},
                                       ln::V3<float>{in.n[0], in.n[1], in.n[2]}, in.cosL);
                const shade::ShadowBound<float> b = shade::shadowBound(a, q, in.tol, in.exactTol);
                lit += q.inMap && b.lit;
                dark += q.inMap && b.dark;
                if (!sameBits(scalar[i], taps[i]) || !sameBits(vec[i], taps[i])) {
                    if (++mismatches <= 5)
                        std::printf(
                            "radius %d map %u query %zu: taps %a, bounds %a (vector %a), "
                            "lit %d dark %d\n",
                            radius, map, i, taps[i], scalar[i], vec[i], int(b.lit), int(b.dark));
                }
            }
            queries += int(qs.size());
        }
        CHECK(mismatches == 0);
        // Not vacuous: the bounds decide hundreds of lanes each way (the tolerances at the
        // edges of the taps' gaps are mostly beyond them).
        CHECK(lit > queries / 250);
        CHECK(dark > queries / 250);
        std::printf("shadow bounds, radius %d: %d queries, %d decided lit, %d dark\n", radius,
                    queries, lit, dark);
    }
}
