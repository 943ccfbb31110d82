#include "core/pixel_formats.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/pixel_formats_kernels.h"

namespace ssrt {

std::string_view pixelFormatName(PixelFormat format) {
    switch (format) {
        case PixelFormat::F32: return "f32";
        case PixelFormat::F16: return "f16";
        case PixelFormat::F16x4: return "f16x4";
        case PixelFormat::Unorm8: return "unorm8";
        case PixelFormat::OctSnorm16: return "oct16";
        case PixelFormat::U8: return "u8";
        case PixelFormat::U16: return "u16";
        case PixelFormat::U32: return "u32";
    }
    return "?";
}

// The scalar functions are the scalar kernel copy on one value: one definition of each
// conversion, the one every SIMD copy is tested against.

uint16_t encodeF16(float x) {
    uint16_t h;
    isa_scalar::encodeF16(&x, &h, 1);
    return h;
}

float decodeF16(uint16_t h) {
    float x;
    isa_scalar::decodeF16(&h, &x, 1);
    return x;
}

uint8_t encodeUnorm8(float x) {
    uint8_t k;
    isa_scalar::encodeUnorm8(&x, &k, 1);
    return k;
}

float decodeUnorm8(uint8_t k) {
    float x;
    isa_scalar::decodeUnorm8(&k, &x, 1);
    return x;
}

Oct16 encodeOct16(float x, float y, float z) {
    Oct16 e;
    isa_scalar::encodeOct16(&x, &y, &z, &e.u, &e.v, 1);
    return e;
}

UnitVector decodeOct16(Oct16 e) {
    UnitVector d;
    isa_scalar::decodeOct16(&e.u, &e.v, &d.x, &d.y, &d.z, 1);
    return d;
}

uint8_t encodeU8(float x) {
    uint8_t k;
    isa_scalar::encodeU8(&x, &k, 1);
    return k;
}

uint16_t encodeU16(float x) {
    uint16_t k;
    isa_scalar::encodeU16(&x, &k, 1);
    return k;
}

uint32_t encodeU32(float x) {
    uint32_t k;
    isa_scalar::encodeU32(&x, &k, 1);
    return k;
}

float decodeU8(uint8_t k) {
    float x;
    isa_scalar::decodeU8(&k, &x, 1);
    return x;
}

float decodeU16(uint16_t k) {
    float x;
    isa_scalar::decodeU16(&k, &x, 1);
    return x;
}

float decodeU32(uint32_t k) {
    float x;
    isa_scalar::decodeU32(&k, &x, 1);
    return x;
}

uint32_t maxIntegerValue(PixelFormat format) {
    switch (format) {
        case PixelFormat::U8: return 255u;
        case PixelFormat::U16: return 65535u;
        case PixelFormat::U32: return 4294967295u;
        default: return 0;
    }
}

namespace {

void requireIntegerFormat(PixelFormat format) {
    if (maxIntegerValue(format) == 0)
        throw std::invalid_argument("checkIntegerValue: " + std::string(pixelFormatName(format)) +
                                    " is not an integer format (u8, u16 or u32)");
}

// Whether `value` is an integer in [0, max] (compared in double: 4294967295 is exact there).
bool holdsInteger(float value, uint32_t max) {
    return std::isfinite(value) && value >= 0.0f && std::floor(value) == value &&
           double(value) <= double(max);
}

[[noreturn]] void failInteger(float value, PixelFormat format, std::string_view what,
                              const std::size_t* index) {
    std::ostringstream s;
    s.precision(9);
    s << what;
    if (index) s << "[" << *index << "]";
    s << " = " << value << " is not an integer in [0, " << maxIntegerValue(format) << "] ("
      << pixelFormatName(format) << ")";
    throw std::invalid_argument(s.str());
}

}  // namespace

void checkIntegerValue(float value, PixelFormat format, std::string_view what) {
    requireIntegerFormat(format);
    if (!holdsInteger(value, maxIntegerValue(format))) failInteger(value, format, what, nullptr);
}

void checkIntegerValues(const float* values, std::size_t count, PixelFormat format,
                        std::string_view what) {
    requireIntegerFormat(format);
    const uint32_t max = maxIntegerValue(format);
    for (std::size_t i = 0; i < count; ++i)
        if (!holdsInteger(values[i], max)) failInteger(values[i], format, what, &i);
}

}  // namespace ssrt
