// Bit-exact comparison of two planes (visible pixels only; row padding ignored), for the
// tests that hold ISAs, thread counts and code paths to the same bits.
#pragma once

#include <cstddef>
#include <cstring>

#include "core/image.h"

namespace ssrt::test {

template <class T>
inline bool sameBits(const Plane<T>& a, const Plane<T>& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        if (std::memcmp(a.row(y), b.row(y), sizeof(T) * std::size_t(a.width())) != 0) return false;
    return true;
}

}  // namespace ssrt::test
