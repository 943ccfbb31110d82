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

}  // namespace ssrt::lanes
