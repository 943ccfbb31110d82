// Lane-generic screen lookups shared by the kernels that read the screen (trace/'s resolves
// and layout reconstruction, denoise/'s REBLUR): pixel indices, nearest and bilinear reads of
// a plane at a continuous pixel position (pixel centres at +0.5, edges clamped), view-space
// points of pixels. Templates, always_inline (core/lanes.h).
#pragma once

#include <cstddef>

#include "core/lane_vec.h"

namespace ssrt::screen {

namespace ln = ssrt::lanes;
using ln::V3;

// Index of pixel (x, y) given as lane floats, each clamped into [0, w) x [0, h) first (so
// every lane, even an unused one, reads inside the plane).
template <class L>
SSRT_INLINE ln::IntOf<L> pixelIndex(L x, L y, int w, int h, std::size_t stride) {
    using I = ln::IntOf<L>;
    const I ix = ln::toIntTrunc(ln::clamp(x, L(0.0f), L(float(w - 1))));
    const I iy = ln::toIntTrunc(ln::clamp(y, L(0.0f), L(float(h - 1))));
    return iy * I(int32_t(stride)) + ix;
}

// The pixel containing continuous position (x, y), clamped to the plane.
template <class L>
SSRT_INLINE ln::IntOf<L> nearestIndex(L x, L y, int w, int h, std::size_t stride) {
    return pixelIndex(ln::floor(x), ln::floor(y), w, h, stride);
}

// Bilinear weights and clamped indices at continuous (x, y): at a pixel centre the result
// is that pixel's value exactly (a + (b - a) 0 = a).
template <class L>
struct Bilinear {
    ln::IntOf<L> i00, i10, i01, i11;
    L tx, ty;
};

template <class L>
SSRT_INLINE Bilinear<L> bilinearAt(L x, L y, int w, int h, std::size_t stride) {
    const L sx = x - L(0.5f), sy = y - L(0.5f);
    const L x0 = ln::floor(sx), y0 = ln::floor(sy);
    Bilinear<L> b;
    b.tx = ln::saturate(sx - x0);
    b.ty = ln::saturate(sy - y0);
    b.i00 = pixelIndex(x0, y0, w, h, stride);
    b.i10 = pixelIndex(x0 + L(1.0f), y0, w, h, stride);
    b.i01 = pixelIndex(x0, y0 + L(1.0f), w, h, stride);
    b.i11 = pixelIndex(x0 + L(1.0f), y0 + L(1.0f), w, h, stride);
    return b;
}

template <class L>
SSRT_INLINE L sample(const float* plane, const Bilinear<L>& b) {
    const L a = ln::gather(plane, b.i00), c = ln::gather(plane, b.i10);
    const L d = ln::gather(plane, b.i01), e = ln::gather(plane, b.i11);
    const L top = a + (c - a) * b.tx, bottom = d + (e - d) * b.tx;
    return top + (bottom - top) * b.ty;
}

// The view-space point at continuous pixel position (x, y) and view depth z (core/camera.h).
template <class L>
SSRT_INLINE V3<L> viewPoint(L x, L y, L z, int w, int h, float tanHalfX, float tanHalfY) {
    const L ndcX = x * L(2.0f / float(w)) - L(1.0f);
    const L ndcY = L(1.0f) - y * L(2.0f / float(h));
    return {ndcX * L(tanHalfX) * z, ndcY * L(tanHalfY) * z, L(0.0f) - z};
}

// World to view with the transpose of a column-major rotation r (view to world).
template <class L>
SSRT_INLINE V3<L> worldToView(const float* r, V3<L> d) {
    return {(L(r[0]) * d.x + L(r[1]) * d.y) + L(r[2]) * d.z,
            (L(r[3]) * d.x + L(r[4]) * d.y) + L(r[5]) * d.z,
            (L(r[6]) * d.x + L(r[7]) * d.y) + L(r[8]) * d.z};
}

// View to world with the column-major rotation r.
template <class L>
SSRT_INLINE V3<L> viewToWorld(const float* r, V3<L> d) {
    return {(L(r[0]) * d.x + L(r[3]) * d.y) + L(r[6]) * d.z,
            (L(r[1]) * d.x + L(r[4]) * d.y) + L(r[7]) * d.z,
            (L(r[2]) * d.x + L(r[5]) * d.y) + L(r[8]) * d.z};
}

}  // namespace ssrt::screen
