// Array entry points to the pixel format conversions (core/pixel_formats.h), per ISA: what
// the renderer's passes call on a row and what the tests hold to the scalar copy bit for bit.
// Each converts n values (any n; no alignment needed). Oct16 planes are int16_t; a
// Plane<uint16_t> row may be passed through reinterpret_cast (same size, may alias).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"

namespace ssrt {

// clang-format off
SSRT_DECLARE_KERNEL(void, encodeF16, (const float* in, uint16_t* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, decodeF16, (const uint16_t* in, float* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, encodeUnorm8, (const float* in, uint8_t* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, decodeUnorm8, (const uint8_t* in, float* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, encodeOct16, (const float* x, const float* y, const float* z,
                                        int16_t* u, int16_t* v, std::size_t n))
SSRT_DECLARE_KERNEL(void, decodeOct16, (const int16_t* u, const int16_t* v, float* x, float* y,
                                        float* z, std::size_t n))
SSRT_DECLARE_KERNEL(void, encodeU8, (const float* in, uint8_t* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, encodeU16, (const float* in, uint16_t* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, encodeU32, (const float* in, uint32_t* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, decodeU8, (const uint8_t* in, float* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, decodeU16, (const uint16_t* in, float* out, std::size_t n))
SSRT_DECLARE_KERNEL(void, decodeU32, (const uint32_t* in, float* out, std::size_t n))
// The neighbouring-tap gathers (the denoiser's history reads) at index[i], i < n (n a multiple
// of 16): out[k n + i] is lanes::gatherF16Row4's tap k (k < 4), gatherF16Pair's low and high
// (k = 4, 5) and lanes::gatherPair's (k = 6, 7). f16 and f32 must be readable at index + 3.
SSRT_DECLARE_KERNEL(void, gatherNeighbours, (const uint16_t* f16, const float* f32,
                                             const int32_t* index, std::size_t n, float* out))
// f16x4 pixels (n a multiple of 16): channel k of in[i] loaded to loaded[k n + i] (lanes::loadF16x4),
// of in[index[i]] gathered to gathered[k n + i] (lanes::gatherF16x4), and the loaded values
// stored back to stored[i] (lanes::storeF16x4).
SSRT_DECLARE_KERNEL(void, f16x4Lanes, (const uint64_t* in, const int32_t* index, std::size_t n,
                                       float* loaded, float* gathered, uint64_t* stored))
// clang-format on

inline void encodeF16(Isa isa, const float* in, uint16_t* out, std::size_t n) {
    SSRT_DISPATCH(isa, encodeF16)(in, out, n);
}
inline void decodeF16(Isa isa, const uint16_t* in, float* out, std::size_t n) {
    SSRT_DISPATCH(isa, decodeF16)(in, out, n);
}
inline void encodeUnorm8(Isa isa, const float* in, uint8_t* out, std::size_t n) {
    SSRT_DISPATCH(isa, encodeUnorm8)(in, out, n);
}
inline void decodeUnorm8(Isa isa, const uint8_t* in, float* out, std::size_t n) {
    SSRT_DISPATCH(isa, decodeUnorm8)(in, out, n);
}
// (x[i], y[i], z[i]) -> (u[i], v[i])
inline void encodeOct16(Isa isa, const float* x, const float* y, const float* z, int16_t* u,
                        int16_t* v, std::size_t n) {
    SSRT_DISPATCH(isa, encodeOct16)(x, y, z, u, v, n);
}
// (u[i], v[i]) -> unit (x[i], y[i], z[i])
inline void decodeOct16(Isa isa, const int16_t* u, const int16_t* v, float* x, float* y, float* z,
                        std::size_t n) {
    SSRT_DISPATCH(isa, decodeOct16)(u, v, x, y, z, n);
}
inline void encodeU8(Isa isa, const float* in, uint8_t* out, std::size_t n) {
    SSRT_DISPATCH(isa, encodeU8)(in, out, n);
}
inline void encodeU16(Isa isa, const float* in, uint16_t* out, std::size_t n) {
    SSRT_DISPATCH(isa, encodeU16)(in, out, n);
}
inline void encodeU32(Isa isa, const float* in, uint32_t* out, std::size_t n) {
    SSRT_DISPATCH(isa, encodeU32)(in, out, n);
}
inline void decodeU8(Isa isa, const uint8_t* in, float* out, std::size_t n) {
    SSRT_DISPATCH(isa, decodeU8)(in, out, n);
}
inline void decodeU16(Isa isa, const uint16_t* in, float* out, std::size_t n) {
    SSRT_DISPATCH(isa, decodeU16)(in, out, n);
}
inline void decodeU32(Isa isa, const uint32_t* in, float* out, std::size_t n) {
    SSRT_DISPATCH(isa, decodeU32)(in, out, n);
}

inline void gatherNeighbours(Isa isa, const uint16_t* f16, const float* f32, const int32_t* index,
                             std::size_t n, float* out) {
    SSRT_DISPATCH(isa, gatherNeighbours)(f16, f32, index, n, out);
}
inline void f16x4Lanes(Isa isa, const uint64_t* in, const int32_t* index, std::size_t n,
                       float* loaded, float* gathered, uint64_t* stored) {
    SSRT_DISPATCH(isa, f16x4Lanes)(in, index, n, loaded, gathered, stored);
}

}  // namespace ssrt
