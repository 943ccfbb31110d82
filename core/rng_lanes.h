// The counter-based RNG (core/rng.h) across lanes: lane i draws for pixel `pixel + i`, with
// the bits randomFloat gives it (integer multiply, xor and shifts only, so every ISA agrees).
// A lane group's numbers then cost a few vector instructions instead of a scalar hash per lane.
#pragma once

#include <cstdint>

#include "core/lanes.h"
#include "core/rng.h"

namespace ssrt::lanes {

template <class U>
SSRT_INLINE U pcgHashLanes(U v) {
    const U state = v * U(747796405u) + U(2891336453u);
    const U word = ((state >> ((state >> 28) + U(4u))) ^ state) * U(277803737u);
    return (word >> 22) ^ word;
}

// randomFloat(pixel + i, frame, sample, dim) in lane i.
template <class L>
SSRT_INLINE L randomFloats(uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t dim) {
    if constexpr (std::is_same_v<L, float>) {
        return randomFloat(pixel, frame, sample, dim);
    } else {
        using U = xsimd::batch<uint32_t, typename L::arch_type>;
        alignas(64) uint32_t iota[U::size];
        for (std::size_t i = 0; i < U::size; ++i) iota[i] = uint32_t(i);
        U h = pcgHashLanes(U(pixel) + U::load_aligned(iota));
        h = pcgHashLanes(h ^ U(frame * 0x9e3779b9u));
        h = pcgHashLanes(h ^ U(sample * 0x85ebca6bu));
        h = pcgHashLanes(h ^ U(dim * 0xc2b2ae35u));
        // toUnitFloat: the top 24 bits, exact as an int32 converted to float.
        const auto top = xsimd::bitwise_cast<xsimd::batch<int32_t, typename L::arch_type>>(h >> 8);
        return toFloat(top) * L(1.0f / 16777216.0f);
    }
}

}  // namespace ssrt::lanes
