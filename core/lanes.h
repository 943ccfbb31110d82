// Lane-generic primitives: one spelling for `float` and `xsimd::batch<float, A>`.
//
// Call them qualified (`lanes::sin(x)`, or through `namespace ln = ssrt::lanes`): an
// unqualified call on an xsimd batch also finds xsimd's functions of the same name by
// argument-dependent lookup, and theirs (more specialised) would win and break the
// scalar == SIMD bit contract. tests/core/lane_math_test.cpp catches a slip.
//
// Kernels are written once over a lane type L and use only these functions (plus the
// arithmetic operators), so the scalar copy and every SIMD width execute the same
// correctly rounded operations in the same order and give the same bits. Everything here
// is always_inline: no out-of-line copy compiled with one ISA's flags can be shared by the
// linker with code compiled for another.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/xsimd_exact.h"

#define SSRT_INLINE inline __attribute__((always_inline))

namespace ssrt::lanes {

// ---- Lane traits ------------------------------------------------------------------------
template <class L>
struct Traits;

template <>
struct Traits<float> {
    using Int = int32_t;
    using Mask = bool;
    using IntMask = bool;
    static constexpr std::size_t kWidth = 1;
};

template <class A>
struct Traits<xsimd::batch<float, A>> {
    using Int = xsimd::batch<int32_t, A>;
    using Mask = xsimd::batch_bool<float, A>;
    using IntMask = xsimd::batch_bool<int32_t, A>;
    static constexpr std::size_t kWidth = xsimd::batch<float, A>::size;
};

template <class L>
using IntOf = typename Traits<L>::Int;
template <class L>
using MaskOf = typename Traits<L>::Mask;
template <class L>
using IntMaskOf = typename Traits<L>::IntMask;
template <class L>
inline constexpr std::size_t kWidth = Traits<L>::kWidth;

// ---- Select, min, max (NaN behaviour pinned down: min(a, b) = a < b ? a : b) ----------
SSRT_INLINE float select(bool m, float a, float b) { return m ? a : b; }
SSRT_INLINE int32_t select(bool m, int32_t a, int32_t b) { return m ? a : b; }
template <class A>
SSRT_INLINE xsimd::batch<float, A> select(xsimd::batch_bool<float, A> m, xsimd::batch<float, A> a,
                                          xsimd::batch<float, A> b) {
    return xsimd::select(m, a, b);
}
template <class A>
SSRT_INLINE xsimd::batch<int32_t, A> select(xsimd::batch_bool<int32_t, A> m,
                                            xsimd::batch<int32_t, A> a,
                                            xsimd::batch<int32_t, A> b) {
    return xsimd::select(m, a, b);
}

// Comparisons: <, <=, >, >= and == are false for NaN on every ISA, but xsimd's != is
// ordered (false for NaN) with AVX and AVX-512 and unordered (true) with SSE and in scalar
// code. Where a NaN can reach a test of inequality, write !(a == b): the same on every ISA.
template <class L>
SSRT_INLINE L min(L a, L b) {
    return lanes::select(a < b, a, b);
}
template <class L>
SSRT_INLINE L max(L a, L b) {
    return lanes::select(a > b, a, b);
}
template <class L>
SSRT_INLINE L clamp(L x, L lo, L hi) {
    return lanes::min(lanes::max(x, lo), hi);
}
template <class L>
SSRT_INLINE L saturate(L x) {
    return lanes::clamp(x, L(0.0f), L(1.0f));
}

// ---- Correctly rounded unary operations -------------------------------------------------
SSRT_INLINE float sqrt(float x) { return __builtin_sqrtf(x); }
template <class A>
SSRT_INLINE xsimd::batch<float, A> sqrt(xsimd::batch<float, A> x) {
    return xsimd::sqrt(x);
}

SSRT_INLINE float abs(float x) { return __builtin_fabsf(x); }
template <class A>
SSRT_INLINE xsimd::batch<float, A> abs(xsimd::batch<float, A> x) {
    return xsimd::abs(x);
}

// ---- Integer lanes ----------------------------------------------------------------------
SSRT_INLINE int32_t toIntTrunc(float x) { return static_cast<int32_t>(x); }
template <class A>
SSRT_INLINE xsimd::batch<int32_t, A> toIntTrunc(xsimd::batch<float, A> x) {
    return xsimd::to_int(x);
}
SSRT_INLINE float toFloat(int32_t x) { return static_cast<float>(x); }
template <class A>
SSRT_INLINE xsimd::batch<float, A> toFloat(xsimd::batch<int32_t, A> x) {
    return xsimd::to_float(x);
}
SSRT_INLINE int32_t bitsOf(float x) {
    int32_t i;
    std::memcpy(&i, &x, 4);
    return i;
}
template <class A>
SSRT_INLINE xsimd::batch<int32_t, A> bitsOf(xsimd::batch<float, A> x) {
    return xsimd::bitwise_cast<xsimd::batch<int32_t, A>>(x);
}
SSRT_INLINE float floatFromBits(int32_t i) {
    float x;
    std::memcpy(&x, &i, 4);
    return x;
}
template <class A>
SSRT_INLINE xsimd::batch<float, A> floatFromBits(xsimd::batch<int32_t, A> i) {
    return xsimd::bitwise_cast<xsimd::batch<float, A>>(i);
}

// floor through truncation, identical on every ISA (SSE2 has no rounding instruction):
// |x| >= 2^23 is already integral; otherwise truncate and step down where that rounded up.
template <class L>
SSRT_INLINE L floor(L x) {
    const L big(8388608.0f);
    const L t = lanes::toFloat(lanes::toIntTrunc(lanes::select(lanes::abs(x) < big, x, L(0.0f))));
    const L f = lanes::select(t > x, t - L(1.0f), t);
    return lanes::select(lanes::abs(x) < big, f, x);
}

// ---- Masks ------------------------------------------------------------------------------
SSRT_INLINE bool any(bool m) { return m; }
SSRT_INLINE bool all(bool m) { return m; }
template <class T, class A>
SSRT_INLINE bool any(xsimd::batch_bool<T, A> m) {
    return xsimd::any(m);
}
template <class T, class A>
SSRT_INLINE bool all(xsimd::batch_bool<T, A> m) {
    return xsimd::all(m);
}

// Exclusive or of two masks. Not `a ^ b`: xsimd 8.1's AVX-512 batch_bool xor is an or
// (arch/xsimd_avx512f.hpp returns self.data | other.data), and not `a != b`, which 8.1
// compares as floats on SSE/AVX (an all-ones mask is a NaN).
SSRT_INLINE bool maskXor(bool a, bool b) { return a != b; }
template <class T, class A>
SSRT_INLINE xsimd::batch_bool<T, A> maskXor(xsimd::batch_bool<T, A> a, xsimd::batch_bool<T, A> b) {
    return (a | b) & ~(a & b);
}

// Float mask -> int mask and back, for selects across types.
SSRT_INLINE bool toIntMask(bool m) { return m; }
// (xsimd 8.1 has no batch_bool_cast: select 1 or 0 and compare in the other type.)
template <class A>
SSRT_INLINE xsimd::batch_bool<int32_t, A> toIntMask(xsimd::batch_bool<float, A> m) {
    using F = xsimd::batch<float, A>;
    return xsimd::to_int(xsimd::select(m, F(1.0f), F(0.0f))) != xsimd::batch<int32_t, A>(0);
}
SSRT_INLINE bool toFloatMask(bool m) { return m; }
template <class A>
SSRT_INLINE xsimd::batch_bool<float, A> toFloatMask(xsimd::batch_bool<int32_t, A> m) {
    using I = xsimd::batch<int32_t, A>;
    return xsimd::to_float(xsimd::select(m, I(1), I(0))) != xsimd::batch<float, A>(0.0f);
}

// Bit i set when lane i is true (lane order = memory order).
SSRT_INLINE uint64_t maskBits(bool m) { return m ? 1u : 0u; }
template <class A>
SSRT_INLINE uint64_t maskBits(xsimd::batch_bool<float, A> m) {
    // xsimd 8.1 has no batch_bool::mask(): read the register with the ISA's own movemask.
#if defined(__aarch64__)
    static_assert(xsimd::batch_bool<float, A>::size == 4);
    // NEON has no movemask: keep bit i of lane i (each lane is all ones or all zeros) and add.
    const uint32x4_t bits = m;  // (a float mask's register is uint32x4_t on NEON)
    const uint32x4_t laneBit = {1u, 2u, 4u, 8u};
    return uint64_t(vaddvq_u32(vandq_u32(bits, laneBit)));
#else
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>) return uint64_t(__mmask16(m));
    else
#endif
#if defined(__AVX__)
        if constexpr (std::is_base_of_v<xsimd::avx, A>)
        return uint64_t(_mm256_movemask_ps(m));
    else
#endif
        return uint64_t(_mm_movemask_ps(m));
#endif
}
template <class A>
SSRT_INLINE uint64_t maskBits(xsimd::batch_bool<int32_t, A> m) {
    return lanes::maskBits(lanes::toFloatMask(m));
}

