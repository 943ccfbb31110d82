// Array entry points to the samplers, their PDFs and the BRDF terms, one copy per ISA: what
// the tests hold to the scalar copy bit for bit and run the chi-square tests through, and
// what perf/bench_sampling.cpp times. Arrays are structure-of-arrays, n floats each.
#pragma once

#include <cstddef>
#include <string_view>

#include "core/dispatch.h"

namespace ssrt {

// Each sampler draws either a half vector (PDF over wm) or a reflected direction (PDF over
// wo); see shading/sampling.h for the methods and their sources.
enum class Sampler {
    CosineHemisphere,
    UniformHemisphere,
    GgxNdf,
    GgxNdfReflection,
    VndfEllipsoid,
    VndfEllipsoidReflection,
    VndfSphericalCaps,
    VndfSphericalCapsReflection,
    VndfBounded,
    VndfBoundedReflection,
};

inline constexpr Sampler kAllSamplers[] = {
    Sampler::CosineHemisphere,
    Sampler::UniformHemisphere,
    Sampler::GgxNdf,
    Sampler::GgxNdfReflection,
    Sampler::VndfEllipsoid,
    Sampler::VndfEllipsoidReflection,
    Sampler::VndfSphericalCaps,
    Sampler::VndfSphericalCapsReflection,
    Sampler::VndfBounded,
    Sampler::VndfBoundedReflection,
};

inline std::string_view samplerName(Sampler s) {
    switch (s) {
        case Sampler::CosineHemisphere: return "cosine_hemisphere";
        case Sampler::UniformHemisphere: return "uniform_hemisphere";
        case Sampler::GgxNdf: return "ggx_ndf";
        case Sampler::GgxNdfReflection: return "ggx_ndf_reflection";
        case Sampler::VndfEllipsoid: return "vndf_ellipsoid";
        case Sampler::VndfEllipsoidReflection: return "vndf_ellipsoid_reflection";
        case Sampler::VndfSphericalCaps: return "vndf_spherical_caps";
        case Sampler::VndfSphericalCapsReflection: return "vndf_spherical_caps_reflection";
        case Sampler::VndfBounded: return "vndf_bounded";
        case Sampler::VndfBoundedReflection: return "vndf_bounded_reflection";
    }
    return "?";
}

// True for the samplers that return a half vector rather than a reflected direction.
inline bool samplerDrawsHalfVector(Sampler s) {
    return s == Sampler::GgxNdf || s == Sampler::VndfEllipsoid || s == Sampler::VndfSphericalCaps ||
           s == Sampler::VndfBounded;
}

// A batch of n configurations in the local frame (normal on +z), structure of arrays: what
// the three entry points below read and write, each its own fields (the others ignored). A
// null input reads a fixed default (shading/sampling_kernel.cpp); a null output is not written.
struct SampleBatch {
    // The view direction (unused by the hemisphere samplers) and the GGX alphas
    const float *wiX = nullptr, *wiY = nullptr, *wiZ = nullptr;
    const float *alphaX = nullptr, *alphaY = nullptr;
    // sampleDirections: uniform numbers in [0, 1)
    const float *u1 = nullptr, *u2 = nullptr;
    // evalSamplerPdf: the direction whose PDF is asked, as the sampler draws it (a half vector
    // or a reflected direction); evalBrdfTerm: the light direction
    const float *woX = nullptr, *woY = nullptr, *woZ = nullptr;
    // evalBrdfTerm: F_Schlick's reflectances
    const float *f0 = nullptr, *f90 = nullptr;
    // sampleDirections: the drawn direction, and its PDF (null: not computed); evalSamplerPdf:
    // the PDF
    float *outX = nullptr, *outY = nullptr, *outZ = nullptr;
    float *outPdf = nullptr;
    // evalBrdfTerm: the term
    float *out = nullptr;
};

SSRT_DECLARE_KERNEL(void, sampleDirections, (Sampler s, const SampleBatch &a, std::size_t n))
SSRT_DECLARE_KERNEL(void, evalSamplerPdf, (Sampler s, const SampleBatch &a, std::size_t n))

inline void sampleDirections(Isa isa, Sampler s, const SampleBatch &a, std::size_t n) {
    SSRT_DISPATCH(isa, sampleDirections)(s, a, n);
}
inline void evalSamplerPdf(Isa isa, Sampler s, const SampleBatch &a, std::size_t n) {
    SSRT_DISPATCH(isa, evalSamplerPdf)(s, a, n);
}

// BRDF terms of shading/brdf.h evaluated on (wi, wo) pairs; h = normalize(wi + wo).
enum class BrdfTerm {
    D_GGX,                 // D_GGX(h.z, alphaX)
    V_SmithGGXCorrelated,  // V_SmithGGXCorrelated(wi.z, wo.z, alphaX)
    F_Schlick,             // F_Schlick(wi.h, f0, f90)
    D_GGXAniso,            // D_GGXAniso(h, alphaX, alphaY)
    Lambda,                // Lambda_GGX(wi)
    G1,                    // G1_GGX(wi)
    G2,                    // G2_GGXCorrelated(wi, wo)
    V_Aniso,               // V_SmithGGXCorrelatedAniso(wi, wo)
    SsrWeight,             // ssrSampleWeight(wi, wo)
    SpecularCos,           // specularCos(wi, wo)
};

SSRT_DECLARE_KERNEL(void, evalBrdfTerm, (BrdfTerm t, const SampleBatch &a, std::size_t n))

inline void evalBrdfTerm(Isa isa, BrdfTerm t, const SampleBatch &a, std::size_t n) {
    SSRT_DISPATCH(isa, evalBrdfTerm)(t, a, n);
}

}  // namespace ssrt
