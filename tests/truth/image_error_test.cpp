// imageError against hand-computed values: the relMSE and RMSE conventions, a non-finite
// pixel counted, and the refusals.
#include "truth/image_error.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

using namespace ssrt;

namespace {

// Two pixels, RGB each.
struct Rgb2 {
    PlaneF p[3];
    Rgb2(const float (&a)[3], const float (&b)[3]) {
        for (int c = 0; c < 3; ++c) {
            p[c] = PlaneF(2, 1);
            p[c].at(0, 0) = a[c];
            p[c].at(1, 0) = b[c];
        }
    }
    const PlaneF* ptr[3] = {&p[0], &p[1], &p[2]};
};

}  // namespace

TEST_CASE("image error: relMSE and RMSE of a hand-computed pair") {
    const Rgb2 image({1.0f, 2.0f, 3.0f}, {0.0f, 0.0f, 0.0f});
    const Rgb2 ref({1.0f, 1.0f, 1.0f}, {0.1f, 0.0f, 0.0f});
    const ImageError e = imageError(image.ptr, ref.ptr);
    // Differences 0, 1, 2 over R = 1 and -0.1, 0, 0 over R = 0.1, 0, 0.
    const double r01 = double(0.1f);
    const double rel = (1.0 / 1.01 + 4.0 / 1.01 + r01 * r01 / (r01 * r01 + 0.01)) / 6.0;
    CHECK(e.relMse == doctest::Approx(rel).epsilon(1e-12));
    CHECK(e.rmse == doctest::Approx(std::sqrt((1.0 + 4.0 + r01 * r01) / 6.0)).epsilon(1e-12));
    CHECK(e.nonFinite == 0);
    // An image against itself: no error.
    const ImageError same = imageError(ref.ptr, ref.ptr);
    CHECK(same.relMse == 0.0);
    CHECK(same.rmse == 0.0);
}

TEST_CASE("image error: a NaN or infinite pixel is counted and cannot hide") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Rgb2 image({1.0f, 2.0f, 3.0f}, {0.0f, nan, 0.0f});
    const Rgb2 ref({1.0f, 1.0f, 1.0f}, {0.1f, 0.0f, 0.0f});
    const ImageError e = imageError(image.ptr, ref.ptr);
    CHECK(e.nonFinite == 1);
    // The pixel's three channels count 1e10 each.
    CHECK(e.relMse == doctest::Approx((5.0 / 1.01 + 3e10) / 6.0).epsilon(1e-12));
    CHECK(e.rmse == doctest::Approx(std::sqrt((5.0 + 3e10) / 6.0)).epsilon(1e-12));
    const Rgb2 inf({std::numeric_limits<float>::infinity(), 1.0f, 1.0f}, {0.1f, 0.0f, 0.0f});
    CHECK(imageError(inf.ptr, ref.ptr).nonFinite == 1);
}

TEST_CASE("image error: refuses planes of another size, null planes and a non-finite reference") {
    const Rgb2 a({1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f});
    PlaneF wide[3] = {PlaneF(3, 1), PlaneF(3, 1), PlaneF(3, 1)};
    const PlaneF* widePtr[3] = {&wide[0], &wide[1], &wide[2]};
    CHECK_THROWS_AS(imageError(a.ptr, widePtr), std::invalid_argument);
    CHECK_THROWS_AS(imageError(widePtr, a.ptr), std::invalid_argument);
    const PlaneF* oneNull[3] = {&wide[0], nullptr, &wide[2]};
    CHECK_THROWS_AS(imageError(oneNull, widePtr), std::invalid_argument);
    const Rgb2 badRef({1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f}, {1.0f, 1.0f, 1.0f});
    CHECK_THROWS_AS(imageError(a.ptr, badRef.ptr), std::invalid_argument);
}
