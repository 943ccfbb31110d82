// Planes of float values stored as f32 (PlaneF) or as f16 (PlaneU16 of IEEE binary16 bits,
// core/pixel_formats.h): borrowed as a pass's inputs (FloatPlane) and, as a kernel sees them, by
// their first rows (SignalIn, SignalOut; SignalIn4, SignalOut4 for four channels kept together;
// core/signal_lanes.h loads and stores them). Planes of one size share one stride in elements
// whatever their format (core/image.h), so one offset addresses a pixel of any.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/image.h"
#include "core/pixel_formats.h"

namespace ssrt {

// A plane as a kernel reads it: row 0 of one of the two formats, or null.
struct SignalIn {
    const float* f32 = nullptr;
    const uint16_t* f16 = nullptr;
    SignalIn() = default;
    SignalIn(std::nullptr_t) {}
    SignalIn(const float* p) : f32(p) {}
    SignalIn(const uint16_t* p) : f16(p) {}
    explicit operator bool() const { return f32 || f16; }
};
// A plane a kernel writes: f16 (encoded, round to nearest even) or f32.
struct SignalOut {
    float* f32 = nullptr;
    uint16_t* f16 = nullptr;
    SignalOut() = default;
    SignalOut(std::nullptr_t) {}
    SignalOut(float* p) : f32(p) {}
    SignalOut(uint16_t* p) : f16(p) {}
    explicit operator bool() const { return f32 || f16; }
    SignalIn in() const { return f16 ? SignalIn(f16) : SignalIn(f32); }
};

// Four channels of a signal (the denoiser's radiance RGB and hit distance) as a kernel reads
// them: one f16x4 plane (core/pixel_formats.h: a pixel's four values in one 64-bit element,
// one load or gather a tap), or a plane each (f32 or f16, any of them null), set by index.
struct SignalIn4 {
    const uint64_t* f16x4 = nullptr;
    SignalIn ch[4];
    SignalIn4() = default;
    SignalIn4(const uint64_t* p) : f16x4(p) {}
    SignalIn& operator[](int c) { return ch[c]; }
    const SignalIn& operator[](int c) const { return ch[c]; }
};
// The same, written: a channel's own plane may be null (not written); an f16x4 plane takes all
// four.
struct SignalOut4 {
    uint64_t* f16x4 = nullptr;
    SignalOut ch[4];
    SignalOut4() = default;
    SignalOut4(uint64_t* p) : f16x4(p) {}
    SignalOut& operator[](int c) { return ch[c]; }
    const SignalOut& operator[](int c) const { return ch[c]; }
    explicit operator bool() const { return f16x4 || ch[0] || ch[1] || ch[2] || ch[3]; }
};

// A borrowed plane of float values, f32 or f16, or none.
struct FloatPlane {
    const PlaneF* f32 = nullptr;
    const PlaneU16* f16 = nullptr;
    FloatPlane() = default;
    FloatPlane(std::nullptr_t) {}
    FloatPlane(const PlaneF* p) : f32(p) {}
    FloatPlane(const PlaneU16* p) : f16(p) {}
    explicit operator bool() const { return f32 || f16; }
    int width() const { return f16 ? f16->width() : f32 ? f32->width() : 0; }
    int height() const { return f16 ? f16->height() : f32 ? f32->height() : 0; }
    bool empty() const { return width() == 0 || height() == 0; }
    // The value at (x, y) (an f16 decoded: exact).
    float at(int x, int y) const { return f16 ? decodeF16(f16->at(x, y)) : f32->at(x, y); }
};

// The float values of an f16 plane, as a PlaneF (exact).
PlaneF decodedF16(const PlaneU16& p);
// Channel `channel` (0-3) of an f16x4 plane, as an f16 plane of its own (the same bits).
PlaneU16 f16x4Channel(const PlaneU64& p, int channel);

}  // namespace ssrt
