// The pixel format conversions of core/pixel_formats.h, written once over the lane type
// (`float` or `xsimd::batch<float, A>`). Float operations are the correctly rounded ones only
// (+ - * /, sqrt, floor, compare, select), the rest is exact integer and bit work, so every
// ISA gives the scalar copy's bits. Codes travel in int32 lanes (IntOf<L>); narrowing them to
// their 8- or 16-bit storage is the caller's (core/pixel_formats_kernel.cpp).
//
// No GLM and nothing that is not templated on the lane type: this is compiled per ISA.
#pragma once

#include "core/lanes.h"

namespace ssrt::lanes {

// ---- f16: IEEE 754-2008 binary16 -----------------------------------------------------------
// After F. Giesen's float_to_half_fast3_rtne and half_to_float ("Half to float done quick",
// 2012, public domain), with F16C's NaN rule: the payload's top bits are kept and quieted.
// It makes no float subnormal and needs none: flush-to-zero modes change nothing.
//
// Where the ISA converts halves itself (x86's F16C, which the avx2 and avx512 copies are
// compiled with: cmake/kernels.cmake, core/isa.cpp) its instructions do the same work with the
// same bits: vcvtps2ph rounds to nearest even by its immediate (not MXCSR's mode) and keeps a
// NaN's top payload bits, quieted; vcvtph2ps is exact (the project sets no DAZ or FTZ, and a
// float subnormal rounds to a signed zero either way). The scalar, SSE and NEON copies keep
// the integer code (aarch64's FCVT is not used).
// tests/core/pixel_formats_test.cpp holds every ISA to the scalar copy's bits, and those to
// the CPU's own conversions and to an oracle in double.

// 256 for an AVX2 batch compiled with F16C, 512 for an AVX-512 one, 0 where the ISA's halves
// are converted in software (scalar, SSE, NEON, or an AVX2 build without -mf16c).
template <class L>
constexpr int hardwareHalfBits() {
    if constexpr (std::is_same_v<L, float>) {
        return 0;
    } else {
#if defined(__AVX512F__)
        if constexpr (std::is_base_of_v<xsimd::avx512f, typename L::arch_type>) return 512;
#endif
#if defined(__AVX2__) && defined(__F16C__)
        if constexpr (std::is_base_of_v<xsimd::avx2, typename L::arch_type>) return 256;
#endif
        return 0;
    }
}

#if defined(__F16C__) || defined(__AVX512F__)
// vcvtps2ph's immediate: round to nearest even whatever MXCSR's mode, no precision exception.
inline constexpr int kHalfRounding = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
#endif
#if defined(__AVX2__) && defined(__F16C__)
// The low 16 bits of each of the 8 int32 lanes, packed into 128 bits (truncated, as
// _mm512_cvtepi32_epi16 does: the lanes' high bits are dropped whatever they hold).
template <class A>
SSRT_INLINE __m128i low16Of(xsimd::batch<int32_t, A> k) {
    const __m256i pick = _mm256_setr_epi8(0, 1, 4, 5, 8, 9, 12, 13, -1, -1, -1, -1, -1, -1, -1, -1,
                                          0, 1, 4, 5, 8, 9, 12, 13, -1, -1, -1, -1, -1, -1, -1, -1);
    return _mm256_castsi256_si128(
        _mm256_permute4x64_epi64(_mm256_shuffle_epi8(__m256i(k), pick), 0x08));
}
#endif

// Binary16 bits (in [0, 65535]) of x, rounded to nearest even.
template <class L>
SSRT_INLINE IntOf<L> f16Bits(L x) {
    using I = IntOf<L>;
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512)
        return I(_mm512_cvtepu16_epi32(_mm512_cvtps_ph(x, kHalfRounding)));
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256)
        return I(_mm256_cvtepu16_epi32(_mm256_cvtps_ph(x, kHalfRounding)));
