// The marchers (trace/march.h) and the Hi-Z pyramid (raster/hiz.h): analytic hits on a
// synthetic mirror floor under a box, the ends of rays that leave the screen, come toward
// the camera or pass behind thin objects, agreement between the marchers, Hi-Z efficiency,
// no NaN anywhere, and the same bits for every thread count and ISA.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/isa.h"
#include "plane_compare.h"
#include "raster/hiz.h"
#include "tests/trace/march_fixture.h"
#include "thread_counts.h"
#include "trace/ray_gen.h"

using namespace ssrt;
using namespace ssrt::test;

namespace {

constexpr Marcher kMarchers[] = {Marcher::Linear, Marcher::Dda, Marcher::HiZ};

MarchEnd causeAt(const MarchResult& r, int x, int y) { return MarchEnd(int(r.cause.at(x, y))); }

bool allFinite(const MarchResult& r) {
    for (const PlaneF* p : {&r.hit, &r.hitX, &r.hitY, &r.hitZ, &r.steps, &r.cause})
        for (int y = 0; y < p->height(); ++y)
            for (int x = 0; x < p->width(); ++x)
                if (!std::isfinite(p->at(x, y))) return false;
    return true;
}

uint64_t resultHash(const MarchResult& r) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const PlaneF* p : {&r.hit, &r.hitX, &r.hitY, &r.hitZ, &r.steps, &r.cause})
        h = hashPlane(*p, h);
    return h;
}

// Where the mirror ray of floor pixel (x, y) meets the box front face, if it does.
bool analyticBoxHit(const GBuf& g, const RayBatch& rays, int x, int y, glm::vec2& pixel) {
    using S = BoxScene;
    const glm::vec3 o(rays.ox.at(x, y), rays.oy.at(x, y), rays.oz.at(x, y));
    const glm::vec3 d(rays.dx.at(x, y), rays.dy.at(x, y), rays.dz.at(x, y));
    if (!(d.z < 0.0f) || -o.z >= S::kBoxZ) return false;
    const float t = (-S::kBoxZ - o.z) / d.z;
    const glm::vec3 p = o + d * t;
    if (p.x < -0.99f || p.x > 0.99f || p.y < S::kFloorY + 0.01f || p.y > S::kBoxTop - 0.01f)
        return false;
    pixel = projectToPixel(g.camera, p);
    // Keep away from the frame edge.
    return pixel.x > 2.0f && pixel.y > 2.0f && pixel.x < float(g.camera.width - 2) &&
           pixel.y < float(g.camera.height - 2);
}

}  // namespace

TEST_CASE("march: names, parsing and settings validation") {
    for (Marcher m : kMarchers) CHECK(parseMarcher(marcherName(m)) == m);
    CHECK(marcherName(Marcher::HiZ) == "hiz");
    CHECK_FALSE(parseMarcher("bogus").has_value());
    MarchSettings s;
    CHECK_NOTHROW(s.validate());
    auto bad = [](auto mutate, const char* field) {
        MarchSettings t;
        mutate(t);
        try {
            t.validate();
            FAIL("no throw for ", field);
        } catch (const std::invalid_argument& e) {
            CHECK(std::string(e.what()).find(field) != std::string::npos);
        }
    };
    bad([](MarchSettings& t) { t.maxSteps = 0; }, "maxSteps");
    bad([](MarchSettings& t) { t.maxDistance = -1.0f; }, "maxDistance");
    bad([](MarchSettings& t) { t.linearStep = 0.0f; }, "linearStep");
    bad([](MarchSettings& t) { t.thickness = std::nanf(""); }, "thickness");
    bad([](MarchSettings& t) { t.ddaStride = 0.5f; }, "ddaStride");
    bad([](MarchSettings& t) { t.ddaJitter = 2.0f; }, "ddaJitter");
    bad([](MarchSettings& t) { t.refineSteps = -1; }, "refineSteps");
    bad([](MarchSettings& t) { t.hizMostDetailedLevel = -1; }, "hizMostDetailedLevel");
    bad([](MarchSettings& t) { t.hizStartLevel = 1, t.hizMostDetailedLevel = 2; }, "hizStartLevel");
    bad([](MarchSettings& t) { t.thicknessAbsolute = -0.1f; }, "thicknessAbsolute");
    bad([](MarchSettings& t) { t.maxDistanceAbsolute = INFINITY; }, "maxDistanceAbsolute");
}

