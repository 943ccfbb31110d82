// Instruction sets the kernels are compiled for, and the choice among them at run time.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ssrt {

// Best last; the order is the preference order when choosing automatically.
enum class Isa { Scalar, SSE2, SSE42, AVX2, AVX512 };

inline constexpr Isa kAllIsas[] = {Isa::Scalar, Isa::SSE2, Isa::SSE42, Isa::AVX2, Isa::AVX512};

// Lower-case name as used by --isa and SSRT_ISA: scalar, sse2, sse42, avx2, avx512.
std::string_view isaName(Isa isa);

// Parses a name from isaName(), or "auto" (returns nullopt for auto); throws on anything else.
std::optional<Isa> parseIsa(std::string_view name);

// True when this binary holds the ISA's kernels (cmake/kernels.cmake's SSRT_ISAS; every
// family unless a build chose fewer).
bool isaBuilt(Isa isa);

// True when the ISA's kernels are built and this CPU (and OS) can run them.
bool isaSupported(Isa isa);

// Every ISA the machine can run, scalar first.
std::vector<Isa> supportedIsas();

// The best supported ISA, unless the environment variable SSRT_ISA names one.
Isa defaultIsa();

// Resolves a requested ISA (nullopt = default) and throws a clear error if the CPU lacks it.
Isa resolveIsa(std::optional<Isa> requested);

}  // namespace ssrt