#endif
    const I bits = lanes::bitsOf(x);
    const I sign = (bits >> 16) & I(0x8000);
    const I a = bits & I(0x7fffffff);  // |x|, as bits
    // |x| < 2^-14: the result is subnormal or zero. Adding 0.5 (ulp 2^-24, the subnormal
    // step) rounds |x| to a multiple of 2^-24, to nearest even by the float addition itself;
    // the bits above 0.5's are the half's (2^-14 comes out as 0x0400, the smallest normal).
    const I sub = lanes::bitsOf(lanes::floatFromBits(a) + L(0.5f)) - I(126 << 23);
    // Normal: rebias the exponent (127 -> 15) and round the 13 dropped bits to nearest even:
    // add 0xfff plus the kept mantissa's lowest bit, then shift. A carry out of the mantissa
    // steps the exponent, up to 0x7c00 (infinity) for |x| in [65520, 65536).
    const I odd = (a >> 13) & I(1);
    const I normal = (a + I(((15 - 127) << 23) + 0xfff) + odd) >> 13;
    // |x| >= 65536 (2^16) is infinity, NaN keeps its sign and top payload bits, quieted.
    const I nan = I(0x7e00) | ((a >> 13) & I(0x3ff));
    const I big = lanes::select(a > I(0x7f800000), nan, I(0x7c00));
    const I h = lanes::select(a >= I(143 << 23), big, lanes::select(a < I(113 << 23), sub, normal));
    return h | sign;
}

// The float of binary16 bits h (in [0, 65535]): exact; a NaN comes back quieted.
template <class L>
SSRT_INLINE L f16Value(IntOf<L> h) {
    using I = IntOf<L>;
    // (The hardware reads each lane's low 16 bits, as the code below does.)
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512) return L(_mm512_cvtph_ps(_mm512_cvtepi32_epi16(h)));
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256) return L(_mm256_cvtph_ps(low16Of(h)));
#endif
    const I o = (h & I(0x7fff)) << 13;  // exponent and mantissa in the float's place
    const I e = o & I(0x7c00 << 13);
    const I rebiased = o + I((127 - 15) << 23);
    // Infinity and NaN: exponent 255; a NaN's quiet bit set (x86 and aarch64 both do)
    const I special =
        (rebiased + I((128 - 16) << 23)) | lanes::select(o > I(0x7c00 << 13), I(0x00400000), I(0));
    // Zero and subnormals: m 2^-24 = (1 + m / 1024) 2^-14 - 2^-14, exact
    const I sub = lanes::bitsOf(lanes::floatFromBits(rebiased + I(1 << 23)) -
                                lanes::floatFromBits(I(113 << 23)));
    const I r =
        lanes::select(e == I(0x7c00 << 13), special, lanes::select(e == I(0), sub, rebiased));
    return lanes::floatFromBits(r | ((h & I(0x8000)) << 16));
}

// f16 planes: binary16 values loaded, stored and gathered as floats, f16Value and f16Bits of
// loadU16, storeU16 and gatherU16 with the same bits, without the int32 lanes in between where
// the hardware converts. A store rounds to nearest even (a value above 65504 may become
// infinity: the caller clamps).
template <class L>
SSRT_INLINE L loadF16(const uint16_t* p) {
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512)
        return L(_mm512_cvtph_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))));
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256)
        return L(_mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
#endif
    return lanes::f16Value<L>(lanes::loadU16<L>(p));
}
template <class L>
SSRT_INLINE void storeF16(uint16_t* p, L x) {
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512)
        return _mm256_storeu_si256(reinterpret_cast<__m256i*>(p),
                                   _mm512_cvtps_ph(x, kHalfRounding));
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256)
        return _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_cvtps_ph(x, kHalfRounding));
#endif
    lanes::storeU16(p, lanes::f16Bits(x));
}
// Per-lane f16 value of base[index], as one load where `run` (runOf(index)) is consecutive.
// The hardware gathers read 32 bits at 2 x index bytes (gatherU16: a 16-bit plane's
// allocation leaves room for the 2 bytes past its end) and the narrowing keeps the low 16.
template <class L>
SSRT_INLINE L gatherF16(const uint16_t* base, IntOf<L> index, Run run) {
    if constexpr (hardwareHalfBits<L>() != 0)
        if (run.consecutive) return lanes::loadF16<L>(base + run.first);
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512)
        return L(_mm512_cvtph_ps(_mm512_cvtepi32_epi16(_mm512_i32gather_epi32(index, base, 2))));
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256)
        return L(_mm256_cvtph_ps(lanes::low16Of(
            IntOf<L>(_mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index, 2)))));
