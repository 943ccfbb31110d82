// SSGI one bounce against analytic answers (a furnace-like frame where every hit sees the
// same direct light; all misses in a constant or gradient sky) and its contract on a
// rendered G-buffer: finite everywhere, the same bits on every ISA and thread count.
#include "trace/ssgi.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/lane_math.h"
#include "core/pixel_formats.h"
#include "core/rng.h"
#include "plane_compare.h"
#include "renderer/direct_lighting.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "shading/environment.h"
#include "thread_counts.h"

using namespace ssrt;

namespace {

constexpr int kW = 90, kH = 50;

using test::sameBits;

DirectArgs lighting(bool gradient) {
    DirectArgs a{};
    const float l[3] = {0.0f, 1.0f, 0.0f}, e[3] = {2.0f, 3.0f, 4.0f};
    std::copy_n(l, 3, a.toLight);
    std::copy_n(e, 3, a.lightRadiance);
    a.skyGradient = gradient;
    const float zen[3] = {0.3f, 0.4f, 0.5f}, hor[3] = {0.9f, 0.8f, 0.7f},
                gnd[3] = {0.1f, 0.05f, 0.02f};
    std::copy_n(zen, 3, a.skyZenith);
    std::copy_n(gradient ? hor : zen, 3, a.skyHorizon);
    std::copy_n(gradient ? gnd : zen, 3, a.skyGround);
    return a;
}

// The view of a G-buffer's planes that SSGI reads (null: absent), all of viewZ's size.
GBufferView ssgiView(const PlaneF& viewZ, const PlaneF normal[3], const PlaneF albedo[3],
                     const PlaneF& metallic) {
    return gbufferView("test", viewZ.width(), viewZ.height(),
                       {{kGViewZ, &viewZ},
                        {kGNormalX, normal ? &normal[0] : nullptr},
                        {kGNormalY, normal ? &normal[1] : nullptr},
                        {kGNormalZ, normal ? &normal[2] : nullptr},
                        {kGAlbedoR, &albedo[0]},
                        {kGAlbedoG, &albedo[1]},
                        {kGAlbedoB, &albedo[2]},
                        {kGMetallic, &metallic}});
}

// A uniform surface: normal +y (towards the light), one albedo and metallic, shadow 0.5,
// emission; every ray a hit at a random pixel.
struct Furnace {
    PlaneF viewZ{kW, kH, 5.0f};
    PlaneF normal[3] = {PlaneF(kW, kH, 0.0f), PlaneF(kW, kH, 1.0f), PlaneF(kW, kH, 0.0f)};
    PlaneF albedo[3] = {PlaneF(kW, kH, 0.5f), PlaneF(kW, kH, 0.6f), PlaneF(kW, kH, 0.7f)};
    PlaneF metallic{kW, kH, 0.2f};
    PlaneF shadow{kW, kH, 0.5f};
    PlaneF emission[3] = {PlaneF(kW, kH, 0.1f), PlaneF(kW, kH, 0.2f), PlaneF(kW, kH, 0.3f)};
    RayBatch rays;
    MarchResult march;
    DirectArgs light = lighting(false);
    SsgiArgs in;

    Furnace() {
        rays.ensureSize(kW, kH);
        march.ensureSize(kW, kH);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const uint32_t i = uint32_t(y * kW + x);
                rays.dx.at(x, y) = 0.0f;
                rays.dy.at(x, y) = 0.0f;
                rays.dz.at(x, y) = 1.0f;
                rays.pdf.at(x, y) = 0.5f;
                march.hit.at(x, y) = 1.0f;
                march.hitX.at(x, y) = float(kW) * randomFloat(i, 5, 0, 0);
                march.hitY.at(x, y) = float(kH) * randomFloat(i, 5, 0, 1);
                march.hitZ.at(x, y) = 5.0f;
            }
        in.camera.width = kW;
        in.camera.height = kH;
        in.g = ssgiView(viewZ, normal, albedo, metallic);
        for (int c = 0; c < 3; ++c) in.emission[c] = viewOf(emission[c], "emission");
        in.shadow = viewOf(shadow, "shadow");
        in.lighting = &light;
    }
};

