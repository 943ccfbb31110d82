// Pixel formats (core/pixel_formats.h): each conversion against an oracle computed another
// way (double arithmetic, the CPU's own half conversions), and every ISA the machine runs
// against the scalar copy, bit for bit.
#include "core/pixel_formats.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/isa.h"
#include "core/pixel_formats_kernels.h"
#include "core/rng.h"

#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

using namespace ssrt;

namespace {

float fromBits(uint32_t b) {
    float x;
    std::memcpy(&x, &b, 4);
    return x;
}
uint32_t bitsOf(float x) {
    uint32_t b;
    std::memcpy(&b, &x, 4);
    return b;
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// ---- The CPU's own half conversions: F16C on x86-64, FCVT on aarch64 -------------------------
#if defined(__x86_64__)
// F16C: CPUID leaf 1, ECX bit 29, with the AVX state the OS saves (its instructions are VEX
// encoded). (clang 14's __builtin_cpu_supports does not know "f16c"; gcc 12's does.)
bool haveHardwareHalf() {
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (!__get_cpuid(1, &a, &b, &c, &d)) return false;
    return (c & bit_F16C) != 0 && __builtin_cpu_supports("avx");
}
__attribute__((target("f16c"))) void hardwareEncodeF16(const float* in, uint16_t* out,
                                                       std::size_t n) {
    for (std::size_t i = 0; i < n; i += 4) {
        float t[4] = {};
        const std::size_t count = std::min<std::size_t>(4, n - i);
        std::copy_n(in + i, count, t);
        uint16_t o[8];
        _mm_storeu_si128(reinterpret_cast<__m128i*>(o),
                         _mm_cvtps_ph(_mm_loadu_ps(t), _MM_FROUND_TO_NEAREST_INT));
        std::copy_n(o, count, out + i);
    }
}
__attribute__((target("f16c"))) void hardwareDecodeF16(const uint16_t* in, float* out,
                                                       std::size_t n) {
    for (std::size_t i = 0; i < n; i += 4) {
        uint16_t t[8] = {};
        const std::size_t count = std::min<std::size_t>(4, n - i);
        std::copy_n(in + i, count, t);
        float o[4];
        _mm_storeu_ps(o, _mm_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(t))));
        std::copy_n(o, count, out + i);
    }
}
#elif defined(__aarch64__)
bool haveHardwareHalf() { return true; }
void hardwareEncodeF16(const float* in, uint16_t* out, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
        const __fp16 h = static_cast<__fp16>(in[i]);
        std::memcpy(out + i, &h, 2);
    }
}
void hardwareDecodeF16(const uint16_t* in, float* out, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
        __fp16 h;
        std::memcpy(&h, in + i, 2);
        out[i] = static_cast<float>(h);
    }
}
#endif

// ---- f16 oracles in double: IEEE 754-2008 binary16 ---------------------------------------------
double halfValue(uint16_t h) {
    const int e = (h >> 10) & 0x1f, m = h & 0x3ff;
    const double s = (h & 0x8000) ? -1.0 : 1.0;
    if (e == 0) return s * std::ldexp(m, -24);
    if (e == 31) return m ? NAN : s * INFINITY;
    return s * std::ldexp(1024 + m, e - 25);
}

uint16_t oracleEncodeF16(float x) {
    const uint32_t b = bitsOf(x);
    const uint16_t sign = uint16_t((b >> 16) & 0x8000);
    if (std::isnan(x)) return uint16_t(sign | 0x7e00 | ((b >> 13) & 0x3ff));
    const double ax = std::fabs(double(x));
    if (ax >= 65520.0) return uint16_t(sign | 0x7c00);  // 65504 + half its ulp: ties to even
    if (ax < std::ldexp(1.0, -14))                      // subnormal step 2^-24
        return uint16_t(sign | uint16_t(std::nearbyint(std::ldexp(ax, 24))));
    int e;
    std::frexp(ax, &e);  // ax = f 2^e, f in [0.5, 1): step 2^(e - 11)
    const double n = std::nearbyint(std::ldexp(ax, 11 - e));  // in [1024, 2048], to even
    return uint16_t(sign | (((e - 1 + 15) << 10) + int(n) - 1024));
}

