// The SSR resolve against analytic answers on a synthetic frame (a wall facing the camera,
// hits placed by hand), and its contract on a rendered G-buffer: finite everywhere, the same
// bits for every ISA and thread count.
#include "trace/ssr_resolve.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/rng.h"
#include "plane_compare.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "thread_counts.h"
#include "trace/color_pyramid.h"

using namespace ssrt;

namespace {

constexpr int kW = 100, kH = 70;  // not a multiple of the tile or of any lane width

using test::sameBits;

// Colour of pixel (x, y): distinct everywhere.
float colourOf(int c, int x, int y) {
    return c == 0   ? 0.01f * float(x) + 0.1f
           : c == 1 ? 0.02f * float(y) + 0.2f
                    : 0.5f + 0.001f * float(x * y);
}

// A wall at depth 5 facing the camera (identity rotation), every pixel's ray hitting where
// `hitAt` says at depth 2 (a surface in front of the wall), pdf 1, roughness `rough`.
struct WallFixture {
    PlaneF viewZ{kW, kH, 5.0f};
    PlaneF normal[3] = {PlaneF(kW, kH, 0.0f), PlaneF(kW, kH, 0.0f), PlaneF(kW, kH, 1.0f)};
    PlaneF roughness;
    PlaneF color[3], prev[3];
    PlaneF motion[2] = {PlaneF(kW, kH, 0.0f), PlaneF(kW, kH, 0.0f)};
    RayBatch rays;
    MarchResult march;
    SsrResolveArgs in;
    ColorPyramid pyramid;

    explicit WallFixture(float rough = 0.0f) : roughness(kW, kH, rough) {
        for (int c = 0; c < 3; ++c) {
            color[c] = PlaneF(kW, kH);
            prev[c] = PlaneF(kW, kH);
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    color[c].at(x, y) = colourOf(c, x, y);
                    prev[c].at(x, y) = 2.0f * colourOf(c, x, y) + 1.0f;
                }
        }
        rays.ensureSize(kW, kH);
        march.ensureSize(kW, kH);
        rays.ox.fill(0.0f);
        rays.oy.fill(0.0f);
        rays.oz.fill(-5.0f);
        rays.dx.fill(0.0f);
        rays.dy.fill(0.0f);
        rays.dz.fill(1.0f);
        rays.pdf.fill(1.0f);
        march.hit.fill(1.0f);
        march.hitZ.fill(2.0f);  // in front of the wall, so every hit faces this pixel
        march.steps.fill(1.0f);
        march.cause.fill(float(MarchEnd::Hit));
        hitAt([](int x, int y, float& hx, float& hy) {
            hx = float(x) + 0.5f;
            hy = float(y) + 0.5f;
        });
        in.camera.width = kW;
        in.camera.height = kH;
        in.camera.tanHalfX = 0.5f * float(kW) / float(kH);
        in.camera.tanHalfY = 0.5f;
        in.g = gbufferView("test", kW, kH,
                           {{kGViewZ, &viewZ},
                            {kGNormalX, &normal[0]},
                            {kGNormalY, &normal[1]},
                            {kGNormalZ, &normal[2]},
                            {kGRoughness, &roughness},
                            {kGMotionX, &motion[0]},
                            {kGMotionY, &motion[1]}});
        for (int c = 0; c < 3; ++c) {
            in.color[c] = viewOf(color[c], "color");
            in.prevColor[c] = viewOf(prev[c], "prevColor");
        }
    }

    template <class F>
    void hitAt(F f) {
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) f(x, y, march.hitX.at(x, y), march.hitY.at(x, y));
    }

    SsrOutput resolve(const SsrResolveSettings& s, Isa isa = Isa::Scalar, int threads = 2) {
        if (s.mode == SsrResolveMode::Mip) {
            const PlaneF* src[3];
            for (int c = 0; c < 3; ++c)
                src[c] = s.radiance == HitRadiance::Current ? &color[c] : &prev[c];
            buildColorPyramid(src, pyramid, threads);
            in.pyramid = &pyramid;
        }
        SsrOutput out;
        resolveSsr(isa, s, in, rays, march, out, 0, 1, threads);
        return out;
    }
};

SsrResolveSettings settings(SsrResolveMode mode, HitRadiance radiance = HitRadiance::Current,
                            bool bilinear = true) {
    SsrResolveSettings s;
    s.mode = mode;
    s.radiance = radiance;
    s.bilinear = bilinear;
    return s;
}

}  // namespace