// ---- Memory -----------------------------------------------------------------------------
template <class L>
SSRT_INLINE L load(const float* p) {
    if constexpr (std::is_same_v<L, float>) return *p;
    else return L::load_unaligned(p);
}
template <class L>
SSRT_INLINE IntOf<L> loadInt(const int32_t* p) {
    if constexpr (std::is_same_v<L, float>) return *p;
    else return IntOf<L>::load_unaligned(p);
}
SSRT_INLINE void store(float* p, float x) { *p = x; }
SSRT_INLINE void store(int32_t* p, int32_t x) { *p = x; }
template <class A>
SSRT_INLINE void store(float* p, xsimd::batch<float, A> x) {
    x.store_unaligned(p);
}
template <class A>
SSRT_INLINE void store(int32_t* p, xsimd::batch<int32_t, A> x) {
    x.store_unaligned(p);
}

// Store that bypasses the caches (no read for ownership) for planes written once per frame;
// `p` must be aligned to the lane group. Call streamFence() before another thread reads.
SSRT_INLINE void storeStream(float* p, float x) { *p = x; }
template <class A>
SSRT_INLINE void storeStream(float* p, xsimd::batch<float, A> x) {
#if defined(__aarch64__)
    x.store_aligned(p);  // (NEON's non-temporal pair stores are scalar; a plain store it is)
#else
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>) _mm512_stream_ps(p, x);
    else