// Every ISA the machine runs encodes `in` to the scalar copy's bits, which are the oracle's
// and, where the CPU converts halves, the hardware's.
void checkEncodeF16(const std::vector<float>& in) {
    std::vector<uint16_t> ref(in.size()), got(in.size());
    encodeF16(Isa::Scalar, in.data(), ref.data(), in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        if (ref[i] == oracleEncodeF16(in[i])) continue;
        CAPTURE(bitsOf(in[i]));
        REQUIRE(ref[i] == oracleEncodeF16(in[i]));
    }
    if (haveHardwareHalf()) {
        hardwareEncodeF16(in.data(), got.data(), in.size());
        REQUIRE(sameBits(ref, got));
    }
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        encodeF16(isa, in.data(), got.data(), in.size());
        REQUIRE(sameBits(ref, got));
    }
}

}  // namespace

TEST_CASE("pixel formats: names, channels and bytes") {
    std::set<std::string_view> names;
    for (PixelFormat f : kAllPixelFormats) {
        names.insert(pixelFormatName(f));
        CHECK(bytesPerTexel(f) % channelsPerTexel(f) == 0);
    }
    CHECK(names ==
          std::set<std::string_view>{"f32", "f16", "f16x4", "unorm8", "oct16", "u8", "u16", "u32"});
    CHECK(pixelFormatName(PixelFormat::OctSnorm16) == "oct16");
    CHECK(channelsPerTexel(PixelFormat::OctSnorm16) * 2 == bytesPerTexel(PixelFormat::OctSnorm16));
    CHECK(bytesPerTexel(PixelFormat::F16) == sizeof(uint16_t));
    CHECK(bytesPerTexel(PixelFormat::F16x4) == sizeof(uint64_t));
    CHECK(channelsPerTexel(PixelFormat::F16x4) * 2 == bytesPerTexel(PixelFormat::F16x4));
    CHECK(bytesPerTexel(PixelFormat::Unorm8) == sizeof(uint8_t));
    CHECK(bytesPerTexel(PixelFormat::U32) == sizeof(uint32_t));
    CHECK(bytesPerTexel(PixelFormat::F32) == sizeof(float));
    CHECK(maxIntegerValue(PixelFormat::U16) == 65535u);
}

TEST_CASE("f16: all 65536 halves decode exactly, as the hardware does, on every ISA") {
    std::vector<uint16_t> all(65536);
    for (uint32_t h = 0; h < 65536; ++h) all[h] = uint16_t(h);
    std::vector<float> ref(all.size()), got(all.size());
    decodeF16(Isa::Scalar, all.data(), ref.data(), all.size());
    for (uint32_t h = 0; h < 65536; ++h) {
        CAPTURE(h);
        const double v = halfValue(uint16_t(h));
        if (std::isnan(v)) {
            REQUIRE(std::isnan(ref[h]));
            // quieted, sign and payload kept
            REQUIRE((bitsOf(ref[h]) & 0x80000000u) == (h & 0x8000u) << 16);
            REQUIRE(((bitsOf(ref[h]) >> 13) & 0x1ff) == (h & 0x1ff));
            REQUIRE((bitsOf(ref[h]) & 0x00400000u) != 0);
        } else {
            REQUIRE(double(ref[h]) == v);
            REQUIRE(std::signbit(ref[h]) == bool(h & 0x8000));
        }
        REQUIRE(bitsOf(decodeF16(uint16_t(h))) == bitsOf(ref[h]));
    }
    if (haveHardwareHalf()) {
        hardwareDecodeF16(all.data(), got.data(), all.size());
        REQUIRE(sameBits(ref, got));
    } else {
        MESSAGE("this CPU has no half conversion instructions: hardware identity not checked");
    }
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        decodeF16(isa, all.data(), got.data(), all.size());
        REQUIRE(sameBits(ref, got));
    }
    // and back: every non-NaN half encodes to itself, every NaN to its quieted self
    std::vector<uint16_t> again(all.size());
    encodeF16(Isa::Scalar, ref.data(), again.data(), ref.size());
    for (uint32_t h = 0; h < 65536; ++h)
        REQUIRE(again[h] == (std::isnan(ref[h]) ? (h | 0x0200) : h));
}

