#include "core/plane_pool.h"

#include <algorithm>
#include <utility>

namespace ssrt {

void PlanePool::take(PlaneF& p, int width, int height) {
    if (p.width() == width && p.height() == height && !p.empty()) return;
    give(p);
    const auto same = std::find_if(free_.begin(), free_.end(), [&](const PlaneF& f) {
        return f.width() == width && f.height() == height;
    });
    if (same == free_.end()) {
        p.ensureSize(width, height);
        return;
    }
    p = std::move(*same);
    free_.erase(same);
}

void PlanePool::give(PlaneF& p) {
    if (!p.empty() && poison_) p.fill(*poison_);
    if (!p.empty()) free_.push_back(std::move(p));
    p = PlaneF();
}

void PlanePool::keepOnly(int width, int height, int halfWidth, int halfHeight) {
    std::erase_if(free_, [&](const PlaneF& f) {
        return !(f.width() == width && f.height() == height) &&
               !(f.width() == halfWidth && f.height() == halfHeight);
    });
}

std::size_t PlanePool::bytes() const {
    std::size_t n = 0;
    for (const PlaneF& p : free_) n += p.bytes();
    return n;
}

}  // namespace ssrt