TEST_CASE("march: relative lengths resolve per frame, absolute ones replace them") {
    MarchSettings s;
    s.maxDistance = 2.0f;
    s.linearStep = 0.01f;
    s.thickness = 0.05f;
    const MarchLengths rel = marchLengths(s, 8.0f);
    CHECK(rel.maxDistance == 16.0f);  // two diagonals
    CHECK(rel.stepScale == 0.01f);
    CHECK(rel.stepBias == 0.0f);
    CHECK(rel.thicknessScale == 0.05f);
    CHECK(rel.thicknessBias == 0.0f);
    s.maxDistanceAbsolute = 3.0f;
    s.linearStepAbsolute = 0.2f;
    s.thicknessAbsolute = 0.1f;
    const MarchLengths abs = marchLengths(s, 8.0f);
    CHECK(abs.maxDistance == 3.0f);
    CHECK(abs.stepScale == 0.0f);
    CHECK(abs.stepBias == 0.2f);
    CHECK(abs.thicknessScale == 0.0f);
    CHECK(abs.thicknessBias == 0.1f);
    // Absolute lengths need no scene; a relative maxDistance does.
    CHECK(marchLengths(s, 0.0f).maxDistance == 3.0f);
    s.maxDistanceAbsolute = 0.0f;
    CHECK_THROWS_AS(marchLengths(s, 0.0f), std::invalid_argument);
    CHECK_THROWS_AS(marchLengths(s, NAN), std::invalid_argument);
}

TEST_CASE("march: stats percentiles, mean and combination") {
    MarchStats a, b;
    a.rays = 4, a.steps = 10, a.stepHistogram = {0, 1, 2, 0, 0, 0, 0, 1};  // 1, 2, 2, 7 (sum 12)
    b.rays = 0, b.stepHistogram = {0, 0, 0};
    a.add(b);
    CHECK(a.stepHistogram.size() == 8);
    CHECK(a.meanSteps() == doctest::Approx(2.5));
    CHECK(a.stepsPercentile(0.0) == 1);
    CHECK(a.stepsPercentile(0.5) == 2);
    CHECK(a.stepsPercentile(0.75) == 2);
    CHECK(a.stepsPercentile(1.0) == 7);
    CHECK(a.maxStepsTaken() == 7);
}

TEST_CASE("march: hi-z levels equal the brute-force min of their footprint") {
    // An odd-sized rendered G-buffer with background, so the odd rows/columns and the
    // background convention are both exercised.
    const GBuf g = renderGBuffer("spheres", 101, 77);
    HiZPyramid hiz;
    buildHiZ(g.viewZ, hiz, 2);
    REQUIRE(hiz.levels() == hiZLevelCount(101, 77));
    CHECK(hiz.levels() == 8);  // 101 -> 51 -> 26 -> 13 -> 7 -> 4 -> 2 -> 1
    CHECK(hiz.minZ.back().width() == 1);
    CHECK(hiz.minZ.back().height() == 1);
    const float inf = std::numeric_limits<float>::infinity();
    bool background = false;
    for (int L = 0; L < hiz.levels(); ++L) {
        const PlaneF& lo = hiz.minZ[std::size_t(L)];
        for (int cy = 0; cy < lo.height(); ++cy)
            for (int cx = 0; cx < lo.width(); ++cx) {
                float mn = inf;
                for (int y = cy << L; y < std::min((cy + 1) << L, 77); ++y)
                    for (int x = cx << L; x < std::min((cx + 1) << L, 101); ++x) {
                        const float z = g.viewZ.at(x, y) > 0.0f ? g.viewZ.at(x, y) : inf;
                        background |= z == inf;
                        mn = std::min(mn, z);
                    }
                REQUIRE(lo.at(cx, cy) == mn);
            }
    }
    CHECK(background);
    // Rebuilding into the same pyramid reuses it and gives the same bits with 1 thread.
    const float* before = hiz.minZ[3].row(0);
    const uint64_t h = hashPlane(hiz.minZ[2]);
    buildHiZ(g.viewZ, hiz, 1);
    CHECK(hiz.minZ[3].row(0) == before);
    CHECK(hashPlane(hiz.minZ[2]) == h);
}