TEST_CASE("f16: encoding rounds to nearest even, as the hardware does, on every ISA") {
    std::size_t swept = 0;
    // 1. Every rounding boundary: the midpoint of each pair of adjacent finite halves
    //    (subnormals included) and its neighbours 1 and 2 ulp away, both signs.
    std::vector<float> in;
    for (uint32_t h = 0; h < 0x7c00; ++h) {
        const double mid = 0.5 * (halfValue(uint16_t(h)) + halfValue(uint16_t(h + 1)));
        const float m = float(mid);
        REQUIRE(double(m) == mid);  // representable: 12 significant bits
        for (float x : {m, std::nextafter(m, 0.0f), std::nextafter(m, INFINITY),
                        std::nextafter(std::nextafter(m, 0.0f), 0.0f),
                        std::nextafter(std::nextafter(m, INFINITY), INFINITY)}) {
            in.push_back(x);
            in.push_back(-x);
        }
    }
    // 2. Every float exponent (and sign, NaN and infinity) with the low 13 bits (those a
    //    half drops) at their boundaries: exact, just above, just below and at the halfway
    //    point, with kept mantissas odd and even (all upper 19 bits).
    for (uint32_t upper = 0; upper < (1u << 19); ++upper)
        for (uint32_t low : {0x0u, 0x1u, 0xfffu, 0x1000u, 0x1001u, 0x1fffu})
            in.push_back(fromBits(upper << 13 | low));
    checkEncodeF16(in);
    swept += in.size();
    // 3. Every 251st float bit pattern (17.1 M), a million at a time.
    in.clear();
    for (uint64_t b = 0; b < (uint64_t(1) << 32); b += 251) {
        in.push_back(fromBits(uint32_t(b)));
        if (in.size() == (1u << 20)) {
            checkEncodeF16(in);
            swept += in.size();
            in.clear();
        }
    }
    checkEncodeF16(in);
    swept += in.size();
    MESSAGE("f16 encoding: " << swept << " floats against the oracle, the hardware and every ISA");
    // The edges, spelled out
    CHECK(encodeF16(65504.0f) == 0x7bff);
    CHECK(encodeF16(65519.996f) == 0x7bff);
    CHECK(encodeF16(65520.0f) == 0x7c00);
    CHECK(encodeF16(std::ldexp(1.0f, -25)) == 0x0000);                        // tie to even 0
    CHECK(encodeF16(std::nextafter(std::ldexp(1.0f, -25), 1.0f)) == 0x0001);  // above the tie
    CHECK(encodeF16(std::ldexp(3.0f, -25)) == 0x0002);                        // tie to even 2
    CHECK(encodeF16(-0.0f) == 0x8000);
    CHECK(encodeF16(fromBits(0x7f800001u)) == 0x7e00);  // signalling NaN: quieted, still NaN
}

TEST_CASE("unorm8: decoding is the correctly rounded k / 255") {
    int differs = 0;
    std::vector<uint8_t> codes(256);
    for (int k = 0; k < 256; ++k) {
        CAPTURE(k);
        codes[k] = uint8_t(k);
        const float x = decodeUnorm8(uint8_t(k));
        // the float nearest to k / 255: its neighbours are no nearer (products exact in double)
        const double err = std::fabs(double(x) * 255.0 - k);
        REQUIRE(err <= std::fabs(double(std::nextafter(x, 2.0f)) * 255.0 - k));
        REQUIRE(err <= std::fabs(double(std::nextafter(x, -1.0f)) * 255.0 - k));
        REQUIRE(encodeUnorm8(x) == k);
        volatile float inv = 1.0f / 255.0f;  // (opaque: the multiply happens at run time)
        if (float(k) * inv != x) ++differs;
    }
    MESSAGE("unorm8: k * (1 / 255.f) misses the nearest float to k / 255 for " << differs
                                                                               << " of 256 k");
    CHECK(differs > 0);  // the division is the choice that matters
    std::vector<float> ref(256), got(256);
    decodeUnorm8(Isa::Scalar, codes.data(), ref.data(), 256);
    for (Isa isa : supportedIsas()) {
        decodeUnorm8(isa, codes.data(), got.data(), 256);
        REQUIRE(sameBits(ref, got));
    }
}

