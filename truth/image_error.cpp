#include "truth/image_error.h"

#include <cmath>
#include <stdexcept>

#include "core/rel_mse.h"

namespace ssrt {

namespace {

// A non-finite pixel's error per channel: large enough that no finite image can hide it.
constexpr double kNonFiniteError = 1e10;

void requirePlanes(const PlaneF* const image[3], const PlaneF* const reference[3]) {
    if (!image || !reference) throw std::invalid_argument("image error: null plane list");
    for (int c = 0; c < 3; ++c)
        if (!image[c] || !reference[c]) throw std::invalid_argument("image error: null plane");
    const int w = reference[0]->width(), h = reference[0]->height();
    for (int c = 0; c < 3; ++c)
        if (image[c]->width() != w || image[c]->height() != h || reference[c]->width() != w ||
            reference[c]->height() != h)
            throw std::invalid_argument("image error: planes differ in size");
}

}  // namespace

ImageError imageError(const PlaneF* const image[3], const PlaneF* const reference[3]) {
    requirePlanes(image, reference);
    const int w = reference[0]->width(), h = reference[0]->height();
    ImageError e;
    if (w == 0 || h == 0) return e;
    // Sums in double, in row order: one fixed order, so the same planes give the same bits.
    double rel = 0.0, sq = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float i[3], r[3];
            bool finite = true;
            for (int c = 0; c < 3; ++c) {
                i[c] = image[c]->at(x, y);
                r[c] = reference[c]->at(x, y);
                if (!std::isfinite(r[c]))
                    throw std::invalid_argument("image error: the reference is not finite");
                finite = finite && std::isfinite(i[c]);
            }
            if (!finite) {
                ++e.nonFinite;
                rel += 3.0 * kNonFiniteError;
                sq += 3.0 * kNonFiniteError;
                continue;
            }
            for (int c = 0; c < 3; ++c) {
                const double d = double(i[c]) - double(r[c]);
                rel += relSquaredError(double(i[c]), double(r[c]));
                sq += d * d;
            }
        }
    const double n = 3.0 * double(w) * double(h);
    e.relMse = rel / n;
    e.rmse = std::sqrt(sq / n);
    return e;
}

}  // namespace ssrt