#endif
    return lanes::f16Value<L>(lanes::gatherU16<L>(base, index, run));
}

// Per-lane f16 values of base[index] and base[index + 1] (two horizontally neighbouring
// taps): where the hardware gathers, one 32-bit gather reads both (the low half is
// base[index], x86 being little-endian), half the gathers of two gatherF16; the same bits.
// base[index + 1] must be readable in every lane (the caller's: the plane's own pixel or its
// row padding).
template <class L>
SSRT_INLINE void gatherF16Pair(const uint16_t* base, IntOf<L> index, L& lo, L& hi) {
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512) {
        const __m512i g = _mm512_i32gather_epi32(index, base, 2);
        lo = L(_mm512_cvtph_ps(_mm512_cvtepi32_epi16(g)));
        hi = L(_mm512_cvtph_ps(_mm512_cvtepi32_epi16(_mm512_srli_epi32(g, 16))));
        return;
    }
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256) {
        const __m256i g = _mm256_i32gather_epi32(reinterpret_cast<const int*>(base), index, 2);
        // Per 128 bits: the low halves, then the high ones; then the 64-bit quarters in order
        // (lo of lanes 0-3, 4-7, hi of lanes 0-3, 4-7).
        const __m256i pick = _mm256_setr_epi8(0, 1, 4, 5, 8, 9, 12, 13, 2, 3, 6, 7, 10, 11, 14, 15,
                                              0, 1, 4, 5, 8, 9, 12, 13, 2, 3, 6, 7, 10, 11, 14, 15);
        const __m256i s = _mm256_permute4x64_epi64(_mm256_shuffle_epi8(g, pick), 0xd8);
        lo = L(_mm256_cvtph_ps(_mm256_castsi256_si128(s)));
        hi = L(_mm256_cvtph_ps(_mm256_extracti128_si256(s, 1)));
        return;
    }
#endif
    lo = lanes::gatherF16<L>(base, index, Run{false, 0});
    hi = lanes::gatherF16<L>(base, index + IntOf<L>(1), Run{false, 0});
}

// ---- f16x4: four f16 channels of a pixel in one 64-bit element -----------------------------
// (channel k in bits 16k .. 16k + 15, x86 and aarch64 being little-endian: halves 4 i + k of the
// element array.) Loaded, gathered and stored with the bits of four f16 planes.

#if defined(__AVX512F__)
// The halves of 16 lanes' 64-bit elements (lanes 0-7 in a, 8-15 in b), half k of each lane
// into out[k], converted.
template <class L>
SSRT_INLINE void f16x4Split(__m512i a, __m512i b, L out[4]) {
    // Lane l's half k is half 4 l + k of a:b (32 on: b's).
    alignas(64) static constexpr uint16_t kHalves01[32] = {
        0, 4, 8, 12, 16, 20, 24, 28, 32, 36, 40, 44, 48, 52, 56, 60,
        1, 5, 9, 13, 17, 21, 25, 29, 33, 37, 41, 45, 49, 53, 57, 61};
    const __m512i pick01 = _mm512_load_si512(kHalves01);
    const __m512i t01 = _mm512_permutex2var_epi16(a, pick01, b);
    const __m512i t23 =
        _mm512_permutex2var_epi16(a, _mm512_add_epi16(pick01, _mm512_set1_epi16(2)), b);
    out[0] = L(_mm512_cvtph_ps(_mm512_castsi512_si256(t01)));
    out[1] = L(_mm512_cvtph_ps(_mm512_extracti64x4_epi64(t01, 1)));
    out[2] = L(_mm512_cvtph_ps(_mm512_castsi512_si256(t23)));
    out[3] = L(_mm512_cvtph_ps(_mm512_extracti64x4_epi64(t23, 1)));
}
#endif
#if defined(__AVX2__) && defined(__F16C__)
// The same for 8 lanes (lanes 0-3 in a, 4-7 in b).
template <class L>
SSRT_INLINE void f16x4Split(__m256i a, __m256i b, L out[4]) {
    // Per 128 bits (two lanes' four halves), 32-bit element k = half k of the two lanes.
    const __m256i byHalf = _mm256_setr_epi8(0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15, 0,
                                            1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15);
    const __m256i ta = _mm256_shuffle_epi8(a, byHalf), tb = _mm256_shuffle_epi8(b, byHalf);
    // unpacklo: [half 0 of lanes 0-1, 4-5, half 1 of 0-1, 4-5 | the same of lanes 2-3, 6-7]
    const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
    const __m256i t01 = _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi32(ta, tb), order);
    const __m256i t23 = _mm256_permutevar8x32_epi32(_mm256_unpackhi_epi32(ta, tb), order);
    out[0] = L(_mm256_cvtph_ps(_mm256_castsi256_si128(t01)));
    out[1] = L(_mm256_cvtph_ps(_mm256_extracti128_si256(t01, 1)));
    out[2] = L(_mm256_cvtph_ps(_mm256_castsi256_si128(t23)));
    out[3] = L(_mm256_cvtph_ps(_mm256_extracti128_si256(t23, 1)));
}
#endif

