// Rasterization rules: watertight, no double hits, the top-left rule, degenerate, tiny and
// huge triangles, bad vertices, and every ISA against the scalar kernel bit for bit.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/rng.h"
#include "raster_fixture.h"
#include "thread_counts.h"

using namespace ssrt;
using namespace ssrt::test;

namespace {

// Snap to the 1/256-pixel grid so the test's geometry is exactly the rasterizer's.
glm::vec2 snap(glm::vec2 p) { return glm::round(p * 256.0f) / 256.0f; }

// Jittered grid over [x0, x1) x [y0, y1), two triangles per cell, random diagonal.
std::vector<PixelTri> tiledRectangle(glm::vec2 lo, glm::vec2 hi, int nx, int ny, uint32_t seed) {
    std::vector<glm::vec2> pts;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            glm::vec2 p = lo + (hi - lo) * glm::vec2(float(i) / nx, float(j) / ny);
            if (i > 0 && i < nx && j > 0 && j < ny) {
                const glm::vec2 cell = (hi - lo) / glm::vec2(nx, ny);
                p +=
                    cell * 0.4f *
                    glm::vec2(randomFloat(i, j, seed, 0) - 0.5f, randomFloat(i, j, seed, 1) - 0.5f);
            }
            pts.push_back(snap(p));
        }
    std::vector<PixelTri> tris;
    auto at = [&](int i, int j) { return pts[j * (nx + 1) + i]; };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const glm::vec2 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (randomFloat(i, j, seed, 2) < 0.5f) {
                tris.push_back({a, b, c});
                tris.push_back({a, c, d});
            } else {
                tris.push_back({a, b, d});
                tris.push_back({b, c, d});
            }
        }
    return tris;
}

// Pixel centres inside [lo, hi) under the top-left rule for an axis-aligned rectangle.
bool centreInRect(int x, int y, glm::vec2 lo, glm::vec2 hi) {
    const float cx = x + 0.5f, cy = y + 0.5f;
    return cx >= lo.x && cx < hi.x && cy >= lo.y && cy < hi.y;
}

void requireExactCover(const RasterResult& r, glm::vec2 lo, glm::vec2 hi) {
    int expected = 0;
    for (int y = 0; y < r.vb.ids.height(); ++y)
        for (int x = 0; x < r.vb.ids.width(); ++x) {
            const bool inside = centreInRect(x, y, lo, hi);
            expected += inside;
            CAPTURE(x);
            CAPTURE(y);
            REQUIRE((r.vb.ids.at(x, y) != kNoPrimitive) == inside);
        }
    // Every covered sample passed the (equal-depth, strictly nearer) test exactly once:
    // a second triangle covering the same centre would be counted as covered, not written.
    CHECK(r.stats.pixelsCovered == uint64_t(expected));
    CHECK(r.stats.pixelsWritten == uint64_t(expected));
}

}  // namespace

TEST_CASE("a fan around a shared vertex covers every centre exactly once") {
    const int w = 128, h = 128;
    const glm::vec2 c = snap({64.3f, 63.7f});
    for (int n : {3, 7, 16, 61}) {
        CAPTURE(n);
        std::vector<PixelTri> tris;
        std::vector<glm::vec2> rim;
        for (int i = 0; i < n; ++i) {
            const float a = 6.2831853f * float(i) / float(n) + 0.1f;
            rim.push_back(snap(c + 50.0f * glm::vec2(std::cos(a), std::sin(a))));
        }
        for (int i = 0; i < n; ++i) tris.push_back({c, rim[i], rim[(i + 1) % n]});
        const RasterResult r = rasterPixelTris(tris, w, h);
        // No double hits anywhere (all at one depth: a second hit is covered, not written).
        CHECK(r.stats.pixelsCovered == r.stats.pixelsWritten);
        // No cracks: every centre clearly inside the polygon is covered, none clearly outside.
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const glm::vec2 p(x + 0.5f, y + 0.5f);
                float minDist = 1e9f;
                bool inside = true;
                for (int i = 0; i < n; ++i) {
                    const glm::vec2 e = rim[(i + 1) % n] - rim[i];
                    const float d =
                        (e.x * (p.y - rim[i].y) - e.y * (p.x - rim[i].x)) / glm::length(e);
                    inside &= d > 0.0f;
                    minDist = std::min(minDist, std::fabs(d));
                }
                if (minDist < 1e-3f) continue;
                CAPTURE(x);
                CAPTURE(y);
                REQUIRE((r.vb.ids.at(x, y) != kNoPrimitive) == inside);
            }
    }
}

TEST_CASE("random meshes tiling a rectangle leave no cracks and no double hits") {
    const int w = 200, h = 136;  // not powers of two, not multiples of the tile size
    for (uint32_t seed = 0; seed < 6; ++seed) {
        CAPTURE(seed);
        const glm::vec2 lo = seed % 2 ? glm::vec2(3.5f, 7.5f) : glm::vec2(0.0f, 0.0f);
        const glm::vec2 hi = seed % 2 ? glm::vec2(190.5f, 130.5f) : glm::vec2(200.0f, 136.0f);
        const auto tris = tiledRectangle(lo, hi, 9 + seed, 7 + seed, seed);
        requireExactCover(rasterPixelTris(tris, w, h), lo, hi);
    }
}