TEST_CASE("ssr resolve: a hit on a pixel's centre gives that pixel's colour (Current)") {
    WallFixture f;
    // Every ray hits the pixel mirrored left-right.
    f.hitAt([](int x, int y, float& hx, float& hy) {
        hx = float(kW - 1 - x) + 0.5f;
        hy = float(y) + 0.5f;
    });
    for (bool bilinear : {true, false}) {
        CAPTURE(bilinear);
        // Mip at roughness 0: level 0, exact.
        const SsrOutput out =
            f.resolve(settings(SsrResolveMode::Mip, HitRadiance::Current, bilinear));
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c)
                    CHECK(out.color[c].at(x, y) == colourOf(c, kW - 1 - x, y));
    }
    // Reuse: every neighbour hits the same pixel, so the ratio estimator returns its colour.
    f.hitAt([](int, int, float& hx, float& hy) {
        hx = 41.5f;
        hy = 33.5f;
    });
    for (bool bilinear : {true, false}) {
        const SsrOutput out =
            f.resolve(settings(SsrResolveMode::Reuse, HitRadiance::Current, bilinear));
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c)
                    CHECK(out.color[c].at(x, y) ==
                          doctest::Approx(colourOf(c, 41, 33)).epsilon(1e-6));
    }
    // Off the centre, bilinear mixes the neighbours and nearest does not.
    f.hitAt([](int, int, float& hx, float& hy) {
        hx = 41.75f;
        hy = 33.5f;
    });
    const SsrOutput nearest =
        f.resolve(settings(SsrResolveMode::Reuse, HitRadiance::Current, false));
    const SsrOutput bilinear =
        f.resolve(settings(SsrResolveMode::Reuse, HitRadiance::Current, true));
    CHECK(nearest.color[0].at(5, 5) == doctest::Approx(colourOf(0, 41, 33)).epsilon(1e-6));
    CHECK(bilinear.color[0].at(5, 5) ==
          doctest::Approx(0.75f * colourOf(0, 41, 33) + 0.25f * colourOf(0, 42, 33)).epsilon(1e-5));
}

TEST_CASE("ssr resolve: Reprojected reads the previous colour at hit + motion") {
    WallFixture f;
    f.motion[0].fill(3.0f);
    f.motion[1].fill(-2.0f);
    f.hitAt([](int x, int y, float& hx, float& hy) {
        hx = float(kW - 1 - x) + 0.5f;
        hy = float(y) + 0.5f;
    });
    const SsrOutput mip = f.resolve(settings(SsrResolveMode::Mip, HitRadiance::Reprojected));
    int checked = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const int px = kW - 1 - x + 3, py = y - 2;
            const bool onScreen = px >= 0 && px < kW && py >= 0 && py < kH;
            if (!onScreen) {
                // Reprojected off the frame: a miss.
                CHECK(mip.opacity.at(x, y) == 0.0f);
                continue;
            }
            for (int c = 0; c < 3; ++c) CHECK(mip.color[c].at(x, y) == f.prev[c].at(px, py));
            ++checked;
        }
    CHECK(checked > kW * kH / 2);
    // Reuse, every ray on one pixel.
    f.hitAt([](int, int, float& hx, float& hy) {
        hx = 41.5f;
        hy = 33.5f;
    });
    const SsrOutput reuse = f.resolve(settings(SsrResolveMode::Reuse, HitRadiance::Reprojected));
    for (int c = 0; c < 3; ++c)
        CHECK(reuse.color[c].at(60, 20) == doctest::Approx(f.prev[c].at(44, 31)).epsilon(1e-6));
}