// Random rays from most surface pixels and hits anywhere: the frame's edges and background
// pixels included.
void randomRaysAndHits(const PlaneF& viewZ, RayBatch& rays, MarchResult& march) {
    const int w = viewZ.width(), h = viewZ.height();
    rays.ensureSize(w, h);
    march.ensureSize(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint32_t i = uint32_t(y * w + x);
            const float u[5] = {randomFloat(i, 9, 0, 0), randomFloat(i, 9, 0, 1),
                                randomFloat(i, 9, 0, 2), randomFloat(i, 9, 0, 3),
                                randomFloat(i, 9, 0, 4)};
            const bool ray = viewZ.at(x, y) > 0.0f && u[0] > 0.1f;
            rays.pdf.at(x, y) = ray ? u[1] : 0.0f;
            const float dx = u[2] - 0.5f, dy = u[3] - 0.5f, dz = u[4] - 0.5f;
            const float len = std::sqrt(dx * dx + dy * dy + dz * dz);
            rays.dx.at(x, y) = ray ? dx / len : 0.0f;
            rays.dy.at(x, y) = ray ? dy / len : 0.0f;
            rays.dz.at(x, y) = ray ? dz / len : 0.0f;
            march.hit.at(x, y) = ray && u[4] < 0.6f ? 1.0f : 0.0f;
            march.hitX.at(x, y) = march.hit.at(x, y) > 0 ? float(w) * u[2] * 1.1f - 2.0f : 0.0f;
            march.hitY.at(x, y) = march.hit.at(x, y) > 0 ? float(h) * u[3] : 0.0f;
        }
}

// SSGI's G-buffer inputs (viewZ, normal, albedo, metallic, shadow) from a rendered frame.
void gbufferInputs(const Frame& frame, SsgiArgs& in) {
    in.g = frame.gbuffer.view();
    in.shadow = viewOf(frame.plane(Res::Shadow), "shadow");
}

}  // namespace

TEST_CASE("ssgi: every hit on a surface of known direct light gives that radiance") {
    Furnace f;
    const float albedo[3] = {0.5f, 0.6f, 0.7f}, e[3] = {2.0f, 3.0f, 4.0f},
                em[3] = {0.1f, 0.2f, 0.3f};
    PlaneF out[3];
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) {
                const double expect = albedo[c] * 0.8 / M_PI * e[c] * 0.5 + em[c];
                CHECK(out[c].at(x, y) == doctest::Approx(expect).epsilon(1e-6));
            }
    // Without emission planes: the sun's part alone; facing away from the light: emission only.
    f.in.emission[0] = f.in.emission[1] = f.in.emission[2] = {};
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2);
    CHECK(out[1].at(7, 7) == doctest::Approx(0.6 * 0.8 / M_PI * 3.0 * 0.5).epsilon(1e-6));
    f.normal[1].fill(-1.0f);
    f.in.emission[0] = viewOf(f.emission[0], "emission");
    f.in.emission[1] = viewOf(f.emission[1], "emission");
    f.in.emission[2] = viewOf(f.emission[2], "emission");
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2);
    CHECK(out[2].at(7, 7) == doctest::Approx(0.3f).epsilon(1e-6));
}

TEST_CASE("ssgi: every miss in a constant sky gives the sky -- a gradient sky by world direction") {
    Furnace f;
    f.march.hit.fill(0.0f);
    PlaneF out[3];
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) CHECK(out[c].at(x, y) == f.light.skyZenith[c]);
    // Gradient sky, camera turned so that view -z is world +y and view +z world -y: rays
    // along view -z see the zenith, along view +z the ground.
    f.light = lighting(true);
    const float rot[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};
    std::copy_n(rot, 9, f.in.camera.viewToWorld);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) f.rays.dz.at(x, y) = x % 2 ? -1.0f : 1.0f;
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2);
    for (int c = 0; c < 3; ++c) {
        CHECK(out[c].at(11, 3) == doctest::Approx(f.light.skyZenith[c]).epsilon(1e-6));
        CHECK(out[c].at(12, 3) == f.light.skyGround[c]);
    }
}