TEST_CASE("march: hi-z packs 1/minZ once, and marching from it equals packing per call") {
    const GBuf g = renderGBuffer("spheres", 101, 77);
    HiZPyramid hiz;
    buildHiZ(g.viewZ, hiz, 2);
    REQUIRE(hiz.packedOffset.size() == std::size_t(hiz.levels()));
    bool background = false;
    for (int L = 0; L < hiz.levels(); ++L) {
        const PlaneF& lo = hiz.minZ[std::size_t(L)];
        const float* packed = hiz.invMinPacked.data() + hiz.packedOffset[std::size_t(L)];
        // Rows of tiles padded to a power of two tiles (101 px: 26 tiles, pitch 32).
        const int tilesY = (lo.height() + 3) / 4;
        int tilesX = 1;
        while (tilesX * 4 < lo.width()) tilesX *= 2;
        CHECK(hiZPackedPitch(lo.width()) == tilesX);
        CHECK((1 << hiZPackedPitchLog2(lo.width())) == tilesX);
        for (int y = 0; y < tilesY * 4; ++y)
            for (int x = 0; x < tilesX * 4; ++x) {
                // 4x4 tiles of 16 floats, row-major within a tile and across tiles; texels past
                // the level's edge are background.
                const std::size_t at =
                    std::size_t((y / 4 * tilesX + x / 4) * 16 + y % 4 * 4 + x % 4);
                CHECK(at == hiZPackedIndex(x, y, tilesX));
                const bool inside = x < lo.width() && y < lo.height();
                const float want = inside ? 1.0f / lo.at(x, y) : 0.0f;  // background (+inf) -> 0
                background |= inside && want == 0.0f;
                REQUIRE(std::bit_cast<uint32_t>(packed[at]) == std::bit_cast<uint32_t>(want));
            }
        const std::size_t next = std::size_t(L) + 1 < hiz.packedOffset.size()
                                     ? hiz.packedOffset[std::size_t(L) + 1]
                                     : hiz.invMinPacked.size();
        CHECK(next - hiz.packedOffset[std::size_t(L)] == std::size_t(tilesX * tilesY * 16));
    }
    CHECK(background);
    // Whole tiles on cache lines.
    CHECK(reinterpret_cast<std::uintptr_t>(hiz.invMinPacked.data()) % 64 == 0);
    CHECK(hiz.packedOffset.back() + 16 == hiz.invMinPacked.size());  // the last level is 1x1
    // A pyramid without the packed copy (not from buildHiZ) is packed by marchRays itself.
    HiZPyramid bare;
    buildHiZ(g.viewZ, bare, 1);
    bare.invMinPacked.clear();
    bare.packedOffset.clear();
    const RayBatch rays = mirrorRays(g);
    MarchResult a, b;
    const MarchSettings s;
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        marchRays(isa, Marcher::HiZ, s, {}, g.camera, g.view(), nullptr, &hiz, rays, a, 2);
        marchRays(isa, Marcher::HiZ, s, {}, g.camera, g.view(), nullptr, &bare, rays, b, 2);
        // (Both paths give the same bits by design: this holds the stored copy to the one
        // marchRays would make, not that the stored one is used; the benchmarks show that.)
        CHECK(sameBits(a.hit, b.hit));
        CHECK(sameBits(a.hitX, b.hitX));
        CHECK(sameBits(a.hitY, b.hitY));
        CHECK(sameBits(a.hitZ, b.hitZ));
        CHECK(sameBits(a.steps, b.steps));
        CHECK(sameBits(a.cause, b.cause));
    }
    // Equal planes say something only if rays hit.
    int hits = 0;
    for (int y = 0; y < 77; ++y)
        for (int x = 0; x < 101; ++x) hits += a.hit.at(x, y) > 0.0f;
    CHECK(hits > 100);
}

