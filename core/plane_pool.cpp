#include "core/plane_pool.h"

#include <algorithm>
#include <utility>

namespace ssrt {

namespace {

template <class T>
bool sized(const Plane<T>& p, int width, int height) {
    return p.width() == width && p.height() == height;
}

}  // namespace

template <class T, class U>
void PlanePool::takeFrom(Plane<T>& p, std::vector<Plane<T>>& same, std::vector<Plane<U>>& other,
                         int width, int height) {
    if (sized(p, width, height) && !p.empty()) return;
    giveTo(p, same);
    const auto it = std::find_if(same.begin(), same.end(),
                                 [&](const Plane<T>& f) { return sized(f, width, height); });
    if (it != same.end()) {
        p = std::move(*it);
        same.erase(it);
        return;
    }
    // None of this type: a plane of the other type of this size whose block holds it lends its
    // block (an f16 plane in an f32 plane's; the block keeps its size and goes back to an f32
    // plane later), so blocks change hands and never return to the allocator: a sequence
    // allocates in its first frame only.
    auto lender = other.end();
    for (auto it = other.begin(); it != other.end(); ++it)
        if (sized(*it, width, height) &&
            (lender == other.end() || it->capacity() > lender->capacity()))
            lender = it;
    if (lender != other.end()) {
        p = Plane<T>::reuse(*lender, width, height);  // (a new plane where the block is too small)
        if (lender->empty()) other.erase(lender);
        return;
    }
    p.ensureSize(width, height);
}

template <class T>
void PlanePool::giveTo(Plane<T>& p, std::vector<Plane<T>>& free) {
    if (!p.empty()) free.push_back(std::move(p));
    p = Plane<T>();
}

void PlanePool::take(PlaneF& p, int width, int height) { takeFrom(p, f32_, f16_, width, height); }
void PlanePool::take(PlaneU16& p, int width, int height) { takeFrom(p, f16_, f32_, width, height); }
void PlanePool::give(PlaneF& p) { giveTo(p, f32_); }
void PlanePool::give(PlaneU16& p) { giveTo(p, f16_); }

void PlanePool::keepOnly(int width, int height, int halfWidth, int halfHeight) {
    const auto drop = [&](const auto& f) {
        return !sized(f, width, height) && !sized(f, halfWidth, halfHeight);
    };
    std::erase_if(f32_, drop);
    std::erase_if(f16_, drop);
}

// (Their blocks' bytes: an f16 plane in an f32 plane's block holds all of it.)
std::size_t PlanePool::bytes() const {
    std::size_t n = 0;
    for (const PlaneF& p : f32_) n += p.capacity();
    for (const PlaneU16& p : f16_) n += p.capacity();
    return n;
}

}  // namespace ssrt
