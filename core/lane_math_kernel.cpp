#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "core/lane_math.h"
#include "core/lane_math_kernels.h"
#include "core/rng_lanes.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;

static SSRT_INLINE Lane apply(MathFn fn, Lane a, Lane b) {
    switch (fn) {
        case MathFn::Floor: return ln::floor(a);
        case MathFn::Sqrt: return ln::sqrt(a);
        case MathFn::Div: return a / b;
        case MathFn::Exp2: return ln::exp2(a);
        case MathFn::Log2: return ln::log2(a);
        case MathFn::Exp: return ln::exp(a);
        case MathFn::Log: return ln::log(a);
        case MathFn::Pow: return ln::pow(a, b);
        case MathFn::Sin: return ln::sin(a);
        case MathFn::Cos: return ln::cos(a);
        case MathFn::Asin: return ln::asin(a);
        case MathFn::Acos: return ln::acos(a);
        case MathFn::Atan: return ln::atan(a);
        case MathFn::Atan2: return ln::atan2(a, b);
    }
    return a;
}

void evalMath(MathFn fn, const float* a, const float* b, float* out, std::size_t n) {
    constexpr std::size_t w = ln::kWidth<Lane>;
    std::size_t i = 0;
    for (; i + w <= n; i += w)
        ln::store(out + i, apply(fn, ln::load<Lane>(a + i), ln::load<Lane>(b ? b + i : a + i)));
    if (i == n) return;
    // Tail: pad to a full lane group (padding lanes compute on 1.0 and are dropped).
    float ta[w], tb[w], to[w];
    for (std::size_t k = 0; k < w; ++k) {
        ta[k] = i + k < n ? a[i + k] : 1.0f;
        tb[k] = i + k < n ? (b ? b[i + k] : a[i + k]) : 1.0f;
    }
    ln::store(to, apply(fn, ln::load<Lane>(ta), ln::load<Lane>(tb)));
    for (std::size_t k = 0; i + k < n; ++k) out[i + k] = to[k];
}

void evalRandom(uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t dim, float* out,
                std::size_t n) {
    constexpr std::size_t w = ln::kWidth<Lane>;
    for (std::size_t i = 0; i < n; i += w) {
        float group[w];
        ln::store(group, ln::randomFloats<Lane>(pixel + uint32_t(i), frame, sample, dim));
        for (std::size_t k = 0; k < w && i + k < n; ++k) out[i + k] = group[k];
    }
}

}  // namespace ssrt::SSRT_ISA_NS
