#include "core/isa.h"

#include <cstdlib>
#include <stdexcept>
#include <xsimd/xsimd.hpp>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

namespace ssrt {

std::string_view isaName(Isa isa) {
    switch (isa) {
        case Isa::Scalar: return "scalar";
        case Isa::SSE2: return "sse2";
        case Isa::SSE42: return "sse42";
        case Isa::AVX2: return "avx2";
        case Isa::AVX512: return "avx512";
        case Isa::NEON: return "neon";
    }
    return "unknown";
}

bool isaOfThisArchitecture(Isa isa) {
    if (isa == Isa::Scalar) return true;
#if defined(__x86_64__)
    return isa != Isa::NEON;
#elif defined(__aarch64__)
    return isa == Isa::NEON;
#else
    return false;
#endif
}

namespace {

// F16C (CPUID leaf 1, ECX bit 29): the avx2 and avx512 kernels are compiled with it
// (cmake/kernels.cmake) and convert halves with it. Every AVX2 CPU has it, but a hypervisor
// may hide the bit: without it neither family is offered. (xsimd 8 does not report it; its
// AVX2 check already covers the AVX state the OS must save for these VEX instructions.)
bool cpuHasF16C() {
#if defined(__x86_64__)
    unsigned a = 0, b = 0, c = 0, d = 0;
    return __get_cpuid(1, &a, &b, &c, &d) && (c & bit_F16C) != 0;
#else
    return false;
#endif
}

// "a, b or c" of the given names.
std::string nameList(const std::vector<std::string_view>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += std::string(i == 0                  ? ""
                           : i + 1 == names.size() ? " or "
                                                   : ", ") +
               std::string(names[i]);
    return out;
}

// The architecture of ISAs other than scalar, for the error that names it.
std::string_view architectureOf(Isa isa) { return isa == Isa::NEON ? "aarch64" : "x86-64"; }

}  // namespace

std::string isaChoices() {
    std::vector<std::string_view> names;
    for (Isa isa : kAllIsas)
        if (isaOfThisArchitecture(isa)) names.push_back(isaName(isa));
    return nameList(names);
}

std::optional<Isa> parseIsa(std::string_view name) {
    if (name == "auto") return std::nullopt;
    std::vector<std::string_view> names = {"auto"};
    for (Isa isa : kAllIsas) {
        if (isaName(isa) == name) return isa;
        names.push_back(isaName(isa));
    }
    throw std::invalid_argument("unknown ISA '" + std::string(name) + "' (expected " +
                                nameList(names) + ")");
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
#ifdef SSRT_BUILT_ISA_neon
        case Isa::NEON: return true;
#endif
        default: return false;
    }
}

bool isaSupported(Isa isa) {
    if (!isaBuilt(isa)) return false;
    // xsimd reads CPUID and XGETBV on x86-64 (so an ISA the OS does not save state for is not
    // offered) and the auxiliary vector's hardware capabilities on aarch64.
    const auto cpu = xsimd::available_architectures();
    switch (isa) {
        case Isa::Scalar: return true;
        case Isa::SSE2: return cpu.sse2;
        case Isa::SSE42: return cpu.sse4_2;
        case Isa::AVX2: return cpu.avx2 && cpuHasF16C();
        case Isa::AVX512: return cpu.avx512bw && cpu.avx512dq && cpu.avx512cd && cpuHasF16C();
        case Isa::NEON: return cpu.neon64;
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
    const std::string name(isaName(*requested));
    if (!isaOfThisArchitecture(*requested))
        throw std::runtime_error("ISA '" + name + "' is for " +
                                 std::string(architectureOf(*requested)) +
                                 " CPUs; this binary was built for another architecture");
    if (!isaBuilt(*requested))
        throw std::runtime_error("ISA '" + name +
                                 "' was not built into this binary (cmake -DSSRT_ISAS)");
    if (!isaSupported(*requested))
        throw std::runtime_error("ISA '" + name + "' is not supported by this CPU");
    return *requested;
}

}  // namespace ssrt
