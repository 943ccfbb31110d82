// Run-time choice among the per-ISA copies of a kernel.
//
// A kernel source (listed in SSRT_KERNEL_SOURCES) is compiled once per ISA; each copy lives
// in namespace ssrt::isa_<name>. A header declares the entry point for every copy with
// SSRT_DECLARE_KERNEL and the caller picks one with SSRT_DISPATCH:
//
//   SSRT_DECLARE_KERNEL(void, shadeTile, (const ShadeArgs& args, int tile))
//   SSRT_DISPATCH(isa, shadeTile)(args, tile);
#pragma once

#include "core/isa.h"

// One namespace per line reads as the table it is: not formatted.
// clang-format off
#define SSRT_DECLARE_KERNEL(ret, name, params)  \
    namespace isa_scalar { ret name params; }   \
    namespace isa_sse2 { ret name params; }     \
    namespace isa_sse42 { ret name params; }    \
    namespace isa_avx2 { ret name params; }     \
    namespace isa_avx512 { ret name params; }   \
    namespace isa_neon { ret name params; }

// Evaluates to a pointer to the chosen copy. Only the copies this build compiled are named
// (SSRT_BUILT_ISA_<name>, set by cmake/kernels.cmake from SSRT_ISAS); isaSupported() never
// offers another, so the scalar default is reached only by Isa::Scalar.
#define SSRT_DISPATCH(isa, name)                              \
    ([&]() {                                                  \
        switch (isa) {                                        \
            SSRT_DISPATCH_CASE_sse2(name)                     \
            SSRT_DISPATCH_CASE_sse42(name)                    \
            SSRT_DISPATCH_CASE_avx2(name)                     \
            SSRT_DISPATCH_CASE_avx512(name)                   \
            SSRT_DISPATCH_CASE_neon(name)                     \
            default: return &isa_scalar::name;                \
        }                                                     \
    }())

#ifdef SSRT_BUILT_ISA_sse2
#define SSRT_DISPATCH_CASE_sse2(name) case ::ssrt::Isa::SSE2: return &isa_sse2::name;
#else
#define SSRT_DISPATCH_CASE_sse2(name)
#endif
#ifdef SSRT_BUILT_ISA_sse42
#define SSRT_DISPATCH_CASE_sse42(name) case ::ssrt::Isa::SSE42: return &isa_sse42::name;
#else
#define SSRT_DISPATCH_CASE_sse42(name)
#endif
#ifdef SSRT_BUILT_ISA_avx2
#define SSRT_DISPATCH_CASE_avx2(name) case ::ssrt::Isa::AVX2: return &isa_avx2::name;
#else
#define SSRT_DISPATCH_CASE_avx2(name)
#endif
#ifdef SSRT_BUILT_ISA_avx512
#define SSRT_DISPATCH_CASE_avx512(name) case ::ssrt::Isa::AVX512: return &isa_avx512::name;
#else
#define SSRT_DISPATCH_CASE_avx512(name)
#endif
#ifdef SSRT_BUILT_ISA_neon
#define SSRT_DISPATCH_CASE_neon(name) case ::ssrt::Isa::NEON: return &isa_neon::name;
#else
#define SSRT_DISPATCH_CASE_neon(name)
#endif
// clang-format on

// A caller compiled without the ssrt target's definitions would dispatch everything to
// scalar, silently; kernel objects (SSRT_ISA_NS) only declare, so they need none.
#if !defined(SSRT_ISA_NS) && !defined(SSRT_BUILT_ISA_scalar)
#error "core/dispatch.h needs the ssrt target's SSRT_BUILT_ISA_* definitions (link ssrt)"
#endif
