#include "core/suggest.h"

#include <doctest/doctest.h>

using namespace ssrt;

TEST_CASE(
    "suggest: edits count inserts, deletes, replacements and swapped neighbours, case ignored") {
    CHECK(editDistance("", "") == 0);
    CHECK(editDistance("width", "width") == 0);
    CHECK(editDistance("Width", "wIDTH") == 0);
    CHECK(editDistance("widht", "width") == 1);  // a swap of neighbours is one edit
    CHECK(editDistance("cornel", "cornell") == 1);
    CHECK(editDistance("cornelll", "cornell") == 1);
    CHECK(editDistance("corbell", "cornell") == 1);
    CHECK(editDistance("kitten", "sitting") == 3);
    CHECK(editDistance("", "abc") == 3);
    CHECK(editDistance("abc", "") == 3);
}

TEST_CASE("suggest: the nearest known name within a third of the typed one's length") {
    const std::vector<std::string> known = {"--width", "--height", "--scene", "--quality"};
    CHECK(nearestName("--widht", known) == "--width");
    CHECK(nearestName("--hieght", known) == "--height");
    CHECK(nearestName("--quallity", known) == "--quality");
    CHECK(nearestName("--frobnicate", known).empty());
    CHECK(nearestName("x", {"y"}) == "y");  // (one edit always reaches)
    CHECK(nearestName("ab", {"cd"}).empty());
    // Equals: the first in the list's order.
    CHECK(nearestName("cat", {"bat", "hat"}) == "bat");
    CHECK(didYouMean("cornel", {"cornell", "spheres"}) == "; did you mean cornell?");
    CHECK(didYouMean("teapot", {"cornell", "spheres"}).empty());
}