TEST_CASE("ssr resolve: edge-of-screen fade is 0 on the border, 1 inside, linear between") {
    WallFixture f;
    SsrResolveSettings s = settings(SsrResolveMode::Mip);
    s.edgeFadeLength = 0.1f;
    // Row y hits at x = the border, 2.5% in, 5% in, the middle (by the pixel's column).
    f.hitAt([](int x, int, float& hx, float& hy) {
        const float at[4] = {0.0f, 0.025f * kW, 0.05f * kW, 0.5f * kW};
        hx = at[x % 4];
        hy = 0.5f * kH;
    });
    const SsrOutput out = f.resolve(s);
    const float expect[4] = {0.0f, 0.25f, 0.5f, 1.0f};
    for (int x = 0; x < kW; ++x)
        CHECK(out.opacity.at(x, 10) == doctest::Approx(expect[x % 4]).epsilon(1e-5));
    // The far border and the top and bottom too.
    f.hitAt([](int x, int, float& hx, float& hy) {
        hx = x % 2 ? float(kW) : 0.5f * kW;
        hy = x % 2 ? 0.5f * kH : (x % 4 == 0 ? 0.0f : float(kH));
    });
    const SsrOutput border = f.resolve(s);
    for (int x = 0; x < kW; ++x) CHECK(border.opacity.at(x, 10) == 0.0f);
}

TEST_CASE(
    "ssr resolve: with edgeFadeLength 0 (mixed and world tracing) a hit is whole up to "
    "and on the border") {
    WallFixture f;
    SsrResolveSettings s = settings(SsrResolveMode::Mip);
    s.edgeFadeLength = 0.0f;
    f.hitAt([](int x, int, float& hx, float& hy) {
        const float at[4] = {0.0f, 0.5f, 0.025f * kW, float(kW) - 0.5f};
        hx = at[x % 4];
        hy = x % 8 < 4 ? 0.5f * kH : 0.0f;
    });
    const SsrOutput out = f.resolve(s);
    for (int x = 0; x < kW; ++x) CHECK(out.opacity.at(x, 10) == 1.0f);
}

TEST_CASE("ssr resolve: roughness fade is 1 below the start and 0 above the end") {
    WallFixture f;
    SsrResolveSettings s = settings(SsrResolveMode::Mip);
    s.roughnessFadeStart = 0.4f;
    s.roughnessFadeEnd = 0.8f;
    const float rough[5] = {0.0f, 0.3f, 0.6f, 0.9f, 1.0f};
    const float expect[5] = {1.0f, 1.0f, 0.5f, 0.0f, 0.0f};
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) f.roughness.at(x, y) = rough[x % 5];
    f.hitAt([](int, int, float& hx, float& hy) {  // far from the edges: edge fade 1
        hx = 50.5f;
        hy = 35.5f;
    });
    for (SsrResolveMode mode : {SsrResolveMode::Mip, SsrResolveMode::Reuse}) {
        s.mode = mode;
        const SsrOutput out = f.resolve(s);
        for (int x = 1; x + 1 < kW; ++x)
            CHECK(out.opacity.at(x, 30) == doctest::Approx(expect[x % 5]).epsilon(1e-5));
    }
}

TEST_CASE("ssr resolve: reuse normalises on a uniform hit field, and uses only valid rays") {
    WallFixture f(0.4f);
    for (int c = 0; c < 3; ++c) f.color[c].fill(0.25f * float(c + 1));
    // Random hit positions anywhere in the frame (edge fades < 1 near its border), random
    // pdfs, random depths.
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const uint32_t i = uint32_t(y * kW + x);
            f.march.hitX.at(x, y) = float(kW) * randomFloat(i, 1, 0, 0);
            f.march.hitY.at(x, y) = float(kH) * randomFloat(i, 1, 0, 1);
            f.march.hitZ.at(x, y) = 1.0f + 3.0f * randomFloat(i, 1, 0, 2);
            f.rays.pdf.at(x, y) = 0.1f + 5.0f * randomFloat(i, 1, 0, 3);
        }
    const SsrOutput out = f.resolve(settings(SsrResolveMode::Reuse));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c)
                CHECK(out.color[c].at(x, y) == doctest::Approx(0.25f * float(c + 1)).epsilon(1e-5));
    // Only the pixel itself has a ray (neighbours pdf 0): its own hit's colour, whatever the
    // neighbours' hits say.
    // (New planes: new views of them.)
    for (int c = 0; c < 3; ++c) {
        f.color[c] = WallFixture().color[c].clone();
        f.in.color[c] = viewOf(f.color[c], "color");
    }
    f.rays.pdf.fill(0.0f);
    f.rays.pdf.at(50, 40) = 2.0f;
    f.march.hitX.at(50, 40) = 20.5f;
    f.march.hitY.at(50, 40) = 30.5f;
    const SsrOutput one = f.resolve(settings(SsrResolveMode::Reuse));
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            for (int c = 0; c < 3; ++c)
                CHECK(one.color[c].at(50 + dx, 40 + dy) ==
                      doctest::Approx(colourOf(c, 20, 30)).epsilon(1e-6));
    CHECK(one.opacity.at(52, 40) == 0.0f);
    CHECK(one.color[0].at(52, 40) == 0.0f);
}

