#include "shading/shadow_bounds.h"

#include <vector>

#include "core/tiles.h"

namespace ssrt {

void buildShadowBounds(const float* map, std::size_t stride, int size, int radius, Isa isa,
                       int threads, ShadowBounds& out) {
    const int n = (size + kShadowBlock - 1) / kShadowBlock;
    out.blocks = n;
    out.block.resize(std::size_t(n) * std::size_t(n));
    const auto row = SSRT_DISPATCH(isa, boundShadowBlockRow);
    parallelFor(n, threads, [&](int by) {
        std::vector<float> work(shadowBoundsWork(size));
        row(map, stride, size, radius, by, work.data(), out.block.data() + std::size_t(by) * n);
    });
}

}  // namespace ssrt