// The integer code's split: lane i's element element(i), half k into out[k].
template <class L, class Element>
SSRT_INLINE void f16x4SplitEach(Element element, L out[4]) {
    using I = IntOf<L>;
    if constexpr (std::is_same_v<L, float>) {
        const uint64_t e = element(0);
        for (int k = 0; k < 4; ++k) out[k] = lanes::f16Value<L>(I((e >> (16 * k)) & 0xffff));
    } else {
        alignas(64) int32_t h[4][L::size];
        for (std::size_t i = 0; i < L::size; ++i) {
            const uint64_t e = element(i);
            for (int k = 0; k < 4; ++k) h[k][i] = int32_t((e >> (16 * k)) & 0xffff);
        }
        for (int k = 0; k < 4; ++k) out[k] = lanes::f16Value<L>(I::load_aligned(h[k]));
    }
}

// The four channels of consecutive pixels p[0 .. lanes).
template <class L>
SSRT_INLINE void loadF16x4(const uint64_t* p, L out[4]) {
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512)
        return lanes::f16x4Split<L>(_mm512_loadu_si512(p), _mm512_loadu_si512(p + 8), out);
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256)
        return lanes::f16x4Split<L>(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)),
                                    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p + 4)),
                                    out);
#endif
    lanes::f16x4SplitEach<L>([p](std::size_t i) { return p[i]; }, out);
}

// The four channels of pixels base[index] (one load where `run`, runOf(index), is consecutive).
template <class L>
SSRT_INLINE void gatherF16x4(const uint64_t* base, IntOf<L> index, Run run, L out[4]) {
    if constexpr (!std::is_same_v<L, float>)
        if (run.consecutive) return lanes::loadF16x4<L>(base + run.first, out);
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512) {
        const __m512i i = index;
        return lanes::f16x4Split<L>(
            _mm512_i32gather_epi64(_mm512_castsi512_si256(i), base, 8),
            _mm512_i32gather_epi64(_mm512_extracti64x4_epi64(i, 1), base, 8), out);
    }
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256) {
        const __m256i i = index;
        const auto* p = reinterpret_cast<const long long*>(base);
        return lanes::f16x4Split<L>(_mm256_i32gather_epi64(p, _mm256_castsi256_si128(i), 8),
                                    _mm256_i32gather_epi64(p, _mm256_extracti128_si256(i, 1), 8),
                                    out);
    }
#endif
    if constexpr (std::is_same_v<L, float>) {
        lanes::f16x4SplitEach<L>([&](std::size_t) { return base[index]; }, out);
    } else {
        alignas(64) int32_t at[L::size];
        index.store_aligned(at);
        lanes::f16x4SplitEach<L>([&](std::size_t i) { return base[at[i]]; }, out);
    }
}

