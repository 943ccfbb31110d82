// Instruction sets the kernels are compiled for, and the choice among them at run time.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ssrt {

// Best last within an architecture; the order is the preference order when choosing
// automatically. Scalar runs everywhere; SSE2 to AVX512 are x86-64's, NEON is aarch64's.
enum class Isa { Scalar, SSE2, SSE42, AVX2, AVX512, NEON };

inline constexpr Isa kAllIsas[] = {Isa::Scalar, Isa::SSE2,   Isa::SSE42,
                                   Isa::AVX2,   Isa::AVX512, Isa::NEON};

// Lower-case name as used by --isa and SSRT_ISA: scalar, sse2, sse42, avx2, avx512, neon.
std::string_view isaName(Isa isa);

// The ISAs of the architecture this binary was compiled for (scalar included), best last,
// as one line: "scalar, sse2, sse42, avx2 or avx512" on x86-64, "scalar or neon" on aarch64.
std::string isaChoices();

// True when the ISA belongs to the architecture this binary was compiled for (scalar always):
// only those can be built into it (cmake/kernels.cmake).
bool isaOfThisArchitecture(Isa isa);

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