TEST_CASE("march: mirror floor under a box hits the box face at the analytic pixel") {
    const GBuf g = makeBoxGBuffer(240, 160);
    const RayBatch rays = mirrorRays(g);
    MarchSettings s;
    s.linearStep = 0.02f;
    s.maxDistance = 40.0f;
    for (Marcher m : kMarchers) {
        CAPTURE(marcherName(m));
        MarchResult r;
        march(m, s, g, rays, r);
        int expected = 0, hits = 0, close = 0;
        double maxErr = 0.0;
        for (int y = 0; y < 160; ++y)
            for (int x = 0; x < 240; ++x) {
                glm::vec2 p;
                if (g.ny.at(x, y) != 1.0f || !analyticBoxHit(g, rays, x, y, p)) continue;
                ++expected;
                if (causeAt(r, x, y) != MarchEnd::Hit) continue;
                ++hits;
                const double err = std::hypot(r.hitX.at(x, y) - p.x, r.hitY.at(x, y) - p.y);
                maxErr = std::max(maxErr, err);
                // (A DDA stride over 1 pixel may step over the box's top edge onto the wall.)
                if (err <= 1.5 && std::abs(r.hitZ.at(x, y) - BoxScene::kBoxZ) < 0.06f) ++close;
            }
        std::printf("box mirror %s: %d expected, %d hit, %d within 1.5 px, max error %.2f px\n",
                    marcherName(m).data(), expected, hits, close, maxErr);
        REQUIRE(expected > 500);
        CHECK(hits >= expected * 97 / 100);
        CHECK(close >= hits * 97 / 100);
        CHECK(allFinite(r));
    }
}

TEST_CASE("march: a ray leaving the screen is LeftScreen") {
    const GBuf g = makeBoxGBuffer(160, 120);
    RayBatch rays = emptyRays(160, 120);
    // From the floor in front of the box, up and to the right at constant depth: nothing is
    // in front of it on the way out of the frame.
    const int x = 100, y = 110;
    REQUIRE(g.ny.at(x, y) == 1.0f);
    setRay(rays, g, x, y, {1.0f, 0.4f, 0.0f});
    MarchSettings s;
    for (Marcher m : kMarchers) {
        CAPTURE(marcherName(m));
        MarchResult r;
        const MarchStats st = march(m, s, g, rays, r);
        CHECK(causeAt(r, x, y) == MarchEnd::LeftScreen);
        CHECK(r.hit.at(x, y) == 0.0f);
        CHECK(r.steps.at(x, y) > 0.0f);
        CHECK(st.rays == 1);
        CHECK(st.ends[int(MarchEnd::LeftScreen)] == 1);
        // Every other pixel: no ray, no steps.
        CHECK(causeAt(r, 0, 0) == MarchEnd::NoRay);
        CHECK(r.steps.at(5, 100) == 0.0f);
        CHECK(allFinite(r));
    }
}

TEST_CASE("march: a ray toward the camera terminates at the near plane without NaN") {
    const GBuf g = makeBoxGBuffer(160, 120);
    RayBatch rays = emptyRays(160, 120);
    // Straight back at the camera from the box face, and up-and-back from the floor.
    setRay(rays, g, 80, 60, {0.0f, 0.0f, 1.0f});
    setRay(rays, g, 80, 100, {0.0f, 0.3f, 1.0f});
    MarchSettings s;
    for (Marcher m : kMarchers) {
        CAPTURE(marcherName(m));
        MarchResult r;
        march(m, s, g, rays, r);
        CHECK(causeAt(r, 80, 60) == MarchEnd::LeftScreen);
        CHECK(causeAt(r, 80, 100) == MarchEnd::LeftScreen);
        CHECK(r.steps.at(80, 60) < float(s.maxSteps));
        CHECK(allFinite(r));
    }
}

