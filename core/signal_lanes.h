// Loads, stores and gathers of f32-or-f16 planes (core/float_planes.h: SignalIn, SignalOut) on
// lanes, through core/pixel_formats_lanes.h's conversions (F16C in the avx2 and avx512 copies,
// the integer code elsewhere: the same bits on every ISA). A value above f16's largest finite
// one is stored as that, 65504 (as the denoiser's signals: nothing becomes infinity); NaN stays
// NaN. Compiled per ISA, like the lanes it is written over.
#pragma once

#include <cstddef>

#include "core/float_planes.h"
#include "core/lanes.h"
#include "core/pixel_formats_lanes.h"

namespace ssrt::lanes {

template <class L>
SSRT_INLINE L loadSignal(SignalIn p, std::size_t offset) {
    if (p.f16) return lanes::loadF16<L>(p.f16 + offset);
    return lanes::load<L>(p.f32 + offset);
}
template <class L>
SSRT_INLINE L gatherSignal(SignalIn p, IntOf<L> index, Run run) {
    if (p.f16) return lanes::gatherF16<L>(p.f16, index, run);
    return lanes::gather(p.f32, index, run);
}
template <class L>
SSRT_INLINE L gatherSignal(SignalIn p, IntOf<L> index) {
    if (p.f16) return lanes::gatherF16<L>(p.f16, index, lanes::runOf(index));
    return lanes::gather(p.f32, index);
}
// x clamped to f16's largest finite value (NaN kept): what an f16 store keeps of it.
template <class L>
SSRT_INLINE L clampedToF16(L x) {
    const L big(65504.0f);
    return lanes::select(x > big, big, x);
}
// What an f16 plane gives back for x (storeSignal then loadSignal).
template <class L>
SSRT_INLINE L roundedToF16(L x) {
    return lanes::f16Value<L>(lanes::f16Bits(lanes::clampedToF16(x)));
}
template <class L>
SSRT_INLINE void storeSignal(SignalOut p, std::size_t offset, L x) {
    if (p.f16) return lanes::storeF16(p.f16 + offset, lanes::clampedToF16(x));
    lanes::store(p.f32 + offset, x);
}

// Four channels together (SignalIn4, SignalOut4): an f16x4 plane's in one load, gather or store
// of a pixel's 64-bit element (core/pixel_formats_lanes.h), the same values as four planes.
template <class L>
SSRT_INLINE void loadSignal4(const SignalIn4& p, std::size_t offset, L out[4]) {
    if (p.f16x4) return lanes::loadF16x4<L>(p.f16x4 + offset, out);
    for (int c = 0; c < 4; ++c) out[c] = lanes::loadSignal<L>(p.ch[c], offset);
}
template <class L>
SSRT_INLINE void gatherSignal4(const SignalIn4& p, IntOf<L> index, Run run, L out[4]) {
    if (p.f16x4) return lanes::gatherF16x4<L>(p.f16x4, index, run, out);
    for (int c = 0; c < 4; ++c) out[c] = lanes::gatherSignal<L>(p.ch[c], index, run);
}
template <class L>
SSRT_INLINE void storeSignal4(const SignalOut4& p, std::size_t offset, const L x[4]) {
    if (p.f16x4) {
        const L clamped[4] = {lanes::clampedToF16(x[0]), lanes::clampedToF16(x[1]),
                              lanes::clampedToF16(x[2]), lanes::clampedToF16(x[3])};
        return lanes::storeF16x4<L>(p.f16x4 + offset, clamped);
    }
    for (int c = 0; c < 4; ++c)
        if (p.ch[c]) lanes::storeSignal(p.ch[c], offset, x[c]);
}

// Fetches ahead pixels [x0, x1) of the row at `rowOffset` of the f16 planes among `planes` (f32
// ones are left to the hardware). A kernel run tile by tile reads a few cache lines of a row of
// each plane, then jumps a row: an f16 plane's run (2 lines for a 64-pixel tile) is too short
// for the hardware's stream prefetch to follow, and each row's first load waits on memory
// (measured: the composite reading the direct pass's f16 parts took twice the time it took
// with f32 ones, the same with the row two below fetched ahead). No value depends on it.
inline void prefetchRowF16(const SignalIn* planes, int count, std::size_t rowOffset, int x0,
                           int x1) {
    for (int i = 0; i < count; ++i)
        if (planes[i].f16)
            for (int x = x0; x < x1; x += 32)  // (64-byte lines of 2-byte values)
                __builtin_prefetch(planes[i].f16 + rowOffset + std::size_t(x));
}

// The same for planes about to be written (a store's line is read first).
inline void prefetchRowF16(const SignalOut* planes, int count, std::size_t rowOffset, int x0,
                           int x1) {
    for (int i = 0; i < count; ++i)
        if (planes[i].f16)
            for (int x = x0; x < x1; x += 32)
                __builtin_prefetch(planes[i].f16 + rowOffset + std::size_t(x), 1);
}

}  // namespace ssrt::lanes
