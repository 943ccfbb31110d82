// Counter-based random numbers: a hash of (pixel, frame, sample, dimension), never a
// generator with state, so a value depends only on where and what it is for.
#pragma once

#include <cstdint>

namespace ssrt {

// PCG-style output permutation (O'Neill 2014), as used for hashing by Jarzynski and
// Olano 2020, "Hash Functions for GPU Rendering".
constexpr uint32_t pcgHash(uint32_t v) {
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Hash of the four counters, each stage mixing the previous result with the next counter.
constexpr uint32_t hashCounters(uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t dim) {
    uint32_t h = pcgHash(pixel);
    h = pcgHash(h ^ (frame * 0x9e3779b9u));
    h = pcgHash(h ^ (sample * 0x85ebca6bu));
    return pcgHash(h ^ (dim * 0xc2b2ae35u));
}

// Uniform float in [0, 1): the top 24 bits, exactly representable.
constexpr float toUnitFloat(uint32_t bits) { return float(bits >> 8) * (1.0f / 16777216.0f); }

constexpr float randomFloat(uint32_t pixel, uint32_t frame, uint32_t sample, uint32_t dim) {
    return toUnitFloat(hashCounters(pixel, frame, sample, dim));
}

}  // namespace ssrt