TEST_CASE("march: a thin object crossed with a large linear step is a Thickness miss") {
    // A wall at depth 10 and a thin bar (10 rows, about 1.2 units high and thin in depth) at
    // depth 2 in front of it; rays from the wall go straight up at constant depth 10 and pass
    // 8 units behind the bar: the depth buffer is crossed, but far behind its surface.
    const int w = 64, h = 96;
    GBuf g;
    g.camera = makeCamera(w, h, 60.0f);
    for (PlaneF* p : {&g.viewZ, &g.nx, &g.ny, &g.nz}) *p = PlaneF(w, h, 0.0f);
    g.viewZ.fill(10.0f);
    g.nz.fill(1.0f);
    for (int y = 36; y < 46; ++y)
        for (int x = 0; x < w; ++x) g.viewZ.at(x, y) = 2.0f;
    RayBatch rays = emptyRays(w, h);
    for (int x = 4; x < 60; x += 5) setRay(rays, g, x, 80, {0.0f, 1.0f, 0.0f});
    MarchSettings s;
    s.linearStep = 0.5f;  // about 4 pixels at depth 10
    for (Marcher m : kMarchers) {
        CAPTURE(marcherName(m));
        MarchResult r;
        const MarchStats st = march(m, s, g, rays, r);
        CHECK(st.rays == 12);
        CHECK(st.ends[int(MarchEnd::Thickness)] == 12);
        CHECK(st.ends[int(MarchEnd::Hit)] == 0);
        CHECK(allFinite(r));
    }
    // The same with the built-in thin scene: mirror rays everywhere, no NaN.
    const GBuf thin = renderGBuffer("thin", 160, 90);
    const RayBatch mirror = mirrorRays(thin);
    for (Marcher m : kMarchers) {
        MarchResult r;
        march(m, s, thin, mirror, r);
        CHECK(allFinite(r));
    }
}

TEST_CASE("march: the three marchers agree on the box scene") {
    const GBuf g = makeBoxGBuffer(240, 160);
    const RayBatch rays = mirrorRays(g);
    MarchSettings s;
    s.linearStep = 0.02f;
    s.maxDistance = 40.0f;
    MarchResult r[3];
    for (int i = 0; i < 3; ++i) march(kMarchers[i], s, g, rays, r[i]);
    // Share of rays whose hit/miss agrees, and of common hits within 2 pixels.
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b) {
            int rayCount = 0, agree = 0, both = 0, near = 0;
            for (int y = 0; y < 160; ++y)
                for (int x = 0; x < 240; ++x) {
                    if (rays.pdf.at(x, y) == 0.0f) continue;
                    ++rayCount;
                    const bool ha = r[a].hit.at(x, y) == 1.0f, hb = r[b].hit.at(x, y) == 1.0f;
                    agree += ha == hb;
                    if (ha && hb) {
                        ++both;
                        near += std::hypot(r[a].hitX.at(x, y) - r[b].hitX.at(x, y),
                                           r[a].hitY.at(x, y) - r[b].hitY.at(x, y)) <= 2.0;
                    }
                }
            std::printf("agreement %s/%s: hit/miss %.4f, hits within 2 px %.4f (%d common)\n",
                        marcherName(kMarchers[a]).data(), marcherName(kMarchers[b]).data(),
                        double(agree) / rayCount, double(near) / std::max(both, 1), both);
            CHECK(double(agree) / rayCount >= 0.95);
            CHECK(double(near) / both >= 0.95);
            CHECK(both > 1000);
        }
}

TEST_CASE("march: hi-z takes far fewer steps than linear on the corridor") {
    const GBuf g = renderGBuffer("corridor", 320, 180);
    const RayBatch rays = mirrorRays(g);
    MarchSettings s;
    MarchResult r;
    const MarchStats lin = march(Marcher::Linear, s, g, rays, r);
    const MarchStats dda = march(Marcher::Dda, s, g, rays, r);
    const MarchStats hiz = march(Marcher::HiZ, s, g, rays, r);
    std::printf("corridor mean steps: linear %.1f, dda %.1f, hiz %.1f; hits %llu %llu %llu\n",
                lin.meanSteps(), dda.meanSteps(), hiz.meanSteps(), (unsigned long long)lin.ends[0],
                (unsigned long long)dda.ends[0], (unsigned long long)hiz.ends[0]);
    REQUIRE(lin.rays > 10000);
    CHECK(hiz.meanSteps() * 4.0 < lin.meanSteps());
    CHECK(hiz.meanSteps() * 2.0 < dda.meanSteps());
}

