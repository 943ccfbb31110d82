// The packing keys of the march (trace/march_keys_kernel.cpp): which rays are marched at all, and
// which screen-direction bucket each falls in. The keys only order the rays (no result bit
// depends on them), so a wrong key would show only as slower marching: tested here directly.
#include <doctest/doctest.h>

#include <limits>
#include <vector>

#include "core/isa.h"
#include "trace/march_kernel.h"

using namespace ssrt;

namespace {

struct KeyRay {
    float pdf, ox, oy, oz, dx, dy, dz;
    int key;  // expected
};

// Origin (0, 0, -2), sx = sy = 100: the screen direction is (200 dx, -200 dy) plus, for
// rays with dz != 0 and an origin off the axis, its share of dz. Diamond angle 0, 1, 2, 3 =
// right, down, left, up (screen y grows downwards); 16 sectors per unit; key = 2 sector +
// (dz > 0).
std::vector<KeyRay> keyRays() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    return {
        {1, 0, 0, -2, 1, 0, 0, 0},          // right
        {1, 0, 0, -2, 0, -1, 0, 2 * 16},    // down
        {1, 0, 0, -2, -1, 0, 0, 2 * 32},    // left
        {1, 0, 0, -2, 0, 1, 0, 2 * 48},     // up
        {1, 0, 0, -2, 1, -1, 0, 2 * 8},     // right and down: angle 0.5
        {1, 0, 0, -2, 1, 0, 1, 1},          // right, towards the camera
        {1, 0, 0, -2, 0, 0, -1, 0},         // straight away on the axis: no screen motion
        {0, 0, 0, -2, 1, 0, 0, -1},         // pdf 0
        {1, 0, 0, -2, nan, 0, 0, -1},       // NaN direction
        {1, inf, 0, -2, 1, 0, 0, -1},       // infinite origin
        {1, 0, 0, -2, 0, 0, 0, -1},         // zero direction
        {1, 0, 0, 1, 1, 0, 0, -1},          // origin behind the camera
        {0.5f, 0, 0, -2, 0, 1, 0, 2 * 48},  // up again (a second lane group on narrow ISAs)
    };
}

}  // namespace

TEST_CASE("march keys: rays without a march are -1, the others by screen direction") {
    const std::vector<KeyRay> rays = keyRays();
    const int n = int(rays.size());
    // Readable 16 floats past the rays (kMarchPad), as a tile's row segments are.
    std::vector<float> p[7];
    for (auto& v : p) v.assign(std::size_t(n + 16), 0.0f);
    for (int i = 0; i < n; ++i) {
        const KeyRay& r = rays[std::size_t(i)];
        const float f[7] = {r.pdf, r.ox, r.oy, r.oz, r.dx, r.dy, r.dz};
        for (int c = 0; c < 7; ++c) p[c][std::size_t(i)] = f[c];
    }
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        std::vector<int8_t> key(std::size_t(n + 16), int8_t(99));
        MarchKernelArgs a{};
        a.pdf = p[0].data();
        a.ox = p[1].data(), a.oy = p[2].data(), a.oz = p[3].data();
        a.dx = p[4].data(), a.dy = p[5].data(), a.dz = p[6].data();
        a.count = n;
        a.sx = a.sy = 100.0f;
        a.key = key.data();
        SSRT_DISPATCH(isa, marchSortKeys)(a);
        for (int i = 0; i < n; ++i) {
            CAPTURE(i);
            CHECK(int(key[std::size_t(i)]) == rays[std::size_t(i)].key);
        }
        // Nothing written past the count.
        for (int i = n; i < n + 16; ++i) CHECK(int(key[std::size_t(i)]) == 99);
    }
}
