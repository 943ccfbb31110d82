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
    // None of this type: the other type's planes of this size make room for it (their blocks,
    // freed together, merge; the allocation below reuses them).
    std::erase_if(other, [&](const Plane<U>& f) { return sized(f, width, height); });
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

std::size_t PlanePool::bytes() const {
    std::size_t n = 0;
    for (const PlaneF& p : f32_) n += p.bytes();
    for (const PlaneU16& p : f16_) n += p.bytes();
    return n;
}

}  // namespace ssrt