TEST_CASE("unorm8: encoding rounds the exact product 255 x to nearest, on every ISA") {
    std::vector<float> in;
    // Around every rounding boundary (2k + 1) / 510: 64 floats either side
    for (int k = 0; k < 255; ++k) {
        float x = float((2.0 * k + 1) / 510.0);
        for (int i = 0; i < 64; ++i) x = std::nextafter(x, 0.0f);
        for (int i = 0; i < 129; ++i, x = std::nextafter(x, 1.0f)) in.push_back(x);
    }
    // Every 61st float in [0, 1] (17.5 M), every 4099th bit pattern, and the specials
    for (uint32_t b = 0; b <= 0x3f800000u; b += 61) in.push_back(fromBits(b));
    for (uint64_t b = 0; b < (uint64_t(1) << 32); b += 4099) in.push_back(fromBits(uint32_t(b)));
    for (float x : {0.0f, -0.0f, 0.5f, 1.0f, -1.0f, 2.0f, INFINITY, -INFINITY, NAN})
        in.push_back(x);
    std::vector<uint8_t> ref(in.size()), got(in.size());
    encodeUnorm8(Isa::Scalar, in.data(), ref.data(), in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        const float c = std::isnan(in[i]) ? 0.0f : std::clamp(in[i], 0.0f, 1.0f);
        const double expected = std::floor(double(c) * 255.0 + 0.5);  // exact in double
        if (ref[i] == expected) continue;
        CAPTURE(in[i]);
        REQUIRE(double(ref[i]) == expected);
    }
    CHECK(encodeUnorm8(0.5f) == 128);  // 127.5, the one exact tie
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        encodeUnorm8(isa, in.data(), got.data(), in.size());
        REQUIRE(sameBits(ref, got));
    }
    MESSAGE("unorm8 encoding: " << in.size() << " floats against the exact rounding and every ISA");
}

namespace {

// Angle in degrees between a float vector and a decoded one, in double.
double angleDegrees(const double a[3], const UnitVector& b) {
    const double bx = b.x, by = b.y, bz = b.z;
    const double cx = a[1] * bz - a[2] * by, cy = a[2] * bx - a[0] * bz, cz = a[0] * by - a[1] * bx;
    const double dot = a[0] * bx + a[1] * by + a[2] * bz;
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * (180.0 / M_PI);
}

}  // namespace