TEST_CASE("top-left rule on edges through pixel centres") {
    const int w = 64, h = 64;
    // A square whose edges run exactly through pixel centres, split along either diagonal:
    // left and top edges own their centres, right and bottom ones do not.
    const glm::vec2 lo(10.5f, 20.5f), hi(30.5f, 41.5f);
    const glm::vec2 b(hi.x, lo.y), d(lo.x, hi.y);
    requireExactCover(rasterPixelTris({{lo, b, hi}, {lo, hi, d}}, w, h), lo, hi);
    requireExactCover(rasterPixelTris({{lo, b, d}, {b, hi, d}}, w, h), lo, hi);
    // Winding must not matter (double-sided).
    requireExactCover(rasterPixelTris({{lo, hi, b}, {lo, d, hi}}, w, h), lo, hi);
    // A diagonal through centres: the shared edge's centres are owned by exactly one side.
    const auto r =
        rasterPixelTris({{{0, 0}, {64, 64}, {64, 0}}, {{0, 0}, {0, 64}, {64, 64}}}, w, h);
    CHECK(coveredCount(r.vb) == w * h);
    CHECK(r.stats.pixelsCovered == uint64_t(w * h));
}

TEST_CASE("sub-pixel and degenerate triangles") {
    const int w = 32, h = 32;
    // Tiny triangle around the centre of pixel (5, 7): exactly that pixel.
    auto r = rasterPixelTris({{{5.4f, 7.4f}, {5.7f, 7.45f}, {5.5f, 7.7f}}}, w, h);
    CHECK(coveredCount(r.vb) == 1);
    CHECK(r.vb.ids.at(5, 7) == 0u);
    // Tiny triangle between centres: nothing, and no crash.
    r = rasterPixelTris({{{5.6f, 7.6f}, {5.9f, 7.6f}, {5.7f, 7.9f}}}, w, h);
    CHECK(coveredCount(r.vb) == 0);
    // Collinear and repeated vertices: skipped and counted, never drawn.
    r = rasterPixelTris({{{1, 1}, {10, 10}, {20, 20}}, {{3, 3}, {3, 3}, {9, 4}}}, w, h);
    CHECK(coveredCount(r.vb) == 0);
    CHECK(r.stats.trianglesInvalid == 2);
}

TEST_CASE("huge triangles are clipped to the guard band and cover the screen once") {
    const int w = 160, h = 96;
    const float big = 1.0e6f;
    const auto r = rasterPixelTris({{{-big, -big}, {big, -big}, {0.0f, big}}}, w, h);
    CHECK(r.stats.trianglesClipped == 1);
    CHECK(coveredCount(r.vb) == w * h);
    CHECK(r.stats.pixelsWritten == uint64_t(w * h));
    // Two huge triangles sharing an edge through the screen: still exactly once each pixel.
    const auto r2 = rasterPixelTris(
        {{{-big, -big}, {big, big}, {big, -big}}, {{-big, -big}, {-big, big}, {big, big}}}, w, h);
    CHECK(coveredCount(r2.vb) == w * h);
    CHECK(r2.stats.pixelsCovered == uint64_t(w * h));
}

TEST_CASE("NaN and infinite vertices are skipped") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const auto r = rasterPixelTris(
        {{{nan, 1}, {10, 1}, {5, 9}}, {{inf, 1}, {10, 1}, {5, 9}}, {{1, 1}, {10, 1}, {5, 9}}}, 16,
        16);
    CHECK(r.stats.trianglesInvalid == 2);
    CHECK(coveredCount(r.vb) > 0);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            CHECK(std::isfinite(r.vb.depth.at(x, y)));
            const uint32_t id = r.vb.ids.at(x, y);
            CHECK((id == kNoPrimitive || id == 2u));
        }
}

TEST_CASE("nearer triangles win -- equal depth keeps the first submitted") {
    const int w = 32, h = 32;
    const PixelTri farT{{0, 0}, {32, 0}, {0, 32}, 0.8f};
    const PixelTri nearT{{0, 0}, {32, 0}, {0, 32}, 0.2f};
    auto r = rasterPixelTris({farT, nearT}, w, h);
    CHECK(r.vb.ids.at(2, 2) == 1u);
    r = rasterPixelTris({nearT, farT}, w, h);
    CHECK(r.vb.ids.at(2, 2) == 0u);
    r = rasterPixelTris({nearT, nearT}, w, h);
    CHECK(r.vb.ids.at(2, 2) == 0u);
}

TEST_CASE("every ISA and thread count rasterizes the same bits") {
    const int w = 301, h = 177;
    std::vector<PixelTri> tris;
    for (uint32_t i = 0; i < 400; ++i) {
        auto rnd = [&](uint32_t d, float lo, float hi) {
            return lo + (hi - lo) * randomFloat(i, 7, 0, d);
        };
        const glm::vec2 c(rnd(0, -20, w + 20), rnd(1, -20, h + 20));
        const float size = rnd(2, 0.3f, 120.0f);
        tris.push_back({snap(c + size * glm::vec2(rnd(3, -1, 1), rnd(4, -1, 1))),
                        snap(c + size * glm::vec2(rnd(5, -1, 1), rnd(6, -1, 1))),
                        snap(c + size * glm::vec2(rnd(7, -1, 1), rnd(8, -1, 1))),
                        rnd(9, 0.05f, 0.95f)});
    }
    const RasterResult ref = rasterPixelTris(tris, w, h, Isa::Scalar, 1);
    CHECK(coveredCount(ref.vb) > w * h / 2);
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 2, 8})) {
            const std::string isaStr(isaName(isa));
            CAPTURE(isaStr);
            CAPTURE(threads);
            const RasterResult r = rasterPixelTris(tris, w, h, isa, threads);
            CHECK(hashPlane(r.vb.depth) == hashPlane(ref.vb.depth));
            CHECK(hashPlane(r.vb.ids) == hashPlane(ref.vb.ids));
            CHECK(r.stats.pixelsCovered == ref.stats.pixelsCovered);
            CHECK(r.stats.pixelsWritten == ref.stats.pixelsWritten);
            CHECK(r.stats.blocksPartial == ref.stats.blocksPartial);
        }
}
