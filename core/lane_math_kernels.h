// Array entry points to the lane math, per ISA: what the tests hold to the scalar copy bit
// for bit, and what the benchmarks time.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"

namespace ssrt {

enum class MathFn {
    Floor,
    Sqrt,
    Div,
    Exp2,
    Log2,
    Exp,
    Log,
    Pow,
    Sin,
    Cos,
    Asin,
    Acos,
    Atan,
    Atan2
};

SSRT_DECLARE_KERNEL(void, evalMath,
                    (MathFn fn, const float* a, const float* b, float* out, std::size_t n))

// out[i] = fn(a[i]) or fn(a[i], b[i]) (division, pow, atan2), on the given ISA's copy.
inline void evalMath(Isa isa, MathFn fn, const float* a, const float* b, float* out,
                     std::size_t n) {
    SSRT_DISPATCH(isa, evalMath)(fn, a, b, out, n);
}

SSRT_DECLARE_KERNEL(void, evalRandom,
                    (uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t dim, float* out,
                     std::size_t n))

// out[i] = randomFloat(pixel + i, frame, sample, dim), lane group by lane group
// (lanes::randomFloats, core/rng_lanes.h), on the given ISA's copy.
inline void evalRandom(Isa isa, uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t dim,
                       float* out, std::size_t n) {
    SSRT_DISPATCH(isa, evalRandom)(pixel, frame, sample, dim, out, n);
}

}  // namespace ssrt
