// The plane pool (core/plane_pool.h): a plane already of its size is kept, another is
// allocated; a plane given back is freed to the planes' range, whose pages the next plane of any
// size or element type takes; poisoned planes come NaN-filled.
#include "core/plane_pool.h"

#include <doctest/doctest.h>

#include <cmath>

#include "core/pixel_formats.h"
#include "core/plane_memory.h"

using namespace ssrt;

TEST_CASE("plane pool: planes kept at their size, freed when given back") {
    PlanePool pool;
    PlaneF a(40, 24, 1.0f);
    const float* memory = a.row(0);
    pool.take(a, 40, 24);  // already of that size: kept, as it was
    CHECK(a.row(0) == memory);
    CHECK(a.at(3, 2) == 1.0f);
    pool.take(a, 40, 12);  // of another size: a new plane
    CHECK(a.height() == 12);
    pool.give(a);
    CHECK(a.empty());
    pool.give(a);  // (an empty plane stays empty)
    CHECK(a.empty());
    PlaneU16 h;
    pool.take(h, 20, 12);
    CHECK((h.width() == 20 && h.height() == 12));
}

TEST_CASE("plane pool: a freed plane's memory goes to the next plane, whatever its type") {
    if (!planeMemoryUse().fromRange) return;  // (malloc's: a sanitizer's build)
    PlanePool pool;
    PlaneF a;
    pool.take(a, 640, 360);
    const PlaneMemoryUse before = planeMemoryUse();
    pool.give(a);
    CHECK(planeMemoryUse().bytesInUse < before.bytesInUse);
    // An f16 plane takes (part of) that block: no page beyond the range's highest yet.
    PlaneU16 h;
    pool.take(h, 640, 360);
    CHECK(planeMemoryUse().bytesTouched == before.bytesTouched);
}

TEST_CASE("plane pool: poisoned planes come filled with the poison") {
    PlanePool pool;
    pool.poison(std::nanf(""));
    PlaneF a;
    PlaneU16 h;
    pool.take(a, 40, 24);
    pool.take(h, 40, 24);
    CHECK(std::isnan(a.at(39, 23)));
    CHECK(std::isnan(decodeF16(h.at(0, 0))));
    pool.poison(std::nullopt);
    PlaneF b;
    pool.take(b, 40, 24);  // (whatever the memory held)
    CHECK(b.width() == 40);
}
