// Views of planes (core/plane_view.h): a view keeps its plane's rows, stride, size and name;
// requireViews is the one check of a pass's views, naming the pass and the view.
#include "core/plane_view.h"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

using namespace ssrt;

namespace {

std::string messageOf(std::initializer_list<ViewShape> views) {
    try {
        requireViews("resolveSsr", 40, 24, views);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("plane views: a view keeps its plane's rows, stride, size and name") {
    PlaneF p(40, 24, 2.0f);
    p.at(3, 5) = 7.0f;
    const ViewF v = viewOf(p, "viewZ");
    CHECK(v.data == p.row(0));
    CHECK(v.stride == p.stride());
    CHECK(v.width == 40);
    CHECK(v.height == 24);
    CHECK(v.name == "viewZ");
    CHECK(v.at(3, 5) == 7.0f);
    const PlaneF empty;
    const ViewF none = viewOf(empty, "normal.X");
    CHECK_FALSE(none);
    CHECK(none.name == "normal.X");
    OutF out = outputOf(p, "out");
    out.at(1, 1) = 3.0f;
    CHECK(p.at(1, 1) == 3.0f);
}

TEST_CASE("plane views: requireViews names a missing or mis-sized view, else gives the stride") {
    const PlaneF good(40, 24), wide(41, 24), tall(40, 25), empty;
    const PlaneU16 half(40, 24);
    CHECK(messageOf({viewOf(good, "viewZ"), viewOf(empty, "normal.X")}) ==
          "resolveSsr: normal.X is missing");
    CHECK(messageOf({viewOf(wide, "roughness")}) == "resolveSsr: roughness is 41x24, not 40x24");
    CHECK(messageOf({viewOf(tall, "motion.X")}) == "resolveSsr: motion.X is 40x25, not 40x24");
    CHECK(messageOf({viewOf(good, "viewZ"), viewOf(half, "hitLight.R")}).empty());
    CHECK(requireViews("p", 40, 24, {viewOf(good, "a"), viewOf(half, "b")}) == good.stride());
    CHECK(requireViews("p", 40, 24, {}) == 0);
}

TEST_CASE("plane views: a float view reads either format and is checked as its plane") {
    const PlaneF f32(40, 24, 1.5f);
    const PlaneU16 f16(40, 24), small(20, 12);
    const FloatView a = viewOf(f32, "direct.R"), b = viewOf(f16, "direct.G"), none;
    CHECK(a.in().f32 == f32.row(0));
    CHECK(b.in().f16 == f16.row(0));
    CHECK(b.name() == "direct.G");
    CHECK_FALSE(none);
    CHECK(messageOf({a, b}).empty());
    CHECK(messageOf({FloatView(viewOf(small, "hitLight.B"))}) ==
          "resolveSsr: hitLight.B is 20x12, not 40x24");
}
