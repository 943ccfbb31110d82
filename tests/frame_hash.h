// One hash over every layer of a frame, in order, names included: what the golden-hash and
// bit-identity tests compare.
#pragma once

#include <cstdint>

#include "renderer/frame.h"

namespace ssrt::test {

inline uint64_t frameHash(const Frame& f) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const PlaneRef& p : f.layers()) {
        for (char c : p.name) h = (h ^ uint8_t(c)) * 0x100000001b3ull;
        h = hashPlane(*p.plane, h);
    }
    return h;
}

}  // namespace ssrt::test
