#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "shading/brdf.h"
#include "shading/sampling.h"
#include "shading/sampling_kernels.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
namespace sm = ssrt::sampling;
using V = ln::V3<Lane>;

namespace {

// Runs body(in[K], out[M]) over n elements, a lane group at a time. A null input reads its
// pad value, a null output is not stored; the tail is padded to a full group.
template <std::size_t K, std::size_t M, class F>
SSRT_INLINE void runLanes(const float* const (&in)[K], const float (&pad)[K],
                          float* const (&out)[M], std::size_t n, F body) {
    constexpr std::size_t w = ln::kWidth<Lane>;
    Lane x[K], y[M];
    std::size_t i = 0;
    for (; i + w <= n; i += w) {
        for (std::size_t k = 0; k < K; ++k) x[k] = in[k] ? ln::load<Lane>(in[k] + i) : Lane(pad[k]);
        body(x, y);
        for (std::size_t m = 0; m < M; ++m)
            if (out[m]) ln::store(out[m] + i, y[m]);
    }
    if (i == n) return;
    float tin[K][w], tout[M][w];
    for (std::size_t k = 0; k < K; ++k)
        for (std::size_t j = 0; j < w; ++j) tin[k][j] = in[k] && i + j < n ? in[k][i + j] : pad[k];
    for (std::size_t k = 0; k < K; ++k) x[k] = ln::load<Lane>(tin[k]);
    body(x, y);
    for (std::size_t m = 0; m < M; ++m) {
        ln::store(tout[m], y[m]);
        if (out[m])
            for (std::size_t j = 0; i + j < n; ++j) out[m][i + j] = tout[m][j];
    }
}

// The PDF of a sampler's own output direction d.
SSRT_INLINE Lane pdfOf(Sampler s, V wi, Lane ax, Lane ay, V d) {
    switch (s) {
        case Sampler::CosineHemisphere: return sm::cosineHemispherePdf(d);
        case Sampler::UniformHemisphere: return sm::uniformHemispherePdf(d);
        case Sampler::GgxNdf: return sm::ggxNdfPdf(d, ax, ay);
        case Sampler::GgxNdfReflection: return sm::ggxNdfReflectionPdf(wi, d, ax, ay);
        case Sampler::VndfEllipsoid:
        case Sampler::VndfSphericalCaps: return sm::vndfPdf(wi, d, ax, ay);
        case Sampler::VndfEllipsoidReflection:
        case Sampler::VndfSphericalCapsReflection: return sm::vndfReflectionPdf(wi, d, ax, ay);
        case Sampler::VndfBounded: return sm::vndfBoundedPdf(wi, d, ax, ay);
        case Sampler::VndfBoundedReflection: return sm::vndfBoundedReflectionPdf(wi, d, ax, ay);
    }
    return Lane(0.0f);
}

template <Sampler S>
SSRT_INLINE V draw(V wi, Lane ax, Lane ay, Lane u1, Lane u2) {
    if constexpr (S == Sampler::CosineHemisphere) return sm::sampleCosineHemisphere(u1, u2);
    else if constexpr (S == Sampler::UniformHemisphere) return sm::sampleUniformHemisphere(u1, u2);
    else if constexpr (S == Sampler::GgxNdf) return sm::sampleGgxNdf(ax, ay, u1, u2);
    else if constexpr (S == Sampler::GgxNdfReflection)
        return sm::sampleGgxNdfReflection(wi, ax, ay, u1, u2);
    else if constexpr (S == Sampler::VndfEllipsoid)
        return sm::sampleVndfEllipsoid(wi, ax, ay, u1, u2);
    else if constexpr (S == Sampler::VndfEllipsoidReflection)
        return sm::sampleVndfEllipsoidReflection(wi, ax, ay, u1, u2);
    else if constexpr (S == Sampler::VndfSphericalCaps)
        return sm::sampleVndfSphericalCaps(wi, ax, ay, u1, u2);
    else if constexpr (S == Sampler::VndfSphericalCapsReflection)
        return sm::sampleVndfSphericalCapsReflection(wi, ax, ay, u1, u2);
    else if constexpr (S == Sampler::VndfBounded) return sm::sampleVndfBounded(wi, ax, ay, u1, u2);
    else return sm::sampleVndfBoundedReflection(wi, ax, ay, u1, u2);
}

template <Sampler S>
void sampleWith(const SampleBatch& a, std::size_t n) {
    const float* const in[7] = {a.wiX, a.wiY, a.wiZ, a.alphaX, a.alphaY, a.u1, a.u2};
    constexpr float pad[7] = {0.0f, 0.0f, 1.0f, 0.5f, 0.5f, 0.5f, 0.5f};
    const bool withPdf = a.outPdf != nullptr;
    float* const out[4] = {a.outX, a.outY, a.outZ, a.outPdf};
    runLanes(in, pad, out, n, [withPdf](const Lane(&x)[7], Lane(&y)[4]) {
        const V wi{x[0], x[1], x[2]};
        const V d = draw<S>(wi, x[3], x[4], x[5], x[6]);
        y[0] = d.x;
        y[1] = d.y;
        y[2] = d.z;
        y[3] = withPdf ? pdfOf(S, wi, x[3], x[4], d) : Lane(0.0f);
    });
}

}  // namespace

