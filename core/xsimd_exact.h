// xsimd, with float division and square root correctly rounded on every architecture.
//
// Include this instead of <xsimd/xsimd.hpp> wherever a kernel may divide or take a square root
// of float batches (core/isa_target.h and core/lanes.h do).
//
// xsimd 8.1's neon64 inherits float division and sqrt from its 32-bit neon architecture, which
// has no vector division or square root instruction: it estimates the reciprocal
// (vrecpeq_f32, vrsqrteq_f32) and refines it with Newton steps, results a few ulps away from
// the correctly rounded ones that scalar code and every x86 ISA give (arch/xsimd_neon.hpp; later
// xsimd versions give neon64 its own). AArch64 has both instructions (FDIV, FSQRT on vectors),
// so the neon64 copies are specialised here to use them. These are explicit specialisations of
// xsimd's own templates, not overloads: the batch operators call them by qualified name, and
// only a specialisation of the template they already name is found wherever it is declared,
// as long as it comes before the first use in the file (hence: include this one first).
// tests/core/lane_math_test.cpp compares them with the scalar operations on every ISA.
#pragma once

#include <xsimd/xsimd.hpp>

#if defined(__aarch64__)
namespace xsimd::kernel {

template <>
inline batch<float, neon64> div<neon64>(batch<float, neon64> const& lhs,
                                        batch<float, neon64> const& rhs,
                                        requires_arch<neon>) noexcept {
    return vdivq_f32(lhs, rhs);
}

template <>
inline batch<float, neon64> sqrt<neon64>(batch<float, neon64> const& x,
                                         requires_arch<neon>) noexcept {
    return vsqrtq_f32(x);
}

}  // namespace xsimd::kernel
#endif