#endif
#if defined(__AVX__)
        if constexpr (std::is_base_of_v<xsimd::avx, A>)
        _mm256_stream_ps(p, x);
    else
#endif
        _mm_stream_ps(p, x);
#endif
}
SSRT_INLINE void streamFence() {
#if defined(__SSE2__)
    _mm_sfence();
#endif
}

// 16-bit codes (f16 bits, core/pixel_formats_lanes.h) to and from int32 lanes, zero-extended;
// a store keeps each lane's low 16 bits (the codes are in [0, 65535]). Memory only.
template <class L>
SSRT_INLINE IntOf<L> loadU16(const uint16_t* p) {
    if constexpr (std::is_same_v<L, float>) {
        return int32_t(*p);
    } else {
#if defined(__AVX512F__)
        if constexpr (std::is_base_of_v<xsimd::avx512f, typename L::arch_type>)
            return IntOf<L>(
                _mm512_cvtepu16_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))));
        else
#endif
#if defined(__AVX2__)
            if constexpr (std::is_base_of_v<xsimd::avx2, typename L::arch_type>)
            return IntOf<L>(
                _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
        else
#endif
        {
            alignas(64) int32_t t[L::size];
            for (std::size_t i = 0; i < L::size; ++i) t[i] = int32_t(p[i]);
            return IntOf<L>::load_aligned(t);
        }
    }
}
SSRT_INLINE void storeU16(uint16_t* p, int32_t k) { *p = uint16_t(uint32_t(k)); }
template <class A>
SSRT_INLINE void storeU16(uint16_t* p, xsimd::batch<int32_t, A> k) {
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>)
        return _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm512_cvtepi32_epi16(k));
    else
#endif
#if defined(__AVX2__)
        if constexpr (std::is_base_of_v<xsimd::avx2, A>) {
        const __m256i v = k;
        const __m128i packed =
            _mm_packus_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
        return _mm_storeu_si128(reinterpret_cast<__m128i*>(p), packed);
    } else