TEST_CASE("ssgi: samples average -- pixels without a ray add 0") {
    Furnace f;
    PlaneF out[3];
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 2, 2);  // hits
    const double lit = 0.5 * 0.8 / M_PI * 2.0 * 0.5 + 0.1;
    f.march.hit.fill(0.0f);
    f.rays.pdf.at(3, 4) = 0.0f;                                     // no ray on the second sample
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 1, 2, 2);  // misses: the sky
    CHECK(out[0].at(5, 5) == doctest::Approx((lit + 0.3) / 2).epsilon(1e-6));
    CHECK(out[0].at(3, 4) == doctest::Approx(lit / 2).epsilon(1e-6));
    CHECK_THROWS_AS(resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 2, 2, 2),
                    std::invalid_argument);
    f.in.shadow = viewOf(PlaneF(), "shadow");
    CHECK_THROWS_WITH_AS(resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2),
                         "resolveSsgi: shadow is missing", std::invalid_argument);
    // And the G-buffer planes it reads.
    f.in.shadow = viewOf(f.shadow, "shadow");
    CHECK_NOTHROW(resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2));
    f.in.g.normal[1] = nullptr;
    CHECK_THROWS_AS(resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2),
                    std::invalid_argument);
}

TEST_CASE("ssgi: a world hit lit at the hit gives its own light, on every ISA, in every tile") {
    // Mixed and world tracing's hidden hits (renderer/world_stage.h): their light replaces what
    // the hit pixel lends, whichever pixel the march result names; every other pixel keeps its
    // own answer. Over the frame (lit in row order), a chunk's lanes and tiles' edges included.
    Furnace f;
    PlaneF plain[3];
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, plain, 0, 1, 1);
    std::vector<WorldLit> lit;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if ((x * 7 + y * 3) % 11 == 0 || x == kW - 1)
                lit.push_back({x, y, {float(x), float(y), 9.0f}, {}});
    for (Isa isa : supportedIsas()) {
        const std::string isaStr(isaName(isa));
        CAPTURE(isaStr);
        PlaneF out[3];
        resolveSsgi(isa, f.in, f.rays, f.march, out, 0, 1, 2, lit);
        std::size_t next = 0;
        int replaced = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const bool isLit = next < lit.size() && lit[next].x == x && lit[next].y == y;
                for (int c = 0; c < 3; ++c) {
                    const float expect = isLit ? lit[next].radiance[c] : plain[c].at(x, y);
                    if (out[c].at(x, y) != expect) CHECK(out[c].at(x, y) == expect);
                }
                replaced += isLit;
                next += isLit;
            }
        CHECK(replaced == int(lit.size()));
    }
    // A tile given a hit outside it, or out of row order, is refused (not silently dropped).
    const SsgiResolver resolver(Isa::Scalar, f.in, plain, 0, 1);
    const std::vector<WorldLit> outside = {{kW - 1, kH - 1, {1.0f, 1.0f, 1.0f}, {}}};
    CHECK_THROWS_AS(resolver.tile(0, f.rays, f.march, outside), std::logic_error);
    const std::vector<WorldLit> backwards = {{5, 2, {}, {}}, {3, 2, {}, {}}};
    CHECK_THROWS_AS(resolver.tile(0, f.rays, f.march, backwards), std::logic_error);
}

TEST_CASE("ssgi: finite on a rendered frame, and the same bits on every ISA and thread count") {
    RenderSettings rs;
    rs.width = 133;
    rs.height = 77;
    rs.shadowMapSize = 128;
    rs.threads = 2;
    const Frame frame = Renderer(rs).renderWithoutHistory(makeBuiltinScene("cornell"));
    const int w = frame.width, h = frame.height;
    SsgiArgs in;
    in.camera.width = w;
    in.camera.height = h;
    const float rot[9] = {0.8f, 0.0f, -0.6f, 0.0f, 1.0f, 0.0f, 0.6f, 0.0f, 0.8f};
    std::copy_n(rot, 9, in.camera.viewToWorld);
    gbufferInputs(frame, in);
    const DirectArgs light = lighting(true);
    in.lighting = &light;
    RayBatch rays;
    MarchResult march;
    randomRaysAndHits(frame.gbuffer.viewZ, rays, march);
    PlaneF ref[3];
    for (int k = 0; k < 3; ++k) resolveSsgi(Isa::Scalar, in, rays, march, ref, k, 3, 1);
    bool finite = true;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) finite = finite && std::isfinite(ref[c].at(x, y));
    CHECK(finite);
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 2, 8})) {
            CAPTURE(isaName(isa));
            CAPTURE(threads);
            PlaneF out[3];
            for (int k = 0; k < 3; ++k) resolveSsgi(isa, in, rays, march, out, k, 3, threads);
            for (int c = 0; c < 3; ++c) CHECK(sameBits(out[c], ref[c]));
        }
}