void sampleDirections(Sampler s, const SampleBatch& a, std::size_t n) {
    switch (s) {
        case Sampler::CosineHemisphere: return sampleWith<Sampler::CosineHemisphere>(a, n);
        case Sampler::UniformHemisphere: return sampleWith<Sampler::UniformHemisphere>(a, n);
        case Sampler::GgxNdf: return sampleWith<Sampler::GgxNdf>(a, n);
        case Sampler::GgxNdfReflection: return sampleWith<Sampler::GgxNdfReflection>(a, n);
        case Sampler::VndfEllipsoid: return sampleWith<Sampler::VndfEllipsoid>(a, n);
        case Sampler::VndfEllipsoidReflection:
            return sampleWith<Sampler::VndfEllipsoidReflection>(a, n);
        case Sampler::VndfSphericalCaps: return sampleWith<Sampler::VndfSphericalCaps>(a, n);
        case Sampler::VndfSphericalCapsReflection:
            return sampleWith<Sampler::VndfSphericalCapsReflection>(a, n);
        case Sampler::VndfBounded: return sampleWith<Sampler::VndfBounded>(a, n);
        case Sampler::VndfBoundedReflection:
            return sampleWith<Sampler::VndfBoundedReflection>(a, n);
    }
}

void evalSamplerPdf(Sampler s, const SampleBatch& a, std::size_t n) {
    const float* const in[8] = {a.wiX, a.wiY, a.wiZ, a.alphaX, a.alphaY, a.woX, a.woY, a.woZ};
    constexpr float pad[8] = {0.0f, 0.0f, 1.0f, 0.5f, 0.5f, 0.0f, 0.0f, 1.0f};
    float* const out[1] = {a.outPdf};
    runLanes(in, pad, out, n, [s](const Lane(&x)[8], Lane(&y)[1]) {
        y[0] = pdfOf(s, V{x[0], x[1], x[2]}, x[3], x[4], V{x[5], x[6], x[7]});
    });
}

void evalBrdfTerm(BrdfTerm t, const SampleBatch& a, std::size_t n) {
    const float* const in[10] = {a.wiX, a.wiY,    a.wiZ,    a.woX, a.woY,
                                 a.woZ, a.alphaX, a.alphaY, a.f0,  a.f90};
    constexpr float pad[10] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 0.5f, 0.5f, 0.04f, 1.0f};
    float* const out[1] = {a.out};
    runLanes(in, pad, out, n, [t](const Lane(&x)[10], Lane(&y)[1]) {
        const V wi{x[0], x[1], x[2]}, wo{x[3], x[4], x[5]};
        const Lane ax = x[6], ay = x[7];
        const V h = ln::normalize(wi + wo);
        switch (t) {
            case BrdfTerm::D_GGX: y[0] = brdf::D_GGX(h.z, ax); break;
            case BrdfTerm::V_SmithGGXCorrelated:
                y[0] = brdf::V_SmithGGXCorrelated(wi.z, wo.z, ax);
                break;
            case BrdfTerm::F_Schlick: y[0] = brdf::F_Schlick(ln::dot(wi, h), x[8], x[9]); break;
            case BrdfTerm::D_GGXAniso: y[0] = brdf::D_GGXAniso(h.x, h.y, h.z, ax, ay); break;
            case BrdfTerm::Lambda: y[0] = brdf::Lambda_GGX(wi.x, wi.y, wi.z, ax, ay); break;
            case BrdfTerm::G1: y[0] = brdf::G1_GGX(wi.x, wi.y, wi.z, ax, ay); break;
            case BrdfTerm::G2: y[0] = brdf::G2_GGXCorrelated(wi, wo, ax, ay); break;
            case BrdfTerm::V_Aniso: y[0] = brdf::V_SmithGGXCorrelatedAniso(wi, wo, ax, ay); break;
            case BrdfTerm::SsrWeight: y[0] = brdf::ssrSampleWeight(wi, wo, ax, ay); break;
            case BrdfTerm::SpecularCos: y[0] = brdf::specularCos(wi, wo, ax, ay); break;
        }
    });
}

}  // namespace ssrt::SSRT_ISA_NS
