// A plane as a pass hands it to a kernel: its first row, its row stride, its size and its
// name for messages. Plain data only (it crosses into code compiled per ISA), made from a
// plane by viewOf and checked where a pass takes its views, in one call: requireViews.
//
// Planes of one size share one stride in elements whatever their format (core/image.h), so
// views checked to one size are addressed with one offset per pixel, whichever view it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string_view>

#include "core/float_planes.h"
#include "core/image.h"

namespace ssrt {

template <class T>
struct PlaneView {
    T* data = nullptr;  // row 0; null: absent
    std::size_t stride = 0;
    int width = 0, height = 0;
    std::string_view name;  // the plane's name in messages ("viewZ", "resolve.R", ...)

    explicit operator bool() const { return data != nullptr; }
    T* row(int y) const { return data + std::size_t(y) * stride; }
    T& at(int x, int y) const { return row(y)[x]; }
};

using ViewF = PlaneView<const float>;
using OutF = PlaneView<float>;
using ViewU16 = PlaneView<const uint16_t>;
using OutU16 = PlaneView<uint16_t>;
using ViewU32 = PlaneView<const uint32_t>;

// The view of `p` (an empty plane gives an absent view that keeps its name).
template <class T>
PlaneView<const T> viewOf(const Plane<T>& p, std::string_view name) {
    if (p.empty()) return {nullptr, 0, 0, 0, name};
    return {p.row(0), p.stride(), p.width(), p.height(), name};
}
template <class T>
PlaneView<T> outputOf(Plane<T>& p, std::string_view name) {
    if (p.empty()) return {nullptr, 0, 0, 0, name};
    return {p.row(0), p.stride(), p.width(), p.height(), name};
}

// A view of float values stored as f32 or as f16 (core/float_planes.h), or none: the direct
// pass's parts and SSGI's hit light are f16 in a frame, f32 where a test or the truth makes
// them.
struct FloatView {
    ViewF f32{};
    ViewU16 f16{};
    FloatView() = default;
    FloatView(ViewF v) : f32(v) {}
    FloatView(ViewU16 v) : f16(v) {}
    explicit operator bool() const { return f32 || f16; }
    // Row 0 as a kernel reads it.
    SignalIn in() const { return f16 ? SignalIn(f16.data) : SignalIn(f32.data); }
    std::string_view name() const { return f16 || !f16.name.empty() ? f16.name : f32.name; }
};

// One view as requireViews sees it, whatever its element type.
struct ViewShape {
    const void* data;
    std::size_t stride;
    int width, height;
    std::string_view name;
    template <class T>
    ViewShape(const PlaneView<T>& v)
        : data(v.data), stride(v.stride), width(v.width), height(v.height), name(v.name) {}
    // (an absent float view by the name it was made with)
    ViewShape(const FloatView& v)
        : ViewShape(v.f16 || !v.f16.name.empty() ? ViewShape(v.f16) : ViewShape(v.f32)) {}
};

// The one check of the views a pass is handed: each present and of width x height; else
// std::invalid_argument naming `pass` and the view ("resolveSsr: normal.X is missing",
// "...: viewZ is 320x180, not 640x360"). Returns their one stride (0 for no views).
std::size_t requireViews(std::string_view pass, int width, int height, const ViewShape* views,
                         std::size_t count);
inline std::size_t requireViews(std::string_view pass, int width, int height,
                                std::initializer_list<ViewShape> views) {
    return requireViews(pass, width, height, views.begin(), views.size());
}

}  // namespace ssrt
