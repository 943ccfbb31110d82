// The one plane check (core/plane_check.h): a missing, empty or mis-sized plane is an error
// naming the pass and the plane; a good one gives its first row and the shared stride.
#include "core/plane_check.h"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

using namespace ssrt;

namespace {

std::string messageOf(PlaneCheck& need, const PlaneF* p) {
    try {
        need(p, "viewZ");
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("plane check: missing, empty and mis-sized planes are named errors") {
    PlaneCheck need("denoise", 40, 24);
    CHECK(need.stride() == 0);
    const PlaneF empty, wide(41, 24), tall(40, 25);
    CHECK(messageOf(need, nullptr) == "denoise: viewZ is missing");
    CHECK(messageOf(need, &empty) == "denoise: viewZ is missing");
    CHECK(messageOf(need, &wide) == "denoise: viewZ is 41x24, not 40x24");
    CHECK(messageOf(need, &tall) == "denoise: viewZ is 40x25, not 40x24");
    CHECK(need.stride() == 0);
}

TEST_CASE("plane check: a good plane gives its rows and the stride") {
    PlaneCheck need("composite", 40, 24);
    PlaneF in(40, 24, 1.0f), out(40, 24);
    CHECK(need(in, "in") == in.row(0));
    CHECK(need.output(out, "out") == out.row(0));
    CHECK(need.stride() == in.stride());
    CHECK(need.stride() >= 40);
}
