// Planes of float values stored as f32 (PlaneF) or as f16 (PlaneU16 of IEEE binary16 bits,
// core/pixel_formats.h): borrowed as a pass's inputs (FloatPlane) and, as a kernel sees them, by
// their first rows (SignalIn, SignalOut; core/signal_lanes.h loads and stores them). Planes of
// one size share one stride in elements whatever their format (core/image.h), so one offset
// addresses a pixel of either.
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

}  // namespace ssrt