TEST_CASE("oct16: angular error over a dense sweep of the sphere, every ISA the same bits") {
    // A Fibonacci sphere of 4 M directions, plus the axes, the diagonals and the equator's
    // neighbourhood, where the fold changes side.
    std::vector<float> x, y, z;
    auto add = [&](double a, double b, double c) {
        x.push_back(float(a));
        y.push_back(float(b));
        z.push_back(float(c));
    };
    constexpr int kN = 1 << 22;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kN; ++i) {
        const double cz = 1.0 - (2.0 * i + 1.0) / kN, r = std::sqrt(1.0 - cz * cz);
        add(r * std::cos(golden * i), r * std::sin(golden * i), cz);
    }
    for (int i = 0; i < 4096; ++i) {
        const double phi = 2.0 * M_PI * i / 4096.0;
        for (double cz : {0.0, 1e-7, -1e-7, 1e-4, -1e-4}) {
            const double r = std::sqrt(1.0 - cz * cz);
            add(r * std::cos(phi), r * std::sin(phi), cz);
        }
    }
    const double s3 = 1.0 / std::sqrt(3.0), s2 = 1.0 / std::sqrt(2.0);
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int sz : {-1, 1}) {
                add(sx * s3, sy * s3, sz * s3);
                add(sx * s2, sy * s2, 0.0);
                add(sx * s2, 0.0, sz * s2);
                add(0.0, sy * s2, sz * s2);
                add(sx * 1.0, 0.0, 0.0);
                add(0.0, sy * 1.0, 0.0);
                add(0.0, 0.0, sz * 1.0);
            }
    const std::size_t n = x.size();
    std::vector<int16_t> u(n), v(n), gu(n), gv(n);
    encodeOct16(Isa::Scalar, x.data(), y.data(), z.data(), u.data(), v.data(), n);
    std::vector<float> dx(n), dy(n), dz(n), gx(n), gy(n), gz(n);
    decodeOct16(Isa::Scalar, u.data(), v.data(), dx.data(), dy.data(), dz.data(), n);
    double worst = 0, worstLength = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double a[3] = {x[i], y[i], z[i]};
        const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (double& c : a) c /= len;
        const UnitVector d{dx[i], dy[i], dz[i]};
        worst = std::max(worst, angleDegrees(a, d));
        const double dl = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
        worstLength = std::max(worstLength, std::fabs(dl - 1.0));
    }
    MESSAGE("oct16: max angular error " << worst << " degrees over " << n
                                        << " directions; max | |d| - 1 | " << worstLength);
    CHECK(worst < 0.003);
    // The oracle, in double, on every 8th direction: the code each axis rounds to (the plain
    // encoding) and its 8 neighbours, decoded. The encoder's code must be as near as the best
    // of them, up to the float rounding of its distances; the plain encoding is reported.
    double worstRounded = 0, worstExcess = 0;
    for (std::size_t i = 0; i < n; i += 8) {
        double a[3] = {x[i], y[i], z[i]};
        const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (double& c : a) c /= len;
        const double l1 = std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]);
        double px = a[0] / l1, py = a[1] / l1;
        if (a[2] < 0) {
            const double fx = (1 - std::fabs(py)) * (px >= 0 ? 1 : -1);
            py = (1 - std::fabs(px)) * (py >= 0 ? 1 : -1);
            px = fx;
        }
        const double ru = std::round(px * 32767), rv = std::round(py * 32767);
        double best = 1e30;
        for (int du = -1; du <= 1; ++du)
            for (int dv = -1; dv <= 1; ++dv) {
                const Oct16 c{int16_t(std::clamp(ru + du, -32767.0, 32767.0)),
                              int16_t(std::clamp(rv + dv, -32767.0, 32767.0))};
                const double e = angleDegrees(a, decodeOct16(c));
                best = std::min(best, e);
                if (du == 0 && dv == 0) worstRounded = std::max(worstRounded, e);
            }
        const double ours = angleDegrees(a, decodeOct16(Oct16{u[i], v[i]}));
        worstExcess = std::max(worstExcess, ours - best);
    }
    MESSAGE("oct16: rounding each axis instead: max " << worstRounded << " degrees; the encoder's"
                                                      << " excess over the best of 9 codes at most "
                                                      << worstExcess << " degrees");
    CHECK(worst < worstRounded);
    CHECK(worstExcess < 2e-5);
    CHECK(worstLength <= 2.0 * std::ldexp(1.0, -24) * 2.0);  // 2 ulp of 1 (its ulp below 1)
    // Axes exactly
    CHECK(encodeOct16(0, 0, 1).u == 0);
    CHECK(encodeOct16(1, 0, 0).u == 32767);
    CHECK(decodeOct16(encodeOct16(0, 0, -1)).z == -1.0f);
    CHECK(decodeOct16(encodeOct16(0, 0, 0)).z == 1.0f);  // the zero vector as +z
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        encodeOct16(isa, x.data(), y.data(), z.data(), gu.data(), gv.data(), n);
        REQUIRE(sameBits(u, gu));
        REQUIRE(sameBits(v, gv));
        decodeOct16(isa, u.data(), v.data(), gx.data(), gy.data(), gz.data(), n);
        REQUIRE(sameBits(dx, gx));
        REQUIRE(sameBits(dy, gy));
        REQUIRE(sameBits(dz, gz));
    }
}