// x[k] into channel k of consecutive pixels p[0 .. lanes), each rounded to nearest even (a
// value above 65504 may become infinity: the caller clamps).
template <class L>
SSRT_INLINE void storeF16x4(uint64_t* p, const L x[4]) {
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512) {
        const __m512i t01 =
            _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvtps_ph(x[0], kHalfRounding)),
                               _mm512_cvtps_ph(x[1], kHalfRounding), 1);
        const __m512i t23 =
            _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvtps_ph(x[2], kHalfRounding)),
                               _mm512_cvtps_ph(x[3], kHalfRounding), 1);
        // Half 4 l + k of lanes 0-7 from channel k's lane l: t01's k 16 + l (k < 2), else
        // t23's, 32 on; lanes 8-15 eight further.
        alignas(64) static constexpr uint16_t kLanes0To7[32] = {
            0, 16, 32, 48, 1, 17, 33, 49, 2, 18, 34, 50, 3, 19, 35, 51,
            4, 20, 36, 52, 5, 21, 37, 53, 6, 22, 38, 54, 7, 23, 39, 55};
        const __m512i pick = _mm512_load_si512(kLanes0To7);
        _mm512_storeu_si512(p, _mm512_permutex2var_epi16(t01, pick, t23));
        _mm512_storeu_si512(p + 8, _mm512_permutex2var_epi16(
                                       t01, _mm512_add_epi16(pick, _mm512_set1_epi16(8)), t23));
        return;
    }
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256) {
        __m128i h[4];
        for (int k = 0; k < 4; ++k) h[k] = _mm256_cvtps_ph(x[k], kHalfRounding);
        // Channels 0 and 1 (2 and 3) side by side per lane, lanes 0-3 and 4-7; then the pairs
        // side by side, two lanes' elements a register.
        const __m128i lo01 = _mm_unpacklo_epi16(h[0], h[1]), hi01 = _mm_unpackhi_epi16(h[0], h[1]);
        const __m128i lo23 = _mm_unpacklo_epi16(h[2], h[3]), hi23 = _mm_unpackhi_epi16(h[2], h[3]);
        auto* q = reinterpret_cast<__m128i*>(p);
        _mm_storeu_si128(q, _mm_unpacklo_epi32(lo01, lo23));
        _mm_storeu_si128(q + 1, _mm_unpackhi_epi32(lo01, lo23));
        _mm_storeu_si128(q + 2, _mm_unpacklo_epi32(hi01, hi23));
        _mm_storeu_si128(q + 3, _mm_unpackhi_epi32(hi01, hi23));
        return;
    }
#endif
    if constexpr (std::is_same_v<L, float>) {
        uint64_t e = 0;
        for (int k = 0; k < 4; ++k) e |= uint64_t(uint32_t(lanes::f16Bits(x[k]))) << (16 * k);
        *p = e;
    } else {
        alignas(64) int32_t h[4][L::size];
        for (int k = 0; k < 4; ++k) lanes::f16Bits(x[k]).store_aligned(h[k]);
        for (std::size_t i = 0; i < L::size; ++i) {
            uint64_t e = 0;
            for (int k = 0; k < 4; ++k) e |= uint64_t(uint32_t(h[k][i])) << (16 * k);
            p[i] = e;
        }
    }
}

// Per-lane f16 values of base[index + k], k = 0..3 (a row of four neighbouring taps of an f16
// plane): where the hardware gathers, one 64-bit element a lane reads all four, split as an
// f16x4 pixel's channels; a quarter of the elements of four gatherF16, the same bits.
// base[index + 3] must be readable in every lane (the caller's).
template <class L>
SSRT_INLINE void gatherF16Row4(const uint16_t* base, IntOf<L> index, L out[4]) {
#if defined(__AVX512F__)
    if constexpr (hardwareHalfBits<L>() == 512) {
        const __m512i i = index;
        return lanes::f16x4Split<L>(
            _mm512_i32gather_epi64(_mm512_castsi512_si256(i), base, 2),
            _mm512_i32gather_epi64(_mm512_extracti64x4_epi64(i, 1), base, 2), out);
    }
#endif
#if defined(__AVX2__) && defined(__F16C__)
    if constexpr (hardwareHalfBits<L>() == 256) {
        const __m256i i = index;
        const auto* p = reinterpret_cast<const long long*>(base);
        return lanes::f16x4Split<L>(_mm256_i32gather_epi64(p, _mm256_castsi256_si128(i), 2),
                                    _mm256_i32gather_epi64(p, _mm256_extracti128_si256(i, 1), 2),
                                    out);
    }
#endif
    for (int k = 0; k < 4; ++k)
        out[k] = lanes::gatherF16<L>(base, index + IntOf<L>(k), Run{false, 0});
}