TEST_CASE("ssr resolve: reuse weights neighbours by this pixel's lobe over their pdf") {
    // Two hit colours, half the neighbours each: the one whose rays have the lower pdf
    // (same lobe value) weighs more, in the ratio of the pdfs.
    WallFixture f(0.5f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            // Hits straight in front of each pixel on a plane behind the camera would be
            // odd; instead every ray misses and carries the same direction (the wall's normal),
            // so every neighbour's lobe value is the same.
            f.march.hit.at(x, y) = (x % 2) ? 1.0f : 0.0f;
            f.rays.pdf.at(x, y) = (x % 2) ? 1.0f : 3.0f;
        }
    // Hits all land on one pixel; misses carry fade 0. Opacity = sum(w f) / sum(w).
    f.hitAt([](int, int, float& hx, float& hy) {
        hx = 50.5f;
        hy = 35.5f;
    });
    const SsrOutput out = f.resolve(settings(SsrResolveMode::Reuse));
    // At an even column: neighbours x-1, x+1 hit (pdf 1) and x misses (pdf 3), in 3 rows. The
    // lobe values differ per neighbour (hit directions vs the miss direction), so only check
    // the bounds: 0 < opacity < 1 and the colour of the hit.
    const float o = out.opacity.at(40, 30);
    CHECK(o > 0.0f);
    CHECK(o < 1.0f);
    CHECK(out.color[0].at(40, 30) == doctest::Approx(colourOf(0, 50, 35)).epsilon(1e-6));
    // Lower the misses' pdf: they weigh more, so the opacity drops.
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; x += 2) f.rays.pdf.at(x, y) = 0.5f;
    const SsrOutput lower = f.resolve(settings(SsrResolveMode::Reuse));
    CHECK(lower.opacity.at(40, 30) < o);
}

TEST_CASE("ssr resolve: samples average (opacity-weighted colour, mean opacity)") {
    WallFixture f;
    SsrOutput out;
    const SsrResolveSettings s = settings(SsrResolveMode::Reuse);
    f.hitAt([](int, int, float& hx, float& hy) {
        hx = 41.5f;
        hy = 33.5f;
    });
    resolveSsr(Isa::Scalar, s, f.in, f.rays, f.march, out, 0, 3, 2);
    f.hitAt([](int, int, float& hx, float& hy) {
        hx = 11.5f;
        hy = 13.5f;
    });
    resolveSsr(Isa::Scalar, s, f.in, f.rays, f.march, out, 1, 3, 2);
    f.march.hit.fill(0.0f);  // the third sample misses everywhere
    resolveSsr(Isa::Scalar, s, f.in, f.rays, f.march, out, 2, 3, 2);
    for (int c = 0; c < 3; ++c)
        CHECK(out.color[c].at(30, 30) ==
              doctest::Approx(0.5f * (colourOf(c, 41, 33) + colourOf(c, 11, 13))).epsilon(1e-5));
    CHECK(out.opacity.at(30, 30) == doctest::Approx(2.0f / 3.0f).epsilon(1e-6));
    CHECK_THROWS_AS(resolveSsr(Isa::Scalar, s, f.in, f.rays, f.march, out, 3, 3, 2),
                    std::invalid_argument);
    // The G-buffer it reads: of the camera's size, with the planes the settings need.
    SsrResolveArgs small = f.in;
    small.camera.width = kW - 1;
    CHECK_THROWS_AS(resolveSsr(Isa::Scalar, s, small, f.rays, f.march, out, 0, 1, 2),
                    std::invalid_argument);
    // And the colour: named.
    SsrResolveArgs narrow = f.in;
    const PlaneF narrowColor(kW - 1, kH);
    narrow.color[1] = viewOf(narrowColor, "color.G");
    CHECK_THROWS_WITH_AS(
        resolveSsr(Isa::Scalar, s, narrow, f.rays, f.march, out, 0, 1, 2),
        ("resolveSsr: color.G is " + std::to_string(kW - 1) + "x" + std::to_string(kH) + ", not " +
         std::to_string(kW) + "x" + std::to_string(kH))
            .c_str(),
        std::invalid_argument);
    SsrResolveArgs flat = f.in;
    flat.g.roughness = nullptr;
    CHECK_THROWS_AS(resolveSsr(Isa::Scalar, s, flat, f.rays, f.march, out, 0, 1, 2),
                    std::invalid_argument);
}