TEST_CASE("march: grazing rays, frame edges and background give no NaN") {
    const GBuf g = renderGBuffer("cornell", 96, 64);
    const int w = 96, h = 64;
    RayBatch rays = emptyRays(w, h);
    // Every surface pixel (edges included) with a ray nearly along its view ray (grazing
    // the surface it starts on), alternately away from and toward the camera, and some
    // perpendicular to the view ray.
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (g.viewZ.at(x, y) <= 0.0f) continue;
            const glm::vec3 v = glm::normalize(pixelDir(g.camera, x + 0.5f, y + 0.5f));
            const int kind = (x + y) % 4;
            glm::vec3 d = kind == 0   ? v + glm::vec3(1e-6f, 0, 0)
                          : kind == 1 ? -v
                          : kind == 2 ? glm::cross(v, glm::vec3(0, 1, 0))
                                      : glm::vec3(0, 0, -1) + glm::vec3(0, 1e-7f, 0);
            setRay(rays, g, x, y, d);
        }
    // Background pixels keep pdf 0.
    MarchSettings s;
    s.hizMostDetailedLevel = 0;
    for (Marcher m : kMarchers)
        for (float stride : {1.0f, 7.5f}) {
            CAPTURE(marcherName(m));
            s.ddaStride = stride;
            MarchResult r;
            const MarchStats st = march(m, s, g, rays, r);
            CHECK(allFinite(r));
            uint64_t ended = 0;
            for (uint64_t e : st.ends) ended += e;
            CHECK(ended == st.rays);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    if (g.viewZ.at(x, y) <= 0.0f) {
                        CHECK(causeAt(r, x, y) == MarchEnd::NoRay);
                        CHECK(r.steps.at(x, y) == 0.0f);
                    }
        }
}

TEST_CASE("march: bit-identical for threads 1/2/8 and every ISA the CPU runs") {
    const GBuf g = renderGBuffer("cornell", 200, 136);
    const RayBatch rays = mirrorRays(g);
    for (Marcher m : kMarchers)
        for (int variant = 0; variant < 2; ++variant) {
            CAPTURE(marcherName(m));
            MarchSettings s;
            if (variant == 1) {
                s.ddaStride = 2.5f, s.linearStep = 0.11f, s.hizMostDetailedLevel = 1;
                s.hizStartLevel = 2;
            }
            const RaySeed seed{variant == 1 ? 3u : 0u, 0};
            MarchResult ref;
            const MarchStats refStats = march(m, s, g, rays, ref, Isa::Scalar, 1, seed);
            CHECK(refStats.ends[int(MarchEnd::Hit)] > 100);
            const uint64_t h = resultHash(ref);
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    CAPTURE(isaName(isa));
                    CAPTURE(threads);
                    MarchResult r;
                    const MarchStats st = march(m, s, g, rays, r, isa, threads, seed);
                    CHECK(resultHash(r) == h);
                    CHECK(st.steps == refStats.steps);
                    CHECK(st.laneActive == refStats.laneActive);
                    for (int e = 0; e < kMarchEndCount; ++e) CHECK(st.ends[e] == refStats.ends[e]);
                }
        }
}

TEST_CASE("march: every ray's result is the same bits as when it is marched alone") {
    // marchRays packs a tile's rays in its own order (grouped by screen direction) and marches
    // them a lane group at a time; a ray's result must not depend on that order or on its lane
    // mates. Reference: the same ray in a batch of its own (one ray, one lane).
    PlaneF roughness;
    const GBuf g = renderGBuffer("cornell", 200, 136, &roughness);
    const GBufferView rg = g.view(&roughness);
    RayBatch vndf, cosine;
    generateSpecularRays(Isa::Scalar, SsrMethod::VndfBounded, 2, 0, g.camera, rg, vndf, 1);
    generateDiffuseRays(Isa::Scalar, 2, 0, g.camera, rg, cosine, 1);
    const Isa best = supportedIsas().back();
    for (Marcher m : kMarchers)
        for (const RayBatch* rays : {&vndf, &cosine}) {
            CAPTURE(marcherName(m));
            const MarchSettings s;
            const RaySeed seed{2, 0};
            MarchResult all;
            march(m, s, g, *rays, all, best, 2, seed);
            int compared = 0, hits = 0;
            // Every 37th pixel with a ray (about 700 rays).
            for (int p = 0; p < 200 * 136; p += 37) {
                const int x = p % 200, y = p / 200;
                if (!(rays->pdf.at(x, y) > 0.0f)) continue;
                RayBatch one = emptyRays(200, 136);
                for (auto plane : {&RayBatch::ox, &RayBatch::oy, &RayBatch::oz, &RayBatch::dx,
                                   &RayBatch::dy, &RayBatch::dz, &RayBatch::pdf})
                    (one.*plane).at(x, y) = ((*rays).*plane).at(x, y);
                MarchResult alone;
                march(m, s, g, one, alone, best, 1, seed);
                CAPTURE(x);
                CAPTURE(y);
                for (auto plane : {&MarchResult::hit, &MarchResult::hitX, &MarchResult::hitY,
                                   &MarchResult::hitZ, &MarchResult::steps, &MarchResult::cause})
                    CHECK(std::bit_cast<uint32_t>((all.*plane).at(x, y)) ==
                          std::bit_cast<uint32_t>((alone.*plane).at(x, y)));
                ++compared;
                hits += all.hit.at(x, y) != 0.0f;
            }
            CHECK(compared > 500);
            CHECK(hits > 50);
        }
}

