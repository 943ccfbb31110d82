#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>

#include "core/pixel_formats_kernels.h"
#include "core/pixel_formats_lanes.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;

namespace {

using Int = ln::IntOf<Lane>;
constexpr std::size_t kWidthN = std::size_t(kW);  // (kW as a size, for the counts below)

// One lane group from `count` (<= kW) values, zeros past them.
SSRT_INLINE Lane loadFloats(const float* p, std::size_t count) {
    if (count == kWidthN) return ln::load<Lane>(p);
    float t[kWidthN] = {};
    std::copy_n(p, count, t);
    return ln::load<Lane>(t);
}

template <class T>
SSRT_INLINE Int loadCodes(const T* p, std::size_t count) {
    int32_t t[kWidthN] = {};
    for (std::size_t k = 0; k < count; ++k) t[k] = int32_t(p[k]);  // (u32: modulo 2^32)
    return ln::loadInt<Lane>(t);
}

SSRT_INLINE void storeFloats(float* p, Lane x, std::size_t count) {
    if (count == kWidthN) return ln::store(p, x);
    float t[kWidthN];
    ln::store(t, x);
    std::copy_n(t, count, p);
}

template <class T>
SSRT_INLINE void storeCodes(T* p, Int k, std::size_t count) {
    int32_t t[kWidthN];
    ln::store(t, k);
    for (std::size_t i = 0; i < count; ++i) p[i] = T(uint32_t(t[i]));  // low bits: the code
}

// out[i] = code of in[i], a lane group at a time.
template <class T, class Encode>
SSRT_INLINE void encodeRow(const float* in, T* out, std::size_t n, Encode encode) {
    for (std::size_t i = 0; i < n; i += kWidthN) {
        const std::size_t count = std::min(kWidthN, n - i);
        storeCodes(out + i, encode(loadFloats(in + i, count)), count);
    }
}

template <class T, class Decode>
SSRT_INLINE void decodeRow(const T* in, float* out, std::size_t n, Decode decode) {
    for (std::size_t i = 0; i < n; i += kWidthN) {
        const std::size_t count = std::min(kWidthN, n - i);
        storeFloats(out + i, decode(loadCodes(in + i, count)), count);
    }
}

}  // namespace

void encodeF16(const float* in, uint16_t* out, std::size_t n) {
    encodeRow(in, out, n, [](Lane x) { return ln::f16Bits(x); });
}
void decodeF16(const uint16_t* in, float* out, std::size_t n) {
    decodeRow(in, out, n, [](Int h) { return ln::f16Value<Lane>(h); });
}
void encodeUnorm8(const float* in, uint8_t* out, std::size_t n) {
    encodeRow(in, out, n, [](Lane x) { return ln::unorm8Bits(x); });
}
void decodeUnorm8(const uint8_t* in, float* out, std::size_t n) {
    decodeRow(in, out, n, [](Int k) { return ln::unorm8Value<Lane>(k); });
}

void encodeOct16(const float* x, const float* y, const float* z, int16_t* u, int16_t* v,
                 std::size_t n) {
    for (std::size_t i = 0; i < n; i += kWidthN) {
        const std::size_t count = std::min(kWidthN, n - i);
        Int cu, cv;
        ln::octEncode(loadFloats(x + i, count), loadFloats(y + i, count), loadFloats(z + i, count),
                      cu, cv);
        storeCodes(u + i, cu, count);
        storeCodes(v + i, cv, count);
    }
}

void decodeOct16(const int16_t* u, const int16_t* v, float* x, float* y, float* z, std::size_t n) {
    for (std::size_t i = 0; i < n; i += kWidthN) {
        const std::size_t count = std::min(kWidthN, n - i);
        Lane dx, dy, dz;
        ln::octDecode<Lane>(loadCodes(u + i, count), loadCodes(v + i, count), dx, dy, dz);
        storeFloats(x + i, dx, count);
        storeFloats(y + i, dy, count);
        storeFloats(z + i, dz, count);
    }
}

void encodeU8(const float* in, uint8_t* out, std::size_t n) {
    encodeRow(in, out, n, [](Lane x) { return ln::uintBits(x, 255.0f); });
}
void encodeU16(const float* in, uint16_t* out, std::size_t n) {
    encodeRow(in, out, n, [](Lane x) { return ln::uintBits(x, 65535.0f); });
}
void encodeU32(const float* in, uint32_t* out, std::size_t n) {
    // (4294967040 = 2^32 - 256, the largest float below 2^32)
    encodeRow(in, out, n, [](Lane x) { return ln::uintBits(x, 4294967040.0f); });
}
void decodeU8(const uint8_t* in, float* out, std::size_t n) {
    decodeRow(in, out, n, [](Int k) { return ln::uintValue<Lane>(k); });
}
void decodeU16(const uint16_t* in, float* out, std::size_t n) {
    decodeRow(in, out, n, [](Int k) { return ln::uintValue<Lane>(k); });
}
void decodeU32(const uint32_t* in, float* out, std::size_t n) {
    decodeRow(in, out, n, [](Int k) { return ln::uintValue<Lane>(k); });
}

void gatherNeighbours(const uint16_t* f16, const float* f32, const int32_t* index, std::size_t n,
                      float* out) {
    for (std::size_t i = 0; i < n; i += kWidthN) {
        const Int idx = ln::loadInt<Lane>(index + i);
        Lane t[8];
        ln::gatherF16Row4<Lane>(f16, idx, t);
        ln::gatherF16Pair<Lane>(f16, idx, t[4], t[5]);
        ln::gatherPair(f32, idx, t[6], t[7]);
        for (int k = 0; k < 8; ++k) ln::store(out + std::size_t(k) * n + i, t[k]);
    }
}

void f16x4Lanes(const uint64_t* in, const int32_t* index, std::size_t n, float* loaded,
                float* gathered, uint64_t* stored) {
    for (std::size_t i = 0; i < n; i += kWidthN) {
        const Int idx = ln::loadInt<Lane>(index + i);
        Lane l[4], g[4];
        ln::loadF16x4<Lane>(in + i, l);
        ln::gatherF16x4<Lane>(in, idx, ln::runOf(idx), g);
        ln::storeF16x4<Lane>(stored + i, l);
        for (int k = 0; k < 4; ++k) {
            ln::store(loaded + std::size_t(k) * n + i, l[k]);
            ln::store(gathered + std::size_t(k) * n + i, g[k]);
        }
    }
}

}  // namespace ssrt::SSRT_ISA_NS
