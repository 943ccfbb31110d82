// The plane pool (core/plane_pool.h): a plane given back is the one taken next at its size,
// other sizes are allocated, and a size change frees the rest.
#include "core/plane_pool.h"

#include <doctest/doctest.h>

using namespace ssrt;

TEST_CASE("plane pool: planes go round at their size, others are allocated") {
    PlanePool pool;
    PlaneF a(40, 24, 1.0f), b;
    const float* memory = a.row(0);
    pool.give(a);
    CHECK(a.empty());
    CHECK(pool.size() == 1);
    CHECK(pool.bytes() == PlaneF(40, 24).bytes());
    pool.take(b, 40, 24);  // the same memory, as it was left
    CHECK(b.row(0) == memory);
    CHECK(b.at(3, 2) == 1.0f);
    CHECK(pool.size() == 0);
    PlaneF c;
    pool.take(c, 20, 12);  // none of that size: a new plane
    CHECK(c.width() == 20);
    CHECK(pool.size() == 0);
    pool.take(b, 40, 24);  // already of that size: kept
    CHECK(b.row(0) == memory);
    pool.take(b, 40, 12);  // of another size: given back, a new one taken
    CHECK(b.height() == 12);
    CHECK(pool.size() == 1);
    pool.give(c);
    pool.give(b);
    pool.give(b);  // (an empty plane adds nothing)
    CHECK(pool.size() == 3);
    pool.keepOnly(40, 24, 20, 12);
    CHECK(pool.size() == 2);
    pool.keepOnly(80, 48, 40, 24);
    CHECK(pool.size() == 1);
}