TEST_CASE("oct16: decode(encode(decode(e))) == decode(e), on every ISA") {
    // Every u with the edge and middle values of v (and every v with those of u), plus 2 M
    // hashed codes.
    std::vector<int16_t> u, v;
    for (int a = -32768; a < 32768; ++a)
        for (int b : {-32768, -32767, -32766, -1, 0, 1, 12345, 32766, 32767}) {
            u.push_back(int16_t(a));
            v.push_back(int16_t(b));
            u.push_back(int16_t(b));
            v.push_back(int16_t(a));
        }
    for (uint32_t i = 0; i < (1u << 21); ++i) {
        const uint32_t r = pcgHash(i * 2654435761u ^ 0x9e3779b9u);
        u.push_back(int16_t(uint16_t(r)));
        v.push_back(int16_t(uint16_t(r >> 16)));
    }
    const std::size_t n = u.size();
    std::vector<float> x(n), y(n), z(n), x2(n), y2(n), z2(n);
    std::vector<int16_t> u2(n), v2(n);
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        decodeOct16(isa, u.data(), v.data(), x.data(), y.data(), z.data(), n);
        encodeOct16(isa, x.data(), y.data(), z.data(), u2.data(), v2.data(), n);
        decodeOct16(isa, u2.data(), v2.data(), x2.data(), y2.data(), z2.data(), n);
        REQUIRE(sameBits(x, x2));
        REQUIRE(sameBits(y, y2));
        REQUIRE(sameBits(z, z2));
    }
    MESSAGE("oct16 stability: " << n << " codes");
}

TEST_CASE("u8, u16, u32: integers in floats, exact, every ISA the same bits") {
    // u8 and u16: every value there is
    std::vector<float> f8(256), f16(65536), back;
    std::vector<uint8_t> c8(256), g8(256);
    std::vector<uint16_t> c16(65536), g16(65536);
    for (int k = 0; k < 65536; ++k) {
        c16[k] = uint16_t(k);
        if (k < 256) c8[k] = uint8_t(k);
    }
    decodeU8(Isa::Scalar, c8.data(), f8.data(), 256);
    decodeU16(Isa::Scalar, c16.data(), f16.data(), 65536);
    for (int k = 0; k < 65536; ++k) {
        REQUIRE(f16[k] == float(k));
        REQUIRE(encodeU16(f16[k]) == k);
        if (k < 256) REQUIRE((f8[k] == float(k) && encodeU8(f8[k]) == k));
    }
    // u32: every integer up to 2^24 in steps of 3, every 7th float from 2^24 up to 2^32
    std::vector<float> f32;
    for (uint32_t k = 0; k <= (1u << 24); k += 3) f32.push_back(float(k));
    for (uint32_t b = bitsOf(16777216.0f); b < bitsOf(4294967296.0f); b += 7)
        f32.push_back(fromBits(b));
    f32.push_back(4294967040.0f);
    std::vector<uint32_t> c32(f32.size()), g32(f32.size());
    encodeU32(Isa::Scalar, f32.data(), c32.data(), f32.size());
    back.resize(f32.size());
    decodeU32(Isa::Scalar, c32.data(), back.data(), f32.size());
    for (std::size_t i = 0; i < f32.size(); ++i) {
        CAPTURE(f32[i]);
        REQUIRE(double(c32[i]) == double(f32[i]));
        REQUIRE(back[i] == f32[i]);
    }
    // decodeU32 of any value rounds to nearest even, as C++'s conversion does
    for (uint64_t k = 0; k < (uint64_t(1) << 32); k += 65521)
        REQUIRE(decodeU32(uint32_t(k)) == float(uint32_t(k)));
    // Out of range, NaN and fractions: clamped and truncated, the same on every ISA
    std::vector<float> odd = {-1.0f,    -0.0f,         0.5f,   1.75f,         254.9f,
                              255.0f,   255.5f,        256.0f, 65535.5f,      65536.0f,
                              1e9f,     2147483648.0f, 3e9f,   4294967296.0f, 1e30f,
                              INFINITY, -INFINITY,     NAN,    -NAN};
    CHECK(encodeU8(NAN) == 0);
    CHECK(encodeU8(300.0f) == 255);
    CHECK(encodeU16(-3.0f) == 0);
    CHECK(encodeU32(1e30f) == 4294967040u);
    CHECK(encodeU32(3e9f) == 3000000000u);
    f32.insert(f32.end(), odd.begin(), odd.end());
    std::vector<uint32_t> r32(f32.size());
    encodeU32(Isa::Scalar, f32.data(), r32.data(), f32.size());
    odd.insert(odd.end(), f16.begin(), f16.end());
    std::vector<uint8_t> r8(odd.size()), o8(odd.size());
    std::vector<uint16_t> r16(odd.size()), o16(odd.size());
    encodeU8(Isa::Scalar, odd.data(), r8.data(), odd.size());
    encodeU16(Isa::Scalar, odd.data(), r16.data(), odd.size());
    std::vector<float> d8(256), d16(65536), d32(f32.size());
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        encodeU8(isa, odd.data(), o8.data(), odd.size());
        encodeU16(isa, odd.data(), o16.data(), odd.size());
        g32.resize(f32.size());
        encodeU32(isa, f32.data(), g32.data(), f32.size());
        REQUIRE(sameBits(r8, o8));
        REQUIRE(sameBits(r16, o16));
        REQUIRE(sameBits(r32, g32));
        decodeU8(isa, c8.data(), d8.data(), 256);
        decodeU16(isa, c16.data(), d16.data(), 65536);
        REQUIRE(sameBits(f8, d8));
        REQUIRE(sameBits(f16, d16));
        decodeU32(isa, r32.data(), d32.data(), r32.size());
        std::vector<float> s32(r32.size());
        decodeU32(Isa::Scalar, r32.data(), s32.data(), r32.size());
        REQUIRE(sameBits(s32, d32));
    }
}

