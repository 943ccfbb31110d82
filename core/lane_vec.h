// Small vectors over a lane type, for kernels (GLM stays in set-up code: its inline
// functions must not be compiled with one ISA's flags and shared with another's).
#pragma once

#include "core/lanes.h"

namespace ssrt::lanes {

template <class L>
struct V3 {
    L x, y, z;
};

template <class L>
SSRT_INLINE V3<L> operator+(V3<L> a, V3<L> b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class L>
SSRT_INLINE V3<L> operator-(V3<L> a, V3<L> b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class L>
SSRT_INLINE V3<L> operator*(V3<L> a, L s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <class L>
SSRT_INLINE V3<L> operator*(V3<L> a, V3<L> b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <class L>
SSRT_INLINE L dot(V3<L> a, V3<L> b) {
    return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
template <class L>
SSRT_INLINE V3<L> cross(V3<L> a, V3<L> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class L>
SSRT_INLINE V3<L> splat(float x, float y, float z) {
    return {L(x), L(y), L(z)};
}
template <class L>
SSRT_INLINE V3<L> select(MaskOf<L> m, V3<L> a, V3<L> b) {
    return {lanes::select(m, a.x, b.x), lanes::select(m, a.y, b.y), lanes::select(m, a.z, b.z)};
}

// Unit vector; a zero vector stays zero instead of becoming NaN.
template <class L>
SSRT_INLINE V3<L> normalize(V3<L> v) {
    const L len2 = lanes::dot(v, v);
    const L inv = L(1.0f) / lanes::sqrt(lanes::select(len2 > L(0.0f), len2, L(1.0f)));
    return v * inv;
}

}  // namespace ssrt::lanes