TEST_CASE("ssr resolve: mip mode at roughness 0 equals level 0, and blurs with roughness") {
    WallFixture f;
    f.hitAt([](int x, int y, float& hx, float& hy) {
        hx = float(x) * 0.93f + 0.37f;  // off the pixel centres: bilinear
        hy = float(y) * 0.91f + 0.61f;
    });
    const SsrOutput mip = f.resolve(settings(SsrResolveMode::Mip));
    SsrResolveSettings reuseSettings = settings(SsrResolveMode::Reuse);
    // Reuse with only the own ray per pixel gives the level-0 bilinear read to compare with:
    // use every ray but only for the first lane of each 3x3 (pdf 0 elsewhere).
    f.rays.pdf.fill(0.0f);
    for (int y = 1; y < kH; y += 3)
        for (int x = 1; x < kW; x += 3) f.rays.pdf.at(x, y) = 1.0f;
    const SsrOutput reuse = f.resolve(reuseSettings);
    for (int y = 1; y < kH; y += 3)
        for (int x = 1; x < kW; x += 3)
            for (int c = 0; c < 3; ++c)
                CHECK(mip.color[c].at(x, y) ==
                      doctest::Approx(reuse.color[c].at(x, y)).epsilon(1e-6));
    // Roughness 1: the coarsest level (1 x 1): the frame's mean everywhere.
    WallFixture rough(1.0f);
    const SsrOutput blurred = rough.resolve(settings(SsrResolveMode::Mip));
    const float a = blurred.color[2].at(3, 3), b = blurred.color[2].at(90, 60);
    CHECK(a == b);
    CHECK(rough.pyramid.levels.back()[0].width() == 1);
    CHECK(rough.pyramid.levels.back()[0].height() == 1);
}

TEST_CASE("colour pyramid: 2x2 box levels down to 1x1, odd sizes clamped") {
    PlaneF p[3] = {PlaneF(5, 3), PlaneF(5, 3), PlaneF(5, 3)};
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x)
            for (int c = 0; c < 3; ++c) p[c].at(x, y) = float(x + 10 * y + 100 * c);
    const PlaneF* src[3] = {&p[0], &p[1], &p[2]};
    ColorPyramid pyr;
    buildColorPyramid(src, pyr, 2);
    REQUIRE(pyr.levelCount() == 4);  // 5x3, 3x2, 2x1, 1x1
    CHECK(pyr.levels[1][0].width() == 3);
    CHECK(pyr.levels[1][0].height() == 2);
    CHECK(pyr.levels[1][0].at(0, 0) == 5.5f);   // (0 + 1 + 10 + 11) / 4
    CHECK(pyr.levels[1][0].at(2, 1) == 24.0f);  // x 4 and row 2, both clamped
    CHECK(pyr.levels[3][2].width() == 1);
    CHECK(pyr.levels[0][1].at(4, 2) == p[1].at(4, 2));
}

