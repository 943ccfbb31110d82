// Included first by every kernel source (SSRT_KERNEL_SOURCES). It names the lane type of
// the ISA this copy is compiled for: `Lane` is float for the scalar copy and an
// xsimd::batch<float, Arch> otherwise. Kernels are written once over `Lane`.
#pragma once

#include <cstddef>

#include "core/lanes.h"
#include "core/xsimd_exact.h"

#if defined(SSRT_ISA_scalar)
#define SSRT_KERNEL_SCALAR 1
#elif defined(SSRT_ISA_sse2)
#define SSRT_ARCH xsimd::sse2
#elif defined(SSRT_ISA_sse42)
#define SSRT_ARCH xsimd::sse4_2
#if !defined(__SSE4_2__)
#error "the sse42 kernels must be compiled with -msse4.2"
#endif
#elif defined(SSRT_ISA_avx2)
#define SSRT_ARCH xsimd::avx2
#if !defined(__AVX2__)
#error "the avx2 kernels must be compiled with -mavx2"
#endif
#elif defined(SSRT_ISA_avx512)
#define SSRT_ARCH xsimd::avx512bw
#if !defined(__AVX512BW__)
#error "the avx512 kernels must be compiled with -mavx512bw"
#endif
#elif defined(SSRT_ISA_neon)
#define SSRT_ARCH xsimd::neon64
#if !defined(__aarch64__)
#error "the neon kernels are aarch64's (xsimd::neon64)"
#endif
#else
#error "kernel sources are compiled through ssrt_add_isa_kernels (cmake/kernels.cmake)"
#endif

namespace ssrt::SSRT_ISA_NS {
#if defined(SSRT_KERNEL_SCALAR)
using Lane = float;
#else
using Lane = xsimd::batch<float, SSRT_ARCH>;
#endif

// This copy's lane count and its plain load, defined once for every kernel file of the copy
// (a unity build compiles several of them as one source, where a copy per file would clash).
inline constexpr int kW = int(ssrt::lanes::kWidth<Lane>);
SSRT_INLINE Lane loadAt(const float* plane, std::size_t offset) {
    return ssrt::lanes::load<Lane>(plane + offset);
}
}  // namespace ssrt::SSRT_ISA_NS