// ---- unorm8 --------------------------------------------------------------------------------

// The integer nearest to 255 x, x clamped to [0, 1] (NaN to 0), from the exact product.
template <class L>
SSRT_INLINE IntOf<L> unorm8Bits(L x) {
    using I = IntOf<L>;
    x = lanes::select(x > L(0.0f), x, L(0.0f));
    x = lanes::select(x < L(1.0f), x, L(1.0f));
    // 255 x = 256 x - x = hi + lo exactly (256 x is exact; Fast2Sum, Dekker 1971, since
    // |256 x| >= |x|): hi the float sum, lo its rounding error, |lo| <= ulp(hi) / 2.
    const L a = x * L(256.0f);
    const L hi = a - x;
    const L lo = (a - hi) - x;
    // Round hi + lo: d = frac(hi) - 0.5 is exact for hi >= 0.5 and has the right sign below;
    // where d != 0, |d| >= ulp(hi) > |lo| and d decides; where d == 0, lo does. An exact tie
    // (lo == 0 too) happens only at x = 0.5 (127.5): up, to 128.
    const L t = lanes::floor(hi);
    const L d = (hi - t) - L(0.5f);
    const auto up = (d > L(0.0f)) | ((d == L(0.0f)) & (lo >= L(0.0f)));
    return lanes::toIntTrunc(t) + lanes::select(lanes::toIntMask(up), I(1), I(0));
}

// k / 255, one correctly rounded division.
template <class L>
SSRT_INLINE L unorm8Value(IntOf<L> k) {
    return lanes::toFloat(k) / L(255.0f);
}

// ---- oct16: Cigolle et al. 2014, "A Survey of Efficient Representations for Independent
// Unit Vectors", JCGT 3(2), listings 1 and 2 (float32x2 <-> float32x3, then snorm16) --------

// +1 for x >= 0 (either zero included), -1 below.
template <class L>
SSRT_INLINE L signNotZero(L x) {
    return lanes::select(x >= L(0.0f), L(1.0f), L(-1.0f));
}

// k / 32767, with -32768 read as -1 (as graphics APIs read snorm). The code comes as a float
// (an integer in [-32768, 32767], exact) so that the encoder can try codes without converting.
template <class L>
SSRT_INLINE L snorm16Value(L k) {
    return lanes::max(k / L(32767.0f), L(-1.0f));
}

// Listing 2: the square back to the octahedron, unfolded, normalised; codes as floats.
template <class L>
SSRT_INLINE void octDecodeCodes(L cu, L cv, L& x, L& y, L& z) {
    L px = lanes::snorm16Value(cu), py = lanes::snorm16Value(cv);
    const L pz = (L(1.0f) - lanes::abs(px)) - lanes::abs(py);
    // Unfold the lower hemisphere
    const auto lower = pz < L(0.0f);
    const L fx = (L(1.0f) - lanes::abs(py)) * lanes::signNotZero(px);
    const L fy = (L(1.0f) - lanes::abs(px)) * lanes::signNotZero(py);
    px = lanes::select(lower, fx, px);
    py = lanes::select(lower, fy, py);
    // Normalise (|p| >= 1/sqrt(3): no division by zero). Adding +0 turns a -0 (the fold's
    // (1 - 1) * -1) into +0, so a direction has one set of bits and re-encodes to itself.
    const L len = lanes::sqrt(px * px + py * py + pz * pz);
    x = px / len + L(0.0f);
    y = py / len + L(0.0f);
    z = pz / len + L(0.0f);
}

template <class L>
SSRT_INLINE void octDecode(IntOf<L> u, IntOf<L> v, L& x, L& y, L& z) {
    lanes::octDecodeCodes(lanes::toFloat(u), lanes::toFloat(v), x, y, z);
}