TEST_CASE(
    "ssr resolve: finite everywhere on a rendered frame, and the same bits on every ISA and thread "
    "count") {
    RenderSettings rs;
    rs.width = 133;
    rs.height = 77;
    rs.shadowMapSize = 128;
    rs.threads = 2;
    const Frame frame =
        Renderer(rs).renderWithoutHistory(makeBuiltinScene("spheres"));  // roughness 0..1
    const int w = frame.width, h = frame.height;
    SsrResolveArgs in;
    in.camera.width = w;
    in.camera.height = h;
    in.camera.tanHalfY = 0.4f;
    in.camera.tanHalfX = 0.4f * float(w) / float(h);
    in.g = frame.gbuffer.view();
    for (int c = 0; c < 3; ++c) {
        in.color[c] = viewOf(frame.rgb(Res::Color)[c], "color");
        in.prevColor[c] = viewOf(frame.rgb(Res::Color)[c], "prevColor");
    }
    // Random rays: some without a ray, some with a tiny or huge pdf, hits anywhere including
    // exactly on the frame's edges and beyond.
    RayBatch rays;
    MarchResult march;
    rays.ensureSize(w, h);
    march.ensureSize(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint32_t i = uint32_t(y * w + x);
            const float u[6] = {randomFloat(i, 7, 0, 0), randomFloat(i, 7, 0, 1),
                                randomFloat(i, 7, 0, 2), randomFloat(i, 7, 0, 3),
                                randomFloat(i, 7, 0, 4), randomFloat(i, 7, 0, 5)};
            const bool bg = frame.gbuffer.viewZ.at(x, y) <= 0.0f;
            const float pdfs[5] = {0.0f, 1e-30f, 1.0f, 1e30f, 0.3f};
            rays.pdf.at(x, y) = bg ? 0.0f : pdfs[int(u[0] * 5)];
            const float dz = -u[1], dx = u[2] - 0.5f, dy = u[3] - 0.5f;
            const float len = std::sqrt(dx * dx + dy * dy + dz * dz);
            rays.dx.at(x, y) = rays.pdf.at(x, y) > 0 ? dx / len : 0.0f;
            rays.dy.at(x, y) = rays.pdf.at(x, y) > 0 ? dy / len : 0.0f;
            rays.dz.at(x, y) = rays.pdf.at(x, y) > 0 ? dz / len : 0.0f;
            march.hit.at(x, y) = rays.pdf.at(x, y) > 0 && u[4] < 0.7f ? 1.0f : 0.0f;
            const float edges[4] = {0.0f, float(w), u[5] * float(w), -3.0f};
            march.hitX.at(x, y) = march.hit.at(x, y) > 0 ? edges[int(u[1] * 4)] : 0.0f;
            march.hitY.at(x, y) = march.hit.at(x, y) > 0 ? u[2] * float(h) : 0.0f;
            march.hitZ.at(x, y) = march.hit.at(x, y) > 0 ? 1.0f + 10.0f * u[3] : 0.0f;
        }
    ColorPyramid pyr;
    const auto srcRgb = frame.rgb(Res::Color);
    const PlaneF* src[3] = {&srcRgb[0], &srcRgb[1], &srcRgb[2]};
    buildColorPyramid(src, pyr, 2);
    in.pyramid = &pyr;
    for (SsrResolveMode mode : {SsrResolveMode::Mip, SsrResolveMode::Reuse})
        for (HitRadiance radiance : {HitRadiance::Current, HitRadiance::Reprojected}) {
            SsrResolveSettings s;
            s.mode = mode;
            s.radiance = radiance;
            CAPTURE(int(mode));
            CAPTURE(int(radiance));
            // Two samples, so the accumulation path runs too.
            SsrOutput ref;
            for (int k = 0; k < 2; ++k) resolveSsr(Isa::Scalar, s, in, rays, march, ref, k, 2, 1);
            bool finite = true, inRange = true;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    for (int c = 0; c < 3; ++c)
                        finite = finite && std::isfinite(ref.color[c].at(x, y));
                    const float o = ref.opacity.at(x, y);
                    inRange = inRange && o >= 0.0f && o <= 1.0f;
                    if (frame.gbuffer.viewZ.at(x, y) <= 0.0f) inRange = inRange && o == 0.0f;
                }
            CHECK(finite);
            CHECK(inRange);
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    CAPTURE(isaName(isa));
                    CAPTURE(threads);
                    SsrOutput out;
                    for (int k = 0; k < 2; ++k)
                        resolveSsr(isa, s, in, rays, march, out, k, 2, threads);
                    for (int c = 0; c < 3; ++c) CHECK(sameBits(out.color[c], ref.color[c]));
                    CHECK(sameBits(out.opacity, ref.opacity));
                }
        }
}

namespace {

// Double-precision oracle of one reuse weight: GGX D V (n.l) / pdf for a pixel at p with
// normal n (view space), towards l, at perceptual roughness r.
double reuseWeight(const double p[3], const double n[3], const double l[3], double r, double pdf) {
    auto dot = [](const double* a, const double* b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    const double lenP = std::sqrt(dot(p, p));
    const double v[3] = {-p[0] / lenP, -p[1] / lenP, -p[2] / lenP};
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    const double lenH = std::sqrt(dot(h, h));
    for (double& c : h) c /= lenH;
    const double NoL = dot(n, l), NoV = std::max(dot(n, v), 1e-4), NoH = std::max(dot(n, h), 0.0);
    if (NoL <= 0.0) return 0.0;
    const double a = std::max(r * r, 1e-3), a2 = a * a;
    const double f = NoH * NoH * (a2 - 1.0) + 1.0;
    const double D = a2 / (M_PI * f * f);
    const double V = 0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) +
                            NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
    return D * V * NoL / pdf;
}

}  // namespace

