#include "shading/shadow_bounds.h"

#include <algorithm>

#include "core/tiles.h"

namespace ssrt {

namespace {

// min and max where a NaN wins (a NaN texel must leave its blocks undecided: the bounds'
// proof in shading/direct_lanes.h), written as selects that the compiler vectorizes.
inline float lower(float a, float b) { return (b < a || b != b) ? b : a; }
inline float higher(float a, float b) { return (b > a || b != b) ? b : a; }

// The texels [first, last] whose taps may be read from block `b`: widened by r, clipped.
struct Span {
    int first, last;
};
Span widened(int b, int r, int size) {
    return {std::max(b * kShadowBlock - r, 0), std::min((b + 1) * kShadowBlock - 1 + r, size - 1)};
}

}  // namespace

void buildShadowBounds(const float* map, std::size_t stride, int size, int radius, int threads,
                       ShadowBounds& out) {
    const int n = (size + kShadowBlock - 1) / kShadowBlock;
    out.blocks = n;
    out.loHi.resize(2 * std::size_t(n) * std::size_t(n));
    parallelFor(n, threads, [&](int by) {
        // Down the block row's widened rows, per column; then across each block's columns.
        const Span rows = widened(by, radius, size);
        const float* first = map + std::size_t(rows.first) * stride;
        std::vector<float> lo(first, first + size), hi = lo;
        for (int y = rows.first + 1; y <= rows.last; ++y) {
            const float* row = map + std::size_t(y) * stride;
            for (int x = 0; x < size; ++x) {
                lo[x] = lower(lo[x], row[x]);
                hi[x] = higher(hi[x], row[x]);
            }
        }
        float* dst = out.loHi.data() + 2 * std::size_t(by) * std::size_t(n);
        for (int bx = 0; bx < n; ++bx) {
            const Span cols = widened(bx, radius, size);
            float l = lo[cols.first], h = hi[cols.first];
            for (int x = cols.first + 1; x <= cols.last; ++x) {
                l = lower(l, lo[x]);
                h = higher(h, hi[x]);
            }
            dst[2 * bx] = l;
            dst[2 * bx + 1] = h;
        }
    });
}

}  // namespace ssrt
