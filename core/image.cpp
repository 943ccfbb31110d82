#include "core/image.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>

#include "core/plane_memory.h"

namespace ssrt {

namespace {

// Large planes start at different cache sets. Within a huge page (core/plane_memory.h) the
// virtual offset is the physical one, so planes at the same offset modulo the cache's set
// span (64 KiB for a 1 MiB 16-way L2) put a pixel's values into one set: a pass that reads a
// dozen planes at one pixel evicts its own lines (measured: a sequence's frame 226 -> 263
// ms, SSR's march 27 -> 42 ms). With 4 KiB pages the physical pages scatter them. So each
// large plane starts a different number of pages and cache lines into its block, cycling
// through kStaggers offsets. No pixel depends on it.
constexpr std::size_t kLargePlane = std::size_t(2) << 20;
constexpr std::size_t kStagger = 4096 + kRowAlignment, kStaggers = 16;
std::atomic<std::size_t> nextStagger{0};

void* allocatePlane(std::size_t bytes) {
    const std::size_t stagger =
        bytes >= kLargePlane ? nextStagger.fetch_add(1) % kStaggers * kStagger : 0;
    return allocatePlaneMemory(bytes, stagger);
}

}  // namespace

template <class T>
void Plane<T>::Free::operator()(T* p) const {
    freePlaneMemory(p);
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
std::size_t Plane<T>::blockBytes(std::size_t stride, int height) {
    const std::size_t slack = sizeof(T) < 4 ? kRowAlignment : 0;
    return std::max<std::size_t>(stride * std::size_t(height) * sizeof(T), kRowAlignment) + slack;
}

template <class T>
void Plane<T>::zeroPadding() {
    // Row padding is zeroed: kernels read whole lane groups there and must see defined values.
    for (int y = 0; y < height_; ++y) std::fill(row(y) + width_, row(y) + stride_, T{});
}

template <class T>
Plane<T>::Plane(int width, int height, Uninitialized) : width_(width), height_(height) {
    if (width < 0 || height < 0) throw std::invalid_argument("plane size must not be negative");
    constexpr std::size_t perLine = kRowElements;
    stride_ = (std::size_t(width) + perLine - 1) / perLine * perLine;
    data_.reset(static_cast<T*>(allocatePlane(blockBytes(stride_, height))));
    zeroPadding();
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
uint64_t hashPlane(const PlaneU64& plane, uint64_t seed) { return fnv1a(plane, seed); }
uint64_t hashPlane(const PlaneU32& plane, uint64_t seed) { return fnv1a(plane, seed); }
uint64_t hashPlane(const PlaneU16& plane, uint64_t seed) { return fnv1a(plane, seed); }
uint64_t hashPlane(const PlaneU8& plane, uint64_t seed) { return fnv1a(plane, seed); }

template class Plane<float>;
template class Plane<uint64_t>;
template class Plane<uint32_t>;
template class Plane<uint16_t>;
template class Plane<uint8_t>;

}  // namespace ssrt
