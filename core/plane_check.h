// The one check of the planes a pass reads and writes: each present and of the size the pass
// runs at. Every pass checks its planes through it before a kernel runs, so a wrong plane is
// a clear std::invalid_argument naming the pass and the plane, never a read out of bounds.
// Planes of one size have one row stride (core/image.h pads every row alike), so a kernel
// walks all the planes it was given with one offset per pixel: stride().
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "core/float_planes.h"
#include "core/image.h"

namespace ssrt {

class PlaneCheck {
public:
    // `pass` names the caller in the messages ("denoise", "marchRays", ...).
    PlaneCheck(std::string_view pass, int width, int height)
        : pass_(pass), width_(width), height_(height) {}

    // The plane's first row; throws std::invalid_argument when it is null or empty, or of
    // another size.
    const float* operator()(const PlaneF* p, std::string_view what) {
        check(p, what);
        return p->row(0);
    }
    const float* operator()(const PlaneF& p, std::string_view what) { return (*this)(&p, what); }
    const uint16_t* operator()(const PlaneU16* p, std::string_view what) {
        check(p, what);
        return p->row(0);
    }
    // A plane of either format (FloatPlane): its first row as a kernel reads it.
    SignalIn operator()(FloatPlane p, std::string_view what) {
        if (p.f16) return (*this)(p.f16, what);
        return (*this)(p.f32, what);
    }
    // An output plane: the same check, a writable row.
    float* output(PlaneF& p, std::string_view what) {
        check(&p, what);
        return p.row(0);
    }
    uint16_t* output(PlaneU16& p, std::string_view what) {
        check(&p, what);
        return p.row(0);
    }
    // The row stride of the planes checked (0 before the first).
    std::size_t stride() const { return stride_; }

private:
    template <class T>
    void check(const Plane<T>* p, std::string_view what);

    std::string pass_;
    int width_, height_;
    std::size_t stride_ = 0;
};

}  // namespace ssrt