// Squared distance between the decoding of codes (cu, cv) and the unit vector t.
template <class L>
SSRT_INLINE L octCodeDistance2(L cu, L cv, L tx, L ty, L tz) {
    L x, y, z;
    lanes::octDecodeCodes(cu, cv, x, y, z);
    const L dx = x - tx, dy = y - ty, dz = z - tz;
    return dx * dx + dy * dy + dz * dz;
}

// Listing 1 and the "precise" encoding of section 3.2 (float32x3_to_octn_precise): of the four
// codes around the projected point (floor or ceil on each axis), the one that decodes nearest
// to the direction. Nearer than rounding each axis (which ignores the map's stretch): the test
// measures both maxima. Distance, not the paper's cosine: at 16 bits neighbouring codes'
// cosines differ by ~1e-9, below a float's resolution near 1.
template <class L>
SSRT_INLINE void octEncode(L x, L y, L z, IntOf<L>& u, IntOf<L>& v) {
    // Project onto the octahedron |x| + |y| + |z| = 1 (the zero vector as +z)
    const L n = lanes::abs(x) + lanes::abs(y) + lanes::abs(z);
    const auto zero = !(n > L(0.0f));
    const L safeN = lanes::select(zero, L(1.0f), n);
    const L px = x / safeN, py = y / safeN, pz = lanes::select(zero, L(1.0f), z / safeN);
    // Fold the lower hemisphere over the diagonals
    const auto lower = pz < L(0.0f);
    const L sx = lanes::select(lower, (L(1.0f) - lanes::abs(py)) * lanes::signNotZero(px), px);
    const L sy = lanes::select(lower, (L(1.0f) - lanes::abs(px)) * lanes::signNotZero(py), py);
    // The direction as a unit vector, the target of the search
    const L len = lanes::sqrt(px * px + py * py + pz * pz);
    const L tx = px / len, ty = py / len, tz = pz / len;
    // Codes below the point on each axis, then the other three corners (ceil capped at 32767;
    // the first strictly nearer one wins, in this fixed order)
    const L m(32767.0f);
    const L fu = lanes::floor(lanes::clamp(sx, L(-1.0f), L(1.0f)) * m);
    const L fv = lanes::floor(lanes::clamp(sy, L(-1.0f), L(1.0f)) * m);
    L bu = fu, bv = fv, best = lanes::octCodeDistance2(fu, fv, tx, ty, tz);
    for (int corner = 1; corner < 4; ++corner) {
        const L cu = lanes::min(fu + L(float(corner & 1)), m);
        const L cv = lanes::min(fv + L(float(corner >> 1)), m);
        const L d = lanes::octCodeDistance2(cu, cv, tx, ty, tz);
        const auto nearer = d < best;
        bu = lanes::select(nearer, cu, bu);
        bv = lanes::select(nearer, cv, bv);
        best = lanes::select(nearer, d, best);
    }
    u = lanes::toIntTrunc(bu);
    v = lanes::toIntTrunc(bv);
}

// ---- u8, u16, u32 from floats that hold integers --------------------------------------------

// x clamped to [0, maxValue] (NaN to 0) and truncated; maxValue is 255, 65535 or the largest
// float below 2^32 (4294967040). Values from 2^31 up go through x - 2^31 (exact, Sterbenz).
template <class L>
SSRT_INLINE IntOf<L> uintBits(L x, float maxValue) {
    using I = IntOf<L>;
    x = lanes::select(x > L(0.0f), x, L(0.0f));
    x = lanes::select(x < L(maxValue), x, L(maxValue));
    const auto high = x >= L(2147483648.0f);
    const I k = lanes::toIntTrunc(lanes::select(high, x - L(2147483648.0f), x));
    return k | lanes::select(lanes::toIntMask(high), I(INT32_MIN), I(0));
}

// The float nearest to the unsigned value of k's bits: 65536 hi + lo, one rounding.
template <class L>
SSRT_INLINE L uintValue(IntOf<L> k) {
    using I = IntOf<L>;
    const L hi = lanes::toFloat((k >> 16) & I(0xffff));
    const L lo = lanes::toFloat(k & I(0xffff));
    return hi * L(65536.0f) + lo;
}

}  // namespace ssrt::lanes