TEST_CASE("march: a hit on a surface whose normal faces along the ray is BackFace") {
    // The box scene with the box face's normal turned away from the camera: every reflection
    // that met the box now meets a back face.
    GBuf g = makeBoxGBuffer(240, 160);
    const RayBatch rays = mirrorRays(g);
    for (int y = 0; y < 160; ++y)
        for (int x = 0; x < 240; ++x)
            if (g.viewZ.at(x, y) == BoxScene::kBoxZ) g.nz.at(x, y) = -1.0f;
    MarchSettings s;
    s.linearStep = 0.02f;
    s.maxDistance = 40.0f;
    for (Marcher m : kMarchers) {
        CAPTURE(marcherName(m));
        MarchResult r;
        march(m, s, g, rays, r);
        int expected = 0, backFace = 0;
        for (int y = 0; y < 160; ++y)
            for (int x = 0; x < 240; ++x) {
                glm::vec2 p;
                if (g.ny.at(x, y) != 1.0f || !analyticBoxHit(g, rays, x, y, p)) continue;
                ++expected;
                backFace += causeAt(r, x, y) == MarchEnd::BackFace;
                // (DDA may step over the box's top edge onto the wall: not a box hit.)
                CHECK_FALSE((r.hit.at(x, y) == 1.0f && r.hitZ.at(x, y) < 7.0f));
            }
        REQUIRE(expected > 500);
        CHECK(backFace >= expected * 97 / 100);
    }
}

TEST_CASE("march: hi-z with a coarser most detailed level and a higher start level") {
    const GBuf g = makeBoxGBuffer(240, 160);
    const RayBatch rays = mirrorRays(g);
    MarchSettings s;
    s.maxDistance = 40.0f;
    MarchResult fine, coarse;
    const MarchStats a = march(Marcher::HiZ, s, g, rays, fine);
    s.hizMostDetailedLevel = 1;
    s.hizStartLevel = 3;
    const MarchStats b = march(Marcher::HiZ, s, g, rays, coarse);
    // Box reflections still hit the box, within a cell of the most detailed level (2 px).
    int expected = 0, close = 0;
    for (int y = 0; y < 160; ++y)
        for (int x = 0; x < 240; ++x) {
            glm::vec2 p;
            if (g.ny.at(x, y) != 1.0f || !analyticBoxHit(g, rays, x, y, p)) continue;
            ++expected;
            close += coarse.hit.at(x, y) == 1.0f &&
                     std::hypot(coarse.hitX.at(x, y) - p.x, coarse.hitY.at(x, y) - p.y) <= 2.0;
        }
    std::printf("hi-z level 1: %d of %d box reflections within 2 px; mean steps %.1f vs %.1f\n",
                close, expected, b.meanSteps(), a.meanSteps());
    CHECK(close >= expected * 9 / 10);
    CHECK(allFinite(coarse));
    // Lane bookkeeping: every step issues kWidth slots, at least one active.
    CHECK(b.laneActive <= b.laneSlots);
    CHECK(b.laneActive == b.steps);
    CHECK(a.laneActive == a.steps);
}
