#include "core/isa.h"

#include <cstdlib>
#include <stdexcept>
#include <xsimd/xsimd.hpp>

namespace ssrt {

std::string_view isaName(Isa isa) {
    switch (isa) {
        case Isa::Scalar: return "scalar";
        case Isa::SSE2: return "sse2";
        case Isa::SSE42: return "sse42";
        case Isa::AVX2: return "avx2";
        case Isa::AVX512: return "avx512";
    }
    return "unknown";
}

std::optional<Isa> parseIsa(std::string_view name) {
    if (name == "auto") return std::nullopt;
    for (Isa isa : kAllIsas)
        if (isaName(isa) == name) return isa;
    throw std::invalid_argument("unknown ISA '" + std::string(name) +
                                "' (expected auto, scalar, sse2, sse42, avx2 or avx512)");
}

bool isaBuilt(Isa isa) {
    switch (isa) {
        case Isa::Scalar: return true;
#ifdef SSRT_BUILT_ISA_sse2
        case Isa::SSE2: return true;
#endif
#ifdef SSRT_BUILT_ISA_sse42
        case Isa::SSE42: return true;
#endif
#ifdef SSRT_BUILT_ISA_avx2
        case Isa::AVX2: return true;
#endif
#ifdef SSRT_BUILT_ISA_avx512
        case Isa::AVX512: return true;
#endif
        default: return false;
    }
}

bool isaSupported(Isa isa) {
    if (!isaBuilt(isa)) return false;
    // xsimd reads CPUID and XGETBV, so an ISA the OS does not save state for is not offered.
    const auto cpu = xsimd::available_architectures();
    switch (isa) {
        case Isa::Scalar: return true;
        case Isa::SSE2: return cpu.sse2;
        case Isa::SSE42: return cpu.sse4_2;
        case Isa::AVX2: return cpu.avx2;
        case Isa::AVX512: return cpu.avx512bw && cpu.avx512dq && cpu.avx512cd;
    }
    return false;
}

std::vector<Isa> supportedIsas() {
    std::vector<Isa> out;
    for (Isa isa : kAllIsas)
        if (isaSupported(isa)) out.push_back(isa);
    return out;
}

Isa defaultIsa() {
    if (const char* env = std::getenv("SSRT_ISA"); env && *env) {
        if (auto isa = parseIsa(env)) return resolveIsa(isa);
    }
    return supportedIsas().back();
}

Isa resolveIsa(std::optional<Isa> requested) {
    if (!requested) return defaultIsa();
    if (!isaBuilt(*requested))
        throw std::runtime_error("ISA '" + std::string(isaName(*requested)) +
                                 "' was not built into this binary (cmake -DSSRT_ISAS)");
    if (!isaSupported(*requested))
        throw std::runtime_error("ISA '" + std::string(isaName(*requested)) +
                                 "' is not supported by this CPU");
    return *requested;
}

}  // namespace ssrt