TEST_CASE("integer formats: set-up validation names the value") {
    const auto message = [](float value, PixelFormat f) {
        try {
            checkIntegerValue(value, f, "objectId");
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    for (PixelFormat f : {PixelFormat::U8, PixelFormat::U16, PixelFormat::U32}) {
        CHECK_NOTHROW(checkIntegerValue(0.0f, f, "v"));
        CHECK_NOTHROW(checkIntegerValue(255.0f, f, "v"));
        for (float bad : {-1.0f, 0.5f, NAN, INFINITY, 4294967296.0f})
            CHECK_THROWS_AS(checkIntegerValue(bad, f, "v"), std::invalid_argument);
    }
    CHECK_THROWS_AS(checkIntegerValue(256.0f, PixelFormat::U8, "v"), std::invalid_argument);
    CHECK_NOTHROW(checkIntegerValue(65535.0f, PixelFormat::U16, "v"));
    CHECK_THROWS_AS(checkIntegerValue(65536.0f, PixelFormat::U16, "v"), std::invalid_argument);
    CHECK_NOTHROW(checkIntegerValue(4294967040.0f, PixelFormat::U32, "v"));
    CHECK_THROWS_AS(checkIntegerValue(1.0f, PixelFormat::F16, "v"), std::invalid_argument);
    const std::string m = message(256.5f, PixelFormat::U8);
    CHECK(m.find("objectId") != std::string::npos);
    CHECK(m.find("256.5") != std::string::npos);
    CHECK(m.find("u8") != std::string::npos);
    const float values[] = {1.0f, 2.0f, 70000.0f, 3.0f};
    CHECK_NOTHROW(checkIntegerValues(values, 4, PixelFormat::U32, "ids"));
    try {
        checkIntegerValues(values, 4, PixelFormat::U16, "ids");
        FAIL("70000 is not a u16");
    } catch (const std::invalid_argument& e) {
        CHECK(std::string(e.what()).find("ids[2] = 70000") != std::string::npos);
    }
}

TEST_CASE(
    "Plane<uint16_t> and Plane<uint8_t>: a float plane's stride, hashes of the visible "
    "pixels") {
    PlaneU16 a(37, 5, 0x1234);
    PlaneU8 b(37, 5, 7);
    // One offset addresses a pixel in planes of one size whatever their formats.
    CHECK(a.stride() == PlaneF(37, 5).stride());
    CHECK(b.stride() == PlaneF(37, 5).stride());
    CHECK(a.stride() % kRowElements == 0);
    CHECK(PlaneU16(48, 1).stride() == PlaneF(48, 1).stride());
    CHECK(a.stride() >= 37);
    CHECK(b.stride() >= 37);
    const uint64_t ha = hashPlane(a), hb = hashPlane(b);
    CHECK(hashPlane(a.clone()) == ha);
    CHECK(hashPlane(b.clone()) == hb);
    // padding is not hashed; a visible pixel is
    a.row(2)[a.stride() - 1] = 99;
    b.row(2)[b.stride() - 1] = 99;
    CHECK(hashPlane(a) == ha);
    CHECK(hashPlane(b) == hb);
    a.at(36, 4) = 0x1235;
    b.at(36, 4) = 8;
    CHECK(hashPlane(a) != ha);
    CHECK(hashPlane(b) != hb);
    // the same bytes hash alike whatever the element type: FNV-1a over bytes
    PlaneU8 bytes(2, 1, 0);
    bytes.at(0, 0) = 0x34;
    bytes.at(1, 0) = 0x12;
    CHECK(hashPlane(bytes) == hashPlane(PlaneU16(1, 1, 0x1234)));
    b.fill(3);
    CHECK(b.at(0, 0) == 3);
    CHECK(b.at(36, 4) == 3);
}

TEST_CASE(
    "neighbouring-tap gathers: a row of four f16 taps, an f16 pair and an f32 pair, every "
    "ISA the same bits as reading each tap") {
    // Every half (NaNs with their payloads included) and f32 values of every class, NaNs with
    // payloads and both signs among them, at random indices (4 taps readable from each).
    const std::size_t size = 65536 + 3, n = 4096;
    std::vector<uint16_t> f16(size);
    std::vector<float> f32(size);
    for (std::size_t i = 0; i < size; ++i) {
        f16[i] = uint16_t((i * 40503u) & 0xffffu);
        const uint32_t bits = uint32_t(i * 2654435761u);
        std::memcpy(&f32[i], &bits, sizeof bits);
    }
    std::vector<int32_t> index(n);
    for (std::size_t i = 0; i < n; ++i)
        index[i] = int32_t(randomFloat(uint32_t(i), 1, 7, 0) * float(size - 3)) % int32_t(size - 3);
    std::vector<float> expected(8 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const int32_t x = index[i];
        for (int k = 0; k < 4; ++k) expected[k * n + i] = decodeF16(f16[x + k]);
        expected[4 * n + i] = decodeF16(f16[x]);
        expected[5 * n + i] = decodeF16(f16[x + 1]);
        expected[6 * n + i] = f32[x];
        expected[7 * n + i] = f32[x + 1];
    }
    std::vector<float> got(8 * n);
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        std::fill(got.begin(), got.end(), 0.0f);
        gatherNeighbours(isa, f16.data(), f32.data(), index.data(), n, got.data());
        REQUIRE(sameBits(expected, got));
    }
}

TEST_CASE(
    "f16x4: loads, gathers and stores of four f16 channels a pixel, every ISA the bits of "
    "each half on its own") {
    // Every half in every channel (NaNs with their payloads included), at random indices and in
    // runs of consecutive ones (a gather that is a load).
    const std::size_t n = 65536;
    std::vector<uint64_t> in(n);
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 4; ++k)
            in[i] |= uint64_t((i * 40503u + std::size_t(k) * 12345u) & 0xffffu) << (16 * k);
    std::vector<int32_t> index(n);
    for (std::size_t i = 0; i < n; ++i)
        index[i] = i < n / 2 ? int32_t(randomFloat(uint32_t(i), 2, 7, 0) * float(n)) % int32_t(n)
                             : int32_t(i ^ 16);  // (runs of 16 moved by 16)
    const auto half = [&](std::size_t i, int k) { return uint16_t(in[i] >> (16 * k)); };
    std::vector<float> loaded(4 * n), gathered(4 * n), wantLoaded(4 * n), wantGathered(4 * n);
    std::vector<uint64_t> stored(n), wantStored(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 4; ++k) {
            wantLoaded[k * n + i] = decodeF16(half(i, k));
            wantGathered[k * n + i] = decodeF16(half(std::size_t(index[i]), k));
            wantStored[i] |= uint64_t(encodeF16(decodeF16(half(i, k)))) << (16 * k);
        }
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        f16x4Lanes(isa, in.data(), index.data(), n, loaded.data(), gathered.data(), stored.data());
        REQUIRE(sameBits(wantLoaded, loaded));
        REQUIRE(sameBits(wantGathered, gathered));
        REQUIRE(stored == wantStored);
    }
}