TEST_CASE("ssgi: misses read the equirect sky image when there is one") {
    Furnace f;
    f.march.hit.fill(0.0f);
    // A uniform 8 x 4 image: every direction sees its colour times the intensity.
    EquirectImage img(8, 4, std::vector<float>(3 * 8 * 4, 0.0f));
    for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
        img.rgb[i] = 0.25f;
        img.rgb[i + 1] = 0.5f;
        img.rgb[i + 2] = 1.0f;
    }
    img.updatePoles();
    f.light.envLevelCount = 1;
    f.light.envLevel[0] = img.view();
    f.light.envIntensity = 2.0f;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {  // directions all around
            const uint32_t i = uint32_t(y * kW + x);
            const float dx = randomFloat(i, 4, 0, 0) - 0.5f, dy = randomFloat(i, 4, 0, 1) - 0.5f,
                        dz = randomFloat(i, 4, 0, 2) - 0.5f;
            const float len = std::sqrt(dx * dx + dy * dy + dz * dz);
            f.rays.dx.at(x, y) = dx / len;
            f.rays.dy.at(x, y) = dy / len;
            f.rays.dz.at(x, y) = dz / len;
        }
    PlaneF out[3];
    resolveSsgi(Isa::Scalar, f.in, f.rays, f.march, out, 0, 1, 2);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            CHECK(out[0].at(x, y) == doctest::Approx(0.5f).epsilon(1e-6));
            CHECK(out[2].at(x, y) == doctest::Approx(2.0f).epsilon(1e-6));
        }
}

// The direct pass's hit light is f16 (renderer/frame.h, DirectParts): a surface hit reads the
// G-buffer path's light rounded to nearest even, a miss the same sky.
TEST_CASE("ssgi: the direct pass's hit light gives the bits of the G-buffer path, f16 rounded") {
    for (const bool emits : {false, true}) {
        CAPTURE(emits);
        Scene scene = makeBuiltinScene("cornell");
        if (emits) scene.materials[0].emissive = glm::vec3(2.0f, 1.0f, 0.5f);
        RenderSettings rs;
        rs.width = 133;
        rs.height = 77;
        rs.shadowMapSize = 128;
        rs.threads = 2;
        Frame frame;
        Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), frame);
        DirectLighting dl;
        setDirectLighting(scene, rs, frame.scratch.shadow, nullptr, dl);
        REQUIRE(dl.args.anyEmissive == emits);
        SsgiArgs in;
        in.camera = frame.camera;
        gbufferInputs(frame, in);
        for (int c = 0; c < 3; ++c)
            if (emits) in.emission[c] = viewOf(frame.direct.emission[c], "emission");
        in.lighting = &dl.args;
        RayBatch rays;
        MarchResult march;
        randomRaysAndHits(frame.gbuffer.viewZ, rays, march);
        PlaneF ref[3];
        resolveSsgi(Isa::Scalar, in, rays, march, ref, 0, 1, 1);
        // Lit hits there are, so equal planes say something.
        int lit = 0;
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x)
                lit += march.hit.at(x, y) > 0.0f && ref[0].at(x, y) > 0.0f;
        CHECK(lit > 100);
        SsgiArgs fast = in;
        for (int c = 0; c < 3; ++c) {
            fast.hitLight[c] = viewOf(frame.direct.hitLight[c], "hitLight");
            fast.g.normal[c] = fast.g.albedo[c] = nullptr;
            fast.emission[c] = {};
        }
        fast.g.metallic = nullptr;
        fast.shadow = {};
        PlaneF first[3];
        int rounded = 0, other = 0;
        for (Isa isa : supportedIsas()) {
            CAPTURE(isaName(isa));
            PlaneF out[3];
            resolveSsgi(isa, fast, rays, march, out, 0, 1, 2);
            if (first[0].empty()) {
                for (int c = 0; c < 3; ++c) first[c] = out[c].clone();
                for (int c = 0; c < 3; ++c)
                    for (int y = 0; y < frame.height; ++y)
                        for (int x = 0; x < frame.width; ++x) {
                            const float r = ref[c].at(x, y), o = out[c].at(x, y);
                            const bool surface = march.hit.at(x, y) > 0.0f && r != o;
                            rounded += surface;
                            other += surface && o != decodeF16(encodeF16(r));
                        }
            }
            for (int c = 0; c < 3; ++c) CHECK(sameBits(out[c], first[c]));
        }
        CHECK(rounded > 100);
        CHECK(other == 0);
    }
}
