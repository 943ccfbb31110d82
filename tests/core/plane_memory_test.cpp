// Planes' memory (core/plane_memory.h): blocks come out of one range best fit, a freed block
// is the next one of its size, and freed neighbours merge so that a larger plane fits where
// two smaller ones were.
#include "core/plane_memory.h"

#include <doctest/doctest.h>

#include <cstdint>

#include "core/image.h"

using namespace ssrt;

TEST_CASE("plane memory: freed blocks are reused and merge with their neighbours") {
    const PlaneMemoryUse before = planeMemoryUse();
    if (!before.fromRange) {
        MESSAGE("planes come from malloc in this build (a sanitizer's): nothing to check");
        return;
    }
    constexpr std::size_t kSize = 3 * 4096;
    unsigned char* a = static_cast<unsigned char*>(allocatePlaneMemory(kSize, 0));
    unsigned char* b = static_cast<unsigned char*>(allocatePlaneMemory(kSize, 0));
    unsigned char* c = static_cast<unsigned char*>(allocatePlaneMemory(kSize, 0));
    CHECK(reinterpret_cast<std::uintptr_t>(a) % 64 == 0);
    CHECK(planeMemoryUse().bytesInUse == before.bytesInUse + 3 * 4 * 4096);  // header page each
    a[0] = b[kSize - 1] = c[kSize - 1] = 1;  // the whole size is writable

    freePlaneMemory(b);
    unsigned char* b2 = static_cast<unsigned char*>(allocatePlaneMemory(kSize, 0));
    CHECK(b2 == b);  // best fit: the hole it left, not the range's end

    freePlaneMemory(a);
    freePlaneMemory(b2);  // a and b merge into one free block twice their size
    unsigned char* ab = static_cast<unsigned char*>(allocatePlaneMemory(2 * kSize, 0));
    CHECK(ab == a);

    unsigned char* staggered = static_cast<unsigned char*>(allocatePlaneMemory(kSize, 5 * 64));
    CHECK(reinterpret_cast<std::uintptr_t>(staggered) % 4096 == 6 * 64);  // header line + 5

    freePlaneMemory(staggered);
    freePlaneMemory(ab);
    freePlaneMemory(c);
    CHECK(planeMemoryUse().bytesInUse == before.bytesInUse);
    CHECK(planeMemoryUse().freeBlocks == before.freeBlocks);  // all merged back
}

TEST_CASE("plane memory: planes hold their pixels through reuse") {
    PlaneF first(300, 200, 2.0f);
    const float* memory = first.row(0);
    first = PlaneF();
    PlaneF second(300, 200, 5.0f);
    if (planeMemoryUse().fromRange) CHECK(second.row(0) == memory);
    CHECK(second.at(299, 199) == 5.0f);
    CHECK(second.at(0, 0) == 5.0f);
}