#endif
    {
        alignas(64) int32_t t[xsimd::batch<int32_t, A>::size];
        k.store_aligned(t);
        for (std::size_t i = 0; i < xsimd::batch<int32_t, A>::size; ++i)
            p[i] = uint16_t(uint32_t(t[i]));
    }
}
// Lane i holds float(i).
template <class L>
SSRT_INLINE L laneIndex() {
    alignas(64) float idx[kWidth<L>];
    for (std::size_t i = 0; i < kWidth<L>; ++i) idx[i] = static_cast<float>(i);
    return load<L>(idx);
}

// Per-lane load base[index] (hardware gather where the ISA has one: loads are exact, so
// every ISA returns the same bits).
SSRT_INLINE float gather(const float* base, int32_t index) { return base[index]; }
template <class A>
SSRT_INLINE xsimd::batch<float, A> gather(const float* base, xsimd::batch<int32_t, A> index) {
    // xsimd 8.1 gathers floats one lane at a time; use the hardware gather where there is one.
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>) return _mm512_i32gather_ps(index, base, 4);
    else
#endif
#if defined(__AVX2__)
        if constexpr (std::is_base_of_v<xsimd::avx2, A>)
        return _mm256_i32gather_ps(base, index, 4);
    else
#endif
        return xsimd::batch<float, A>::gather(base, index);
}

// Whether a tap's lanes read consecutive elements (lane i's index is lane 0's plus i), and
// lane 0's index: where they do, one load does a gather's work with the same bits. Taps on a
// still or panning camera's history, and neighbours at a fixed offset, are such runs.
struct Run {
    bool consecutive;
    int32_t first;
};
SSRT_INLINE Run runOf(int32_t index) { return {true, index}; }
template <class A>
SSRT_INLINE Run runOf(xsimd::batch<int32_t, A> index) {
    using I = xsimd::batch<int32_t, A>;
    alignas(64) int32_t lane[I::size];
    alignas(64) int32_t iota[I::size];
    index.store_aligned(lane);
    for (std::size_t i = 0; i < I::size; ++i) iota[i] = int32_t(i);
    return {xsimd::all(index == I(lane[0]) + I::load_aligned(iota)), lane[0]};
}
// gather(base, index), as one load where `run` (runOf(index)) is consecutive.
SSRT_INLINE float gather(const float* base, int32_t index, Run) { return base[index]; }
template <class A>
SSRT_INLINE xsimd::batch<float, A> gather(const float* base, xsimd::batch<int32_t, A> index,
                                          Run run) {
    if (run.consecutive) return xsimd::batch<float, A>::load_unaligned(base + run.first);
    return gather(base, index);
}

// Per-lane table[index] from a short table: pickFromOne's of kWidth floats (index < kWidth),
// pickFromTwo's of twice that (index < 2 kWidth). Read as whole vectors and picked by a
// register permute where the ISA has one (AVX-512: vpermps, vpermt2ps; AVX2: vpermps, and two
// of them and a blend), else gathered: the same values either way. For lanes that read a few
// neighbouring elements each (a level table, pixels that pairs of lanes share).
template <class L>
inline constexpr bool kPicksInRegisters = false;
#if defined(__AVX2__)
template <class A>
inline constexpr bool kPicksInRegisters<xsimd::batch<float, A>> =
    std::is_base_of_v<xsimd::avx2, A> || std::is_base_of_v<xsimd::avx512f, A>;
#endif

SSRT_INLINE float pickFromOne(const float* table, int32_t index) { return table[index]; }
template <class A>
SSRT_INLINE xsimd::batch<float, A> pickFromOne(const float* table, xsimd::batch<int32_t, A> index) {
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>)
        return _mm512_permutexvar_ps(index, _mm512_loadu_ps(table));
#endif
#if defined(__AVX2__)
    if constexpr (std::is_base_of_v<xsimd::avx2, A>)
        return _mm256_permutevar8x32_ps(_mm256_loadu_ps(table), index);
#endif
    return gather(table, index);
}

SSRT_INLINE float pickFromTwo(const float* table, int32_t index) { return table[index]; }
template <class A>
SSRT_INLINE xsimd::batch<float, A> pickFromTwo(const float* table, xsimd::batch<int32_t, A> index) {
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>)
        return _mm512_permutex2var_ps(_mm512_loadu_ps(table), index, _mm512_loadu_ps(table + 16));
