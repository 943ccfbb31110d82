#include "shading/shadow_bounds.h"

#include <memory>

#include "core/tiles.h"

namespace ssrt {

void buildShadowBounds(const float* map, std::size_t stride, int size, int radius, Isa isa,
                       int threads, ShadowBounds& out) {
    const int n = (size + kShadowBlock - 1) / kShadowBlock;
    out.blocks = n;
    out.block.resize(std::size_t(n) * std::size_t(n));
    const auto row = SSRT_DISPATCH(isa, boundShadowBlockRow);
    parallelFor(n, threads, [&](int by) {
        // (uninitialised: the kernel writes each of its floats before it reads it)
        const auto work = std::make_unique_for_overwrite<float[]>(shadowBoundsWork(size));
        row(map, stride, size, radius, by, work.get(), out.block.data() + std::size_t(by) * n);
    });
}

}  // namespace ssrt
