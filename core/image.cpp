#include "core/image.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>

namespace ssrt {

namespace {

// Planes of 2 MiB or more ask the kernel for transparent huge pages (Linux's "madvise" mode,
// Debian's default) over the 2 MiB-aligned part of their memory: their first touch then
// faults (and the kernel zeroes) 2 MiB at a time instead of 4 KiB, the cost that dominated a
// single frame's passes. The planes keep malloc's placement, not a 2 MiB-aligned start: with
// every plane at the same offset modulo the cache's set span, a pass that reads a dozen planes
// at one pixel evicts its own lines (measured: a sequence's frame 6-20 % slower). A kernel
// without huge pages ignores the advice; no pixel depends on it.
constexpr std::size_t kHugePage = std::size_t(2) << 20;

void* allocatePlane(std::size_t bytes) {
    void* p = std::aligned_alloc(kRowAlignment, bytes);
    if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    if (bytes >= kHugePage) {
        const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
        const auto end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHugePage - 1);
        if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
    }
#endif
    return p;
}

}  // namespace

template <class T>
void Plane<T>::Free::operator()(T* p) const {
    std::free(p);
}

template <class T>
Plane<T>::Plane(int width, int height, T fill) : Plane(width, height, kUninitialized) {
    for (int y = 0; y < height; ++y) std::fill_n(row(y), width, fill);
}

template <class T>
void Plane<T>::ensureSize(int width, int height) {
    if (width != width_ || height != height_ || !data_)
        *this = Plane(width, height, kUninitialized);
}

template <class T>
Plane<T>::Plane(int width, int height, Uninitialized) : width_(width), height_(height) {
    if (width < 0 || height < 0) throw std::invalid_argument("plane size must not be negative");
    constexpr std::size_t perLine = kRowAlignment / sizeof(T);
    stride_ = (std::size_t(width) + perLine - 1) / perLine * perLine;
    const std::size_t bytes = std::max<std::size_t>(stride_ * height * sizeof(T), kRowAlignment);
    data_.reset(static_cast<T*>(allocatePlane(bytes)));
    // Row padding is zeroed: kernels read whole lane groups there and must see defined values.
    for (int y = 0; y < height; ++y) std::fill(row(y) + width, row(y) + stride_, T{});
}

template <class T>
void Plane<T>::fill(T value) {
    for (int y = 0; y < height_; ++y) std::fill_n(row(y), width_, value);
}

template <class T>
Plane<T> Plane<T>::clone() const {
    Plane out(width_, height_);
    if (!empty()) std::memcpy(out.data_.get(), data_.get(), stride_ * height_ * sizeof(T));
    return out;
}

template <class T>
static uint64_t fnv1a(const Plane<T>& plane, uint64_t h) {
    for (int y = 0; y < plane.height(); ++y) {
        const auto* bytes = reinterpret_cast<const unsigned char*>(plane.row(y));
        for (std::size_t i = 0; i < std::size_t(plane.width()) * sizeof(T); ++i) {
            h ^= bytes[i];
            h *= 0x100000001b3ull;
        }
    }
    return h;
}

uint64_t hashPlane(const PlaneF& plane, uint64_t seed) { return fnv1a(plane, seed); }
uint64_t hashPlane(const PlaneU32& plane, uint64_t seed) { return fnv1a(plane, seed); }

template class Plane<float>;
template class Plane<uint32_t>;

}  // namespace ssrt