#endif
#if defined(__AVX2__)
    if constexpr (std::is_base_of_v<xsimd::avx2, A>) {
        const __m256i i = index;
        const __m256 lo = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table), i);
        const __m256 hi = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table + 8), i);
        const __m256i upper = _mm256_cmpgt_epi32(i, _mm256_set1_epi32(7));
        return _mm256_blendv_ps(lo, hi, _mm256_castsi256_ps(upper));
    }
#endif
    return gather(table, index);
}

// Per-lane base[index] and base[index + 1] (two horizontally neighbouring taps): where the
// hardware gathers, one 64-bit element a lane reads both (two 8-lane gathers on AVX-512, two
// 4-lane ones on AVX2, then one shuffle apart), half the elements of two 32-bit gathers; the
// same bits as gather(base, index) and gather(base, index + 1). base[index + 1] must be
// readable in every lane (the caller's: the plane's own pixel or its row padding).
SSRT_INLINE void gatherPair(const float* base, int32_t index, float& lo, float& hi) {
    lo = base[index];
    hi = base[index + 1];
}
template <class A>
SSRT_INLINE void gatherPair(const float* base, xsimd::batch<int32_t, A> index,
                            xsimd::batch<float, A>& lo, xsimd::batch<float, A>& hi) {
#if defined(__AVX512F__)
    if constexpr (std::is_base_of_v<xsimd::avx512f, A>) {
        const __m512i i = index;
        const __m512 a =
            _mm512_castsi512_ps(_mm512_i32gather_epi64(_mm512_castsi512_si256(i), base, 4));
        const __m512 b =
            _mm512_castsi512_ps(_mm512_i32gather_epi64(_mm512_extracti64x4_epi64(i, 1), base, 4));
        const __m512i even =
            _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
        lo = _mm512_permutex2var_ps(a, even, b);
        hi = _mm512_permutex2var_ps(a, _mm512_add_epi32(even, _mm512_set1_epi32(1)), b);
        return;
    }
#endif
#if defined(__AVX2__)
    if constexpr (std::is_base_of_v<xsimd::avx2, A>) {
        const __m256i i = index;
        const auto* p = reinterpret_cast<const long long*>(base);
        const __m256 a =
            _mm256_castsi256_ps(_mm256_i32gather_epi64(p, _mm256_castsi256_si128(i), 4));
        const __m256 b =
            _mm256_castsi256_ps(_mm256_i32gather_epi64(p, _mm256_extracti128_si256(i, 1), 4));
        // (per 128 bits: a's and b's even (odd) floats, then the 64-bit quarters in order)
        lo = _mm256_castpd_ps(
            _mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(a, b, 0x88)), 0xd8));
        hi = _mm256_castpd_ps(
            _mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(a, b, 0xdd)), 0xd8));
        return;
    }
#endif
    lo = gather(base, index);
    hi = gather(base, index + xsimd::batch<int32_t, A>(1));
}

// Per-lane base[index] of 16-bit codes (loadU16), as one load where `run` is consecutive.
template <class L>
SSRT_INLINE IntOf<L> gatherU16(const uint16_t* base, IntOf<L> index, Run run) {
    if constexpr (std::is_same_v<L, float>) {
        return int32_t(base[index]);
    } else {
        if (run.consecutive) return loadU16<L>(base + run.first);
            // The hardware gathers read 32 bits at 2 x index bytes and keep the low 16 (x86 is
            // little-endian): 2 bytes past the last element are read, which a 16-bit plane's
            // allocation leaves room for (core/image.cpp).
#if defined(__AVX512F__)
        if constexpr (std::is_base_of_v<xsimd::avx512f, typename L::arch_type>)
            return IntOf<L>(_mm512_i32gather_epi32(index, base, 2)) & IntOf<L>(0xffff);
        else
#endif
#if defined(__AVX2__)
            if constexpr (std::is_base_of_v<xsimd::avx2, typename L::arch_type>)
            return IntOf<L>(_mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index, 2)) &
                   IntOf<L>(0xffff);
        else
#endif
        {
            alignas(64) int32_t lane[L::size];
            index.store_aligned(lane);
            for (std::size_t i = 0; i < L::size; ++i) lane[i] = int32_t(base[lane[i]]);
            return IntOf<L>::load_aligned(lane);
        }
    }
}

}  // namespace ssrt::lanes
