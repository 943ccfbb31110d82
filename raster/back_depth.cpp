#include "raster/back_depth.h"

#include <algorithm>
#include <stdexcept>

#include "core/tiles.h"

namespace ssrt {

namespace {

// The instance holding global triangle `id`, remembered across calls for the run of pixels
// a triangle covers.
class InstanceOf {
public:
    explicit InstanceOf(const std::vector<uint32_t>& offset) : offset_(offset) {}
    std::size_t operator()(uint32_t id) {
        if (id < lo_ || id >= hi_) {
            const auto it = std::upper_bound(offset_.begin(), offset_.end(), id);
            instance_ = std::size_t(it - offset_.begin()) - 1;
            lo_ = offset_[instance_];
            hi_ = it == offset_.end() ? UINT32_MAX : *it;
        }
        return instance_;
    }

private:
    const std::vector<uint32_t>& offset_;
    std::size_t instance_ = 0;
    uint32_t lo_ = 1, hi_ = 0;  // empty: the first call looks up
};

}  // namespace

void resolveBackDepth(const VisibilityBuffer& front, const VisibilityBuffer& back,
                      const std::vector<uint32_t>& triangleOffset, PlaneF& backZ, int threads) {
    const int w = front.depth.width(), h = front.depth.height();
    if (back.depth.width() != w || back.depth.height() != h || front.ids.width() != w ||
        back.ids.width() != w || front.ids.height() != h || back.ids.height() != h)
        throw std::invalid_argument("resolveBackDepth: buffers of different sizes or no ids");
    backZ.ensureSize(w, h);
    parallelFor(h, threads, [&](int y) {
        InstanceOf frontInstance(triangleOffset), backInstance(triangleOffset);
        const float *fk = front.depth.row(y), *bk = back.depth.row(y);
        const uint32_t *fi = front.ids.row(y), *bi = back.ids.row(y);
        float* out = backZ.row(y);
        for (int x = 0; x < w; ++x) {
            // Behind (a smaller key is farther), of the same instance, another triangle.
            const bool known = fi[x] != kNoPrimitive && bi[x] != kNoPrimitive && bi[x] != fi[x] &&
                               bk[x] > 0.0f && bk[x] < fk[x] &&
                               frontInstance(fi[x]) == backInstance(bi[x]);
            out[x] = known ? 1.0f / bk[x] : 0.0f;
        }
    });
}

}  // namespace ssrt
