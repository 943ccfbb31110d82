// Samplers and BRDF terms beyond the chi-square: every ISA returns the scalar bits, the edge
// cases stay finite, the VNDF PDFs agree with D_V and with each other, the HDRP weight is
// f cos / pdf, and bounded VNDF sends fewer reflections below the horizon than the caps.
#include "shading/sampling.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/rng.h"
#include "shading/brdf.h"
#include "shading/sampling_kernels.h"

using namespace ssrt;
namespace sm = ssrt::sampling;
using V = lanes::V3<float>;

namespace {

struct Soa {
    std::vector<float> wx, wy, wz, ax, ay, u1, u2;
    std::size_t size() const { return wx.size(); }
    void push(V wi, float a, float b, float v1, float v2) {
        wx.push_back(wi.x), wy.push_back(wi.y), wz.push_back(wi.z);
        ax.push_back(a), ay.push_back(b), u1.push_back(v1), u2.push_back(v2);
    }
};

V randomDir(uint32_t i, uint32_t salt, bool upper) {
    const float z = upper ? randomFloat(i, salt, 0, 0) : 2.0f * randomFloat(i, salt, 0, 0) - 1.0f;
    const float phi = 6.2831853f * randomFloat(i, salt, 0, 1);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Random inputs plus the edges: alpha at its clamp and at 1, views along the normal, at and
// below the horizon, u at 0 and just under 1 (and 1 itself).
Soa edgeAndRandomInputs(std::size_t nRandom) {
    Soa s;
    for (uint32_t i = 0; i < nRandom; ++i) {
        const float r = randomFloat(i, 11, 0, 2);
        const float a = std::max(r * r, 1e-4f);
        const float b =
            randomFloat(i, 11, 0, 3) < 0.5f ? a : std::max(randomFloat(i, 11, 0, 4), 1e-4f);
        s.push(randomDir(i, 12, i % 4 != 0), a, b, randomFloat(i, 13, 0, 0),
               randomFloat(i, 13, 0, 1));
    }
    const float alphas[] = {0.0f, 1e-7f, 1e-4f, 1e-3f, 0.5f, 1.0f};
    const V views[] = {{0, 0, 1},          {1, 0, 0},
                       {0.6f, 0.8f, 0.0f}, {0.99985f, 0, 0.0174524f},
                       {0.6f, 0, -0.8f},   {0.0174524f, 0, -0.99985f},
                       {0, 0, -1}};
    const float us[] = {0.0f, 0.5f, 0.99999994f, 1.0f};
    for (float a : alphas)
        for (V v : views)
            for (float u1 : us)
                for (float u2 : us) s.push(v, a, a, u1, u2);
    return s;
}

bool isUpperSampler(Sampler s) {
    return s == Sampler::CosineHemisphere || s == Sampler::UniformHemisphere;
}

}  // namespace

TEST_CASE("shading: samplers, PDFs and BRDF terms return the scalar bits on every ISA") {
    const Soa in = edgeAndRandomInputs(4099);  // odd size: the tail path runs too
    const std::size_t n = in.size();
    std::vector<float> rx(n), ry(n), rz(n), rp(n), gx(n), gy(n), gz(n), gp(n);
    for (Sampler s : kAllSamplers) {
        const std::string name(samplerName(s));
        CAPTURE(name);
        const SampleBatch views{.wiX = in.wx.data(),
                                .wiY = in.wy.data(),
                                .wiZ = in.wz.data(),
                                .alphaX = in.ax.data(),
                                .alphaY = in.ay.data()};
        SampleBatch ref = views;
        ref.u1 = in.u1.data(), ref.u2 = in.u2.data();
        ref.outX = rx.data(), ref.outY = ry.data(), ref.outZ = rz.data(), ref.outPdf = rp.data();
        sampleDirections(Isa::Scalar, s, ref, n);
        // PDFs of other directions than the samples: the random view vectors reused.
        std::vector<float> pdfRef(n), pdfGot(n);
        SampleBatch pa = views;
        pa.woX = in.wy.data(), pa.woY = in.wz.data(), pa.woZ = in.wx.data();
        pa.outPdf = pdfRef.data();
        evalSamplerPdf(Isa::Scalar, s, pa, n);
        for (Isa isa : supportedIsas()) {
            const std::string isaStr(isaName(isa));
            CAPTURE(isaStr);
            SampleBatch got = ref;
            got.outX = gx.data(), got.outY = gy.data(), got.outZ = gz.data(),
            got.outPdf = gp.data();
            sampleDirections(isa, s, got, n);
            CHECK(std::memcmp(rx.data(), gx.data(), n * 4) == 0);
            CHECK(std::memcmp(ry.data(), gy.data(), n * 4) == 0);
            CHECK(std::memcmp(rz.data(), gz.data(), n * 4) == 0);
            CHECK(std::memcmp(rp.data(), gp.data(), n * 4) == 0);
            SampleBatch pg = pa;
            pg.outPdf = pdfGot.data();
            evalSamplerPdf(isa, s, pg, n);
            CHECK(std::memcmp(pdfRef.data(), pdfGot.data(), n * 4) == 0);
        }
    }
    const BrdfTerm terms[] = {BrdfTerm::D_GGX,     BrdfTerm::V_SmithGGXCorrelated,
                              BrdfTerm::F_Schlick, BrdfTerm::D_GGXAniso,
                              BrdfTerm::Lambda,    BrdfTerm::G1,
                              BrdfTerm::G2,        BrdfTerm::V_Aniso,
                              BrdfTerm::SsrWeight, BrdfTerm::SpecularCos};
    std::vector<float> ox(n), oy(n), oz(n), f0(n), f90(n), ref(n), got(n);
    for (std::size_t i = 0; i < n; ++i) {
        const V o = randomDir(uint32_t(i), 21, i % 3 != 0);
        ox[i] = o.x, oy[i] = o.y, oz[i] = o.z;
        f0[i] = randomFloat(uint32_t(i), 22, 0, 0), f90[i] = randomFloat(uint32_t(i), 22, 0, 1);
    }
    for (BrdfTerm t : terms) {
        CAPTURE(int(t));
        SampleBatch a{.wiX = in.wx.data(),
                      .wiY = in.wy.data(),
                      .wiZ = in.wz.data(),
                      .alphaX = in.ax.data(),
                      .alphaY = in.ay.data(),
                      .woX = ox.data(),
                      .woY = oy.data(),
                      .woZ = oz.data(),
                      .f0 = f0.data(),
                      .f90 = f90.data(),
                      .out = ref.data()};
        evalBrdfTerm(Isa::Scalar, t, a, n);
        for (Isa isa : supportedIsas()) {
            a.out = got.data();
            evalBrdfTerm(isa, t, a, n);
            CHECK(std::memcmp(ref.data(), got.data(), n * 4) == 0);
        }
    }
}

TEST_CASE("shading: samplers stay finite where methods fail") {
    const Soa in = edgeAndRandomInputs(2000);
    const std::size_t n = in.size();
    std::vector<float> x(n), y(n), z(n), p(n);
    for (Sampler s : kAllSamplers) {
        const std::string name(samplerName(s));
        CAPTURE(name);
        const SampleBatch a{.wiX = in.wx.data(),
                            .wiY = in.wy.data(),
                            .wiZ = in.wz.data(),
                            .alphaX = in.ax.data(),
                            .alphaY = in.ay.data(),
                            .u1 = in.u1.data(),
                            .u2 = in.u2.data(),
                            .outX = x.data(),
                            .outY = y.data(),
                            .outZ = z.data(),
                            .outPdf = p.data()};
        sampleDirections(Isa::Scalar, s, a, n);
        int positiveMisses = 0;
        for (std::size_t i = 0; i < n; ++i) {
            CAPTURE(i);
            const float wix = in.wx[i], wiz = in.wz[i], alpha = in.ax[i], u1 = in.u1[i],
                        u2 = in.u2[i];
            CAPTURE(wix);
            CAPTURE(wiz);
            CAPTURE(alpha);
            CAPTURE(u1);
            CAPTURE(u2);
            REQUIRE(std::isfinite(x[i]));
            REQUIRE(std::isfinite(y[i]));
            REQUIRE(std::isfinite(z[i]));
            REQUIRE(std::isfinite(p[i]));
            REQUIRE(p[i] >= 0.0f);
            const float len = std::sqrt(x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
            // A unit vector, or (a view from straight below: nothing visible) exactly zero.
            CHECK((std::fabs(len - 1.0f) < 1e-5f || len == 0.0f));
            // Valid samples have a positive PDF: u inside [0, 1), a view the method is
            // defined for (the ellipsoid method needs wi.z >= 0; every VNDF sees nothing
            // from straight below), a direction off the boundary where PDFs drop to 0.
            const bool viewOk = isUpperSampler(s) || in.wz[i] > -0.99f;
            const bool ellipsoidBelow =
                (s == Sampler::VndfEllipsoid || s == Sampler::VndfEllipsoidReflection) &&
                in.wz[i] < 0.0f;
            const bool interior = in.u1[i] < 1.0f && in.u2[i] < 1.0f;
            if (viewOk && !ellipsoidBelow && interior && len > 0.0f && !(p[i] > 0.0f)) {
                // Only samples on the edge of the support, where the PDF falls to 0, may
                // round to 0: a half vector on the horizon or normal to the view, a reflection
                // at -wi (or whose half vector lies on the horizon), a direction on the horizon.
                ++positiveMisses;
                const V wi{in.wx[i], in.wy[i], in.wz[i]}, d{x[i], y[i], z[i]};
                double edge;
                if (isUpperSampler(s)) {
                    edge = std::fabs(d.z);
                } else if (samplerDrawsHalfVector(s)) {
                    edge = std::min(std::fabs(d.z), std::fabs(lanes::dot(wi, d)));
                } else {
                    const V hv = wi + d;
                    const double len = std::sqrt(lanes::dot(hv, hv));
                    edge = std::min(0.5 * len, std::fabs(hv.z) /
                                                   std::max(len, 1e-30));  // |wi.h| = |wi + wo| / 2
                }
                CHECK(edge < 1e-2);
            }
        }
        MESSAGE(name << ": samples with PDF 0 on a valid input: " << positiveMisses);
    }
}

TEST_CASE("shading: the VNDF PDFs agree with D_V and with each other") {
    double worstDv = 0, worstBounded = 0, worstRefl = 0, worstSsr = 0;
    for (uint32_t i = 0; i < 20000; ++i) {
        const V wi = randomDir(i, 31, true);
        const float r = 0.05f + 0.95f * randomFloat(i, 32, 0, 0);
        const float ax = r * r, ay = i % 2 ? ax : std::max(0.02f, randomFloat(i, 32, 0, 1));
        const float u1 = randomFloat(i, 33, 0, 0), u2 = randomFloat(i, 33, 0, 1);
        const V m = sm::sampleVndfSphericalCaps(wi, ax, ay, u1, u2);
        const V o = sm::reflect(wi, m);
        // D_V = G1(wi) max(0, wi.m) D(m) / wi.z (Heitz 2014, eq. 16)
        const double dv = brdf::G1_GGX(wi.x, wi.y, wi.z, ax, ay) *
                          std::max(0.0f, lanes::dot(wi, m)) *
                          brdf::D_GGXAniso(m.x, m.y, m.z, ax, ay) / wi.z;
        const double pdf = sm::vndfPdf(wi, m, ax, ay);
        worstDv = std::max(worstDv, std::fabs(pdf - dv) / dv);
        // Reflection PDF = half-vector PDF / (4 wi.m)
        // (at the half vector of (wi, o) itself: recovering m from o costs digits near o = -wi)
        const double pr = sm::vndfReflectionPdf(wi, o, ax, ay);
        const V h = lanes::normalize(wi + o);
        worstRefl = std::max(
            worstRefl, std::fabs(pr - sm::vndfPdf(wi, h, ax, ay) / (4.0 * lanes::dot(wi, h))) / pr);
        // Bounded: above the horizon the same lobe renormalised by (t + wi.z) / (t + k wi.z)
        if (o.z > 0) {
            REQUIRE(sm::vndfBoundedInCap(wi, m, ax, ay));  // the cut-off part only holds o.z < 0
            const double t = brdf::smithT(wi.x, wi.y, wi.z, ax, ay);
            const double k = sm::vndfBoundedK(wi, ax, ay);
            const double pb = sm::vndfBoundedReflectionPdf(wi, o, ax, ay);
            worstBounded =
                std::max(worstBounded, std::fabs(pb - pr * (t + wi.z) / (t + k * wi.z)) / pb);
            // HDRP's weight is f cos / pdf for F = 1
            const double w = brdf::ssrSampleWeight(wi, o, ax, ay);
            const double ref = brdf::specularCos(wi, o, ax, ay) / pr;
            worstSsr = std::max(worstSsr, std::fabs(w - ref) / std::max(ref, 1e-3));
            CHECK(w <= 1.0f);
        }
    }
    MESSAGE("relative errors: vndf vs D_V " << worstDv << ", reflection " << worstRefl
                                            << ", bounded " << worstBounded << ", ssr weight "
                                            << worstSsr);
    CHECK(worstDv < 1e-4);
    CHECK(worstRefl < 1e-4);
    CHECK(worstBounded < 1e-4);
    CHECK(worstSsr < 1e-3);
    // Ellipsoid and caps draw the same distribution, and below the horizon the bounded sampler
    // is the caps sampler: same PDF function, and the same samples there.
    const V below{0.6f, 0.0f, -0.8f};
    for (uint32_t i = 0; i < 1000; ++i) {
        const float u1 = randomFloat(i, 34, 0, 0), u2 = randomFloat(i, 34, 0, 1);
        const V a = sm::sampleVndfSphericalCaps(below, 0.3f, 0.3f, u1, u2);
        const V b = sm::sampleVndfBounded(below, 0.3f, 0.3f, u1, u2);
        CHECK(std::memcmp(&a, &b, sizeof a) == 0);
        CHECK(sm::vndfPdf(below, a, 0.3f, 0.3f) ==
              doctest::Approx(sm::vndfBoundedPdf(below, a, 0.3f, 0.3f)).epsilon(1e-5));
    }
}

TEST_CASE("shading: BRDF terms match their isotropic forms and limits") {
    for (uint32_t i = 0; i < 5000; ++i) {
        const V wi = randomDir(i, 41, true), wo = randomDir(i, 42, true);
        const float r = 0.03f + 0.97f * randomFloat(i, 43, 0, 0), a = r * r;
        const V h = lanes::normalize(wi + wo);
        CHECK(brdf::D_GGXAniso(h.x, h.y, h.z, a, a) ==
              doctest::Approx(brdf::D_GGX(h.z, a)).epsilon(1e-4));
        CHECK(brdf::V_SmithGGXCorrelatedAniso(wi, wo, a, a) ==
              doctest::Approx(brdf::V_SmithGGXCorrelated(wi.z, wo.z, a)).epsilon(1e-5));
        CHECK(brdf::G2_GGXCorrelated(wi, wo, a, a) ==
              doctest::Approx(4.0f * wi.z * wo.z * brdf::V_SmithGGXCorrelatedAniso(wi, wo, a, a))
                  .epsilon(1e-5));
        // 1 / G2 = 1 + Lambda_i + Lambda_o, G1 = 1 / (1 + Lambda)
        const float li = brdf::Lambda_GGX(wi.x, wi.y, wi.z, a, a),
                    lo = brdf::Lambda_GGX(wo.x, wo.y, wo.z, a, a);
        CHECK(brdf::G2_GGXCorrelated(wi, wo, a, a) ==
              doctest::Approx(1.0f / (1.0f + li + lo)).epsilon(1e-4));
        CHECK(brdf::G1_GGX(wi.x, wi.y, wi.z, a, a) ==
              doctest::Approx(1.0f / (1.0f + li)).epsilon(1e-4));
    }
    CHECK(brdf::G1_GGX(0.0f, 0.0f, 1.0f, 0.5f, 0.5f) == 1.0f);
    CHECK(brdf::G1_GGX(1.0f, 0.0f, 0.0f, 0.5f, 0.5f) == 0.0f);
    CHECK(std::isfinite(brdf::Lambda_GGX(1.0f, 0.0f, 0.0f, 0.5f, 0.5f)));
    CHECK(brdf::F_Schlick(1.0f, 0.04f, 0.7f) == 0.04f);
    CHECK(brdf::F_Schlick(0.0f, 0.04f, 0.7f) == doctest::Approx(0.7f));
    CHECK(brdf::F_Schlick(0.0f, 0.04f) == doctest::Approx(1.0f));
}

TEST_CASE("shading: GgxDV has the bits of D_GGX x V_SmithGGXCorrelated") {
    // Grazing, head-on, the alpha clamp, NoL and NoH of 0 and 1, and random values.
    const float edges[] = {0.0f, 1e-4f, 1e-3f, 0.5f, 0.999f, 1.0f};
    for (uint32_t i = 0; i < 20000; ++i) {
        const auto pick = [&](uint32_t dim) {
            const float u = randomFloat(i, 44, 0, dim);
            return i < 2000 ? edges[int(u * 6.0f)] : u;
        };
        const float NoV = std::max(pick(0), 1e-4f), NoL = pick(1), NoH = pick(2);
        const float alpha = brdf::roughnessToAlpha(pick(3));
        const brdf::GgxDV<float> dv(NoV, alpha);
        const float ref = brdf::D_GGX(NoH, alpha) * brdf::V_SmithGGXCorrelated(NoV, NoL, alpha);
        const float got = dv(NoH, NoL);
        CHECK(std::memcmp(&ref, &got, sizeof ref) == 0);
    }
}

TEST_CASE("shading: bounded VNDF sends no more reflections below the horizon than spherical caps") {
    // Fraction of sampled reflections with wo.z < 0, 2^18 samples each, same u for both.
    // Prediction: above the horizon the bounded PDF is the caps PDF times (t + wi.z) / (t + k
    // wi.z), so f_bounded = 1 - (1 - f_caps) (t + wi.z) / (t + k wi.z).
    const float alphas[] = {0.01f, 0.1f, 0.3f, 0.5f, 0.75f, 1.0f};
    const double thetas[] = {0, 30, 60, 75, 85, 89};
    constexpr uint32_t kN = 1 << 18;
    std::vector<float> wx(kN), wy(kN), wz(kN), ax(kN), ay(kN), u1(kN), u2(kN), x(kN), y(kN), z(kN);
    for (uint32_t i = 0; i < kN; ++i)
        u1[i] = randomFloat(i, 51, 0, 0), u2[i] = randomFloat(i, 51, 0, 1);
    std::string table =
        "below-horizon fraction of reflections: caps / bounded (predicted)\n  alpha  ";
    for (double t : thetas) {
        char b[32];
        std::snprintf(b, sizeof b, "  theta=%-2g               ", t);
        table += b;
    }
    table += "\n";
    for (float a : alphas) {
        char b[64];
        std::snprintf(b, sizeof b, "  %-5g", a);
        table += b;
        for (double t : thetas) {
            const V wi{float(std::sin(t * M_PI / 180)), 0.0f, float(std::cos(t * M_PI / 180))};
            std::fill(wx.begin(), wx.end(), wi.x), std::fill(wy.begin(), wy.end(), wi.y),
                std::fill(wz.begin(), wz.end(), wi.z);
            std::fill(ax.begin(), ax.end(), a), std::fill(ay.begin(), ay.end(), a);
            double f[2];
            int k = 0;
            for (Sampler s :
                 {Sampler::VndfSphericalCapsReflection, Sampler::VndfBoundedReflection}) {
                const SampleBatch args{.wiX = wx.data(),
                                       .wiY = wy.data(),
                                       .wiZ = wz.data(),
                                       .alphaX = ax.data(),
                                       .alphaY = ay.data(),
                                       .u1 = u1.data(),
                                       .u2 = u2.data(),
                                       .outX = x.data(),
                                       .outY = y.data(),
                                       .outZ = z.data()};
                sampleDirections(defaultIsa(), s, args, kN);
                uint32_t below = 0;
                for (uint32_t i = 0; i < kN; ++i) below += z[i] < 0.0f;
                f[k++] = double(below) / kN;
            }
            const double tt = brdf::smithT(wi.x, wi.y, wi.z, a, a), kk = sm::vndfBoundedK(wi, a, a);
            const double predicted = 1.0 - (1.0 - f[0]) * (tt + wi.z) / (tt + kk * wi.z);
            const double sigma = std::sqrt(std::max(f[0] * (1 - f[0]), 1.0 / kN) / kN);
            const double caps = f[0], bounded = f[1];
            CAPTURE(a);
            CAPTURE(t);
            CAPTURE(caps);
            CAPTURE(bounded);
            CHECK(f[1] <= f[0] + 4.0 * sigma);
            CHECK(std::fabs(f[1] - predicted) <= 5.0 * sigma + 1e-6);
            std::snprintf(b, sizeof b, "  %.4f / %.4f (%.4f)", f[0], f[1],
                          std::max(predicted, 0.0));
            table += b;
        }
        table += "\n";
    }
    MESSAGE(table);
}
