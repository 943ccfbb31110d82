// Storage formats for a frame's resources (DESIGN.md, "The frame graph"), and their exact
// conversions from and to the float a kernel computes with.
//
// Every conversion is written once over the lane type (core/pixel_formats_lanes.h) from
// correctly rounded float operations and exact integer ones, so the scalar copy and every SIMD
// copy give the same bits (core/pixel_formats_kernels.h runs the per-ISA copies). The
// functions here are the scalar copy, one value at a time: the oracle and the set-up path.
//
//   f32     float as it is
//   f16     IEEE 754-2008 binary16: round to nearest even, subnormals kept, overflow to
//           infinity, NaN stays NaN (quieted, sign and top payload bits kept): the bits of x86
//           F16C (vcvtps2ph with _MM_FROUND_TO_NEAREST_INT, vcvtph2ps) and of aarch64's FCVT
//   f16x4   four f16 channels of one pixel interleaved in one 64-bit element (channel k in
//           bits 16k .. 16k + 15): a pixel's four values in one load or gather
//   unorm8  k = x * 255 rounded to nearest, x clamped to [0, 1]; value k / 255
//   oct16   a unit vector, octahedral map in two snorm16 (Cigolle et al. 2014)
//   u8, u16, u32   a float that holds a non-negative integer (ids, flags, causes)
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ssrt {

enum class PixelFormat : uint8_t { F32, F16, F16x4, Unorm8, OctSnorm16, U8, U16, U32 };

inline constexpr PixelFormat kAllPixelFormats[] = {
    PixelFormat::F32,        PixelFormat::F16, PixelFormat::F16x4, PixelFormat::Unorm8,
    PixelFormat::OctSnorm16, PixelFormat::U8,  PixelFormat::U16,   PixelFormat::U32};

// Stored channels per texel: 2 for oct16 (the snorm16 pair that encodes a 3-vector), 4 for
// f16x4, else 1.
constexpr int channelsPerTexel(PixelFormat format) {
    return format == PixelFormat::OctSnorm16 ? 2 : format == PixelFormat::F16x4 ? 4 : 1;
}

// Bytes one texel takes in memory (all its channels).
constexpr int bytesPerTexel(PixelFormat format) {
    switch (format) {
        case PixelFormat::F32: return 4;
        case PixelFormat::F16: return 2;
        case PixelFormat::F16x4: return 8;
        case PixelFormat::Unorm8: return 1;
        case PixelFormat::OctSnorm16: return 4;
        case PixelFormat::U8: return 1;
        case PixelFormat::U16: return 2;
        case PixelFormat::U32: return 4;
    }
    return 0;
}

// "f32", "f16", "f16x4", "unorm8", "oct16", "u8", "u16", "u32".
std::string_view pixelFormatName(PixelFormat format);

// ---- f16: IEEE 754-2008 binary16 (section 3.6: 1 sign, 5 exponent bits, 10 fraction) -----

// Round to nearest, ties to even. |x| >= 65520 gives infinity; |x| < 2^-25 gives zero (2^-25
// itself is a tie and goes to zero, the even one); NaN gives 0x7e00 | sign | top 9 payload bits.
uint16_t encodeF16(float x);
// Exact (every binary16 value is a float); a NaN comes back quieted with its payload.
float decodeF16(uint16_t h);

// ---- unorm8 ---------------------------------------------------------------------------------

// k = the integer nearest to the exact product 255 x (not to its float rounding), x clamped
// to [0, 1], NaN to 0. The only exact tie in [0, 255] is x = 0.5 (127.5): it goes up to 128,
// which both ties away from zero and ties to even choose, so no tie rule is needed beyond it.
// Nearest to the exact product makes encodeUnorm8(decodeUnorm8(k)) == k for every k and the
// error at most half a step.
uint8_t encodeUnorm8(float x);
// k / 255 as one correctly rounded division: the float nearest to k / 255. (k * (1 / 255.f)
// rounds twice and misses it for some k; tests/core/pixel_formats_test.cpp counts them.)
float decodeUnorm8(uint8_t k);

// ---- oct16: octahedral unit vectors in two snorm16 -----------------------------------------

// Cigolle, Donow, Evangelakos, Mara, McGuire, Meyer 2014, "A Survey of Efficient
// Representations for Independent Unit Vectors", JCGT 3(2): the octahedral map with the lower
// hemisphere folded over the diagonals, each coordinate in [-1, 1] stored as snorm16 (k / 32767;
// -32768 decodes as -1 like -32767). Encoding is the paper's precise variant: of the four codes
// around the point, the one that decodes nearest to the direction. Max angular error 0.00247
// degrees over 4.2 M directions (0.00368 if each axis were rounded on its own); measured in
// tests/core/pixel_formats_test.cpp, which holds it under 0.003.
struct Oct16 {
    int16_t u = 0, v = 0;
};
struct UnitVector {
    float x = 0, y = 0, z = 0;
};
// (x, y, z) need not be normalised (it is projected along its direction); the zero vector
// encodes as +z. Non-finite input gives some code, the same on every ISA.
Oct16 encodeOct16(float x, float y, float z);
// The direction as a unit vector (length 1 within 2 ulp); stable: encode(decode(e)) decodes to
// decode(e)'s bits.
UnitVector decodeOct16(Oct16 e);

// ---- u8, u16, u32: integers carried in floats -----------------------------------------------

// Exact for a float that holds an integer the format can hold (checkIntegerValue). Anything
// else is clamped to the format's range (NaN to 0) and truncated toward zero, the same on every
// ISA: kernels never throw, set-up code checks.
uint8_t encodeU8(float x);
uint16_t encodeU16(float x);
uint32_t encodeU32(float x);
float decodeU8(uint8_t k);
float decodeU16(uint16_t k);
// Exact up to 2^24 and for every value encodeU32 made from a float; others round to nearest
// even (a float has 24 significant bits).
float decodeU32(uint32_t k);

// Largest value the integer format holds: 255, 65535, 4294967295 (0 for other formats).
uint32_t maxIntegerValue(PixelFormat format);

// Set-up validation, not for kernels: throws std::invalid_argument naming `what` and the value
// unless `value` is a finite integer in [0, maxIntegerValue(format)]. `format` must be U8, U16
// or U32 (std::invalid_argument otherwise).
void checkIntegerValue(float value, PixelFormat format, std::string_view what);
// The same for each of `count` values (the message names the first offender and its index).
void checkIntegerValues(const float* values, std::size_t count, PixelFormat format,
                        std::string_view what);

}  // namespace ssrt