TEST_CASE(
    "ssr resolve: reuse is the ratio estimator with GGX D V n.l / pdf weights (double oracle)") {
    WallFixture f(0.45f);
    // Neighbour hits scattered in front of the wall, with their own depths, pdfs, fades and
    // (through the hit pixel) colours; one neighbour misses.
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const uint32_t i = uint32_t(y * kW + x);
            f.march.hitX.at(x, y) = 2.0f + float(kW - 4) * randomFloat(i, 2, 0, 0);
            f.march.hitY.at(x, y) = float(kH) * 0.5f + 20.0f * (randomFloat(i, 2, 0, 1) - 0.5f);
            f.march.hitZ.at(x, y) = 1.0f + 2.0f * randomFloat(i, 2, 0, 2);
            f.rays.pdf.at(x, y) = 0.2f + 3.0f * randomFloat(i, 2, 0, 3);
        }
    const int px = 37, py = 29;
    f.march.hit.at(px + 1, py - 1) = 0.0f;  // a miss along its own direction, (0, 0.6, 0.8)
    f.rays.dx.at(px + 1, py - 1) = 0.0f;
    f.rays.dy.at(px + 1, py - 1) = 0.6f;
    f.rays.dz.at(px + 1, py - 1) = 0.8f;
    SsrResolveSettings s = settings(SsrResolveMode::Reuse, HitRadiance::Current, false);
    s.roughnessFadeStart = 0.9f;  // no roughness fade here
    s.roughnessFadeEnd = 1.0f;
    const SsrOutput out = f.resolve(s);
    // The oracle, in double.
    const double tx = f.in.camera.tanHalfX, ty = f.in.camera.tanHalfY;
    auto point = [&](double sx, double sy, double z, double* q) {
        q[0] = (2.0 * sx / kW - 1.0) * tx * z;
        q[1] = (1.0 - 2.0 * sy / kH) * ty * z;
        q[2] = -z;
    };
    double p[3];
    point(px + 0.5, py + 0.5, 5.0, p);
    const double n[3] = {0.0, 0.0, 1.0};
    double sumW = 0.0, sumWF = 0.0, sumWFL[3] = {0.0, 0.0, 0.0};
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int x = px + dx, y = py + dy;
            double l[3];
            double fade = 0.0;
            double L[3] = {0.0, 0.0, 0.0};
            if (f.march.hit.at(x, y) > 0.5f) {
                const double hx = f.march.hitX.at(x, y), hy = f.march.hitY.at(x, y);
                double q[3];
                point(hx, hy, f.march.hitZ.at(x, y), q);
                const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
                const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (int c = 0; c < 3; ++c) l[c] = d[c] / len;
                const double u = hx / kW, v = hy / kH;
                fade = std::min(1.0, std::min(std::min(u, 1.0 - u), std::min(v, 1.0 - v)) / 0.1);
                for (int c = 0; c < 3; ++c) L[c] = colourOf(c, int(hx), int(hy));
            } else {
                l[0] = f.rays.dx.at(x, y);
                l[1] = f.rays.dy.at(x, y);
                l[2] = f.rays.dz.at(x, y);
            }
            const double w = reuseWeight(p, n, l, 0.45, f.rays.pdf.at(x, y));
            sumW += w;
            sumWF += w * fade;
            for (int c = 0; c < 3; ++c) sumWFL[c] += w * fade * L[c];
        }
    REQUIRE(sumWF > 0.0);
    for (int c = 0; c < 3; ++c)
        CHECK(out.color[c].at(px, py) == doctest::Approx(sumWFL[c] / sumWF).epsilon(2e-4));
    CHECK(out.opacity.at(px, py) == doctest::Approx(sumWF / sumW).epsilon(2e-4));
    CHECK(out.opacity.at(px, py) < 1.0f);  // the miss counts in sum(w) only
}
