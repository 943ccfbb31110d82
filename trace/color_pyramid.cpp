#include "trace/color_pyramid.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "core/tiles.h"

namespace ssrt {

void buildColorPyramid(const PlaneF* const rgb[3], ColorPyramid& pyramid, int threads) {
    for (int c = 0; c < 3; ++c)
        if (!rgb[c] || rgb[c]->empty() || rgb[c]->width() != rgb[0]->width() ||
            rgb[c]->height() != rgb[0]->height())
            throw std::invalid_argument("buildColorPyramid: three non-empty planes of one size");
    const int w0 = rgb[0]->width(), h0 = rgb[0]->height();
    // Level sizes down to 1 x 1.
    int count = 1;
    for (int w = w0, h = h0; (w > 1 || h > 1) && count < ColorPyramid::kMaxLevels; ++count) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
    }
    pyramid.levels.resize(std::size_t(count));
    int w = w0, h = h0;
    for (int l = 0; l < count; ++l) {
        for (PlaneF& p : pyramid.levels[std::size_t(l)]) p.ensureSize(w, h);
        w = (w + 1) / 2;
        h = (h + 1) / 2;
    }
    // Level 0: a copy.
    parallelFor(h0, threads, [&](int y) {
        for (int c = 0; c < 3; ++c)
            std::memcpy(pyramid.levels[0][c].row(y), rgb[c]->row(y),
                        sizeof(float) * std::size_t(w0));
    });
    // Each next level: the 2x2 box of the one before, edges clamped.
    for (int l = 1; l < count; ++l) {
        const auto& src = pyramid.levels[std::size_t(l - 1)];
        auto& dst = pyramid.levels[std::size_t(l)];
        const int sw = src[0].width(), sh = src[0].height();
        const int dw = dst[0].width(), dh = dst[0].height();
        parallelFor(dh, threads, [&](int y) {
            const int y0 = 2 * y, y1 = std::min(2 * y + 1, sh - 1);
            for (int c = 0; c < 3; ++c) {
                const float* r0 = src[c].row(y0);
                const float* r1 = src[c].row(y1);
                float* out = dst[c].row(y);
                for (int x = 0; x < dw; ++x) {
                    const int x0 = 2 * x, x1 = std::min(2 * x + 1, sw - 1);
                    out[x] = ((r0[x0] + r0[x1]) + (r1[x0] + r1[x1])) * 0.25f;
                }
            }
        });
    }
}

}  // namespace ssrt
