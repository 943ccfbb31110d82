// Array entry points to the lane math, per ISA: what the tests hold to the scalar copy bit
// for bit, and what the benchmarks time.
#pragma once

#include <cstddef>

#include "core/dispatch.h"

namespace ssrt {

enum class MathFn { Floor, Sqrt, Exp2, Log2, Exp, Log, Pow, Sin, Cos, Asin, Acos, Atan, Atan2 };

SSRT_DECLARE_KERNEL(void, evalMath,
                    (MathFn fn, const float* a, const float* b, float* out, std::size_t n))

// out[i] = fn(a[i]) or fn(a[i], b[i]) (pow, atan2), on the given ISA's copy.
inline void evalMath(Isa isa, MathFn fn, const float* a, const float* b, float* out,
                     std::size_t n) {
    SSRT_DISPATCH(isa, evalMath)(fn, a, b, out, n);
}

}  // namespace ssrt
