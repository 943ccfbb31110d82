// The equirect sky in the direct-light pass: the background shows the image's texels, a white
// image lights like the constant white sky, the SH irradiance is the cosine convolution, and
// the prefiltered data is built once per image.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/rng.h"
#include "renderer/renderer.h"
#include "renderer/sky_lighting.h"
#include "scenes/builtin_scenes.h"
#include "shading/environment.h"
#include "shading/irradiance_sh.h"

using namespace ssrt;
using V3f = lanes::V3<float>;

namespace {

// Per-texel noise in [0.1, 4.1), different per channel: neighbours differ a lot, so a lookup
// that lands on the wrong texel shows.
std::shared_ptr<const SkyImage> noiseSky(int w, int h, uint32_t seed) {
    auto img = std::make_shared<SkyImage>();
    img->source = "noise";
    img->width = w;
    img->height = h;
    img->rgb.resize(std::size_t(3) * w * h);
    for (std::size_t i = 0; i < img->rgb.size(); ++i)
        img->rgb[i] = 0.1f + 4.0f * randomFloat(uint32_t(i), seed, 0, 0);
    return img;
}

std::shared_ptr<const SkyImage> filledSky(int w, int h, float (*radiance)(V3f, int)) {
    auto img = std::make_shared<SkyImage>();
    img->width = w;
    img->height = h;
    img->rgb.resize(std::size_t(3) * w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const V3f d = env::uvToDirection((x + 0.5f) / w, (y + 0.5f) / h);
            for (int c = 0; c < 3; ++c) img->rgb[(std::size_t(y) * w + x) * 3 + c] = radiance(d, c);
        }
    return img;
}

Scene emptyScene() {
    Scene s;
    s.materials.push_back(Material{});
    return s;
}

}  // namespace

TEST_CASE("sky image: a background pixel looking along a texel's direction shows that texel") {
    constexpr int kW = 32, kH = 16;
    Scene scene = emptyScene();
    scene.sky.kind = Sky::Kind::Image;
    scene.sky.image = noiseSky(kW, kH, 7);
    scene.sky.intensity = 1.5f;
    RenderSettings rs;
    rs.width = rs.height = 33;  // odd: the centre pixel's ray is the view direction
    rs.shadowMapSize = 16;
    rs.exposure = 2.0f;
    // (no structured binding: clang 14 cannot capture one in CAPTURE's lambda)
    for (const auto& at : {std::pair{20, 6}, std::pair{3, 9}, std::pair{31, 11}}) {
        const int tx = at.first, ty = at.second;
        CAPTURE(tx);
        CAPTURE(ty);
        const V3f d = env::uvToDirection((tx + 0.5f) / kW, (ty + 0.5f) / kH);
        scene.camera.position = glm::vec3(0.0f);
        scene.camera.target = glm::vec3(d.x, d.y, d.z);
        scene.camera.fovY = 20.0f;
        scene.previousCamera = scene.camera;
        const Frame f = Renderer(rs).renderWithoutHistory(scene);
        const float* texel = scene.sky.image->rgb.data() + (std::size_t(ty) * kW + tx) * 3;
        for (int c = 0; c < 3; ++c) {
            const float expected = texel[c] * 1.5f * 2.0f;
            // Bilinear tolerance: the ray misses the texel centre by rounding only
            CHECK(f.rgb(Res::Color)[c].at(16, 16) == doctest::Approx(expected).epsilon(2e-3));
        }
        // The scene model's own (nearest-texel) lookup agrees
        const glm::vec3 ref = scene.sky.radiance(scene.camera.target);
        CHECK(ref.r == doctest::Approx(texel[0] * 1.5f));
        CHECK(f.gbuffer.viewZ.at(16, 16) == 0.0f);  // it is background
    }
}

TEST_CASE("sky image: a white image lights like the constant white sky") {
    for (const char* name : {"spheres", "cornell"}) {
        CAPTURE(name);
        Scene constant = makeBuiltinScene(name);
        constant.sky.kind = Sky::Kind::Constant;
        constant.sky.zenith = glm::vec3(1.0f);
        constant.sky.intensity = 0.8f;
        Scene image = constant;
        auto white = std::make_shared<SkyImage>();
        white->width = 64;
        white->height = 32;
        white->rgb.assign(std::size_t(3) * 64 * 32, 1.0f);
        image.sky.kind = Sky::Kind::Image;
        image.sky.image = white;
        RenderSettings rs;
        rs.width = 160;
        rs.height = 90;
        rs.shadowMapSize = 256;
        const Frame a = Renderer(rs).renderWithoutHistory(constant),
                    b = Renderer(rs).renderWithoutHistory(image);
        double worst = 0.0, sum = 0.0;
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < a.height; ++y)
                for (int x = 0; x < a.width; ++x) {
                    const double va = a.rgb(Res::Color)[c].at(x, y),
                                 vb = b.rgb(Res::Color)[c].at(x, y);
                    worst = std::max(worst, std::fabs(va - vb) / std::max(va, 1e-3));
                    sum += va;
                }
        MESSAGE(std::string(name) << ": worst relative difference " << worst);
        CHECK(sum > 0.0);
        CHECK(worst < 2e-3);
    }
}

TEST_CASE("sky image: SH irradiance is the cosine convolution of the image") {
    // Radiance linear in the direction, a + b.d, has irradiance / pi = a + (2/3) b.n exactly
    // (bands 0 and 1); its nine coefficients must find that from the texels.
    const auto img = filledSky(128, 64, [](V3f d, int c) {
        const float b[3][3] = {{0.5f, 0.3f, -0.2f}, {-0.4f, 0.1f, 0.6f}, {0.0f, 0.9f, 0.0f}};
        return 1.0f + b[c][0] * d.x + b[c][1] * d.y + b[c][2] * d.z;
    });
    const ShIrradiance sh = projectIrradianceSh({img->rgb.data(), img->width, img->height});
    const float b[3][3] = {{0.5f, 0.3f, -0.2f}, {-0.4f, 0.1f, 0.6f}, {0.0f, 0.9f, 0.0f}};
    double worst = 0.0;
    for (int k = 0; k < 200; ++k) {
        const V3f n =
            lanes::normalize(V3f{randomFloat(k, 3, 0, 0) - 0.5f, randomFloat(k, 3, 0, 1) - 0.5f,
                                 randomFloat(k, 3, 0, 2) - 0.5f});
        const Rgb e = irradianceSh(sh, n);
        const float got[3] = {e.r, e.g, e.b};
        for (int c = 0; c < 3; ++c) {
            const double expected =
                1.0 + (2.0 / 3.0) * (b[c][0] * n.x + b[c][1] * n.y + b[c][2] * n.z);
            worst = std::max(worst, std::fabs(got[c] - expected));
        }
    }
    MESSAGE("SH irradiance of a linear sky: worst error " << worst);
    CHECK(worst < 2e-3);
    // Band 2: L = y^2 + 0.5 xz = 1/3 + (3y^2 - 1) / 3 + 0.5 xz, whose band-2 part the cosine
    // scales by 1/4: E / pi = 1/3 + (3 n.y^2 - 1) / 12 + 0.125 n.x n.z
    const auto quad = filledSky(128, 64, [](V3f d, int) { return d.y * d.y + 0.5f * d.x * d.z; });
    const ShIrradiance shQuad = projectIrradianceSh({quad->rgb.data(), 128, 64});
    double worstQuad = 0.0;
    for (int k = 0; k < 200; ++k) {
        const V3f n =
            lanes::normalize(V3f{randomFloat(k, 4, 0, 0) - 0.5f, randomFloat(k, 4, 0, 1) - 0.5f,
                                 randomFloat(k, 4, 0, 2) - 0.5f});
        const double expected = 1.0 / 3.0 + (3.0 * n.y * n.y - 1.0) / 12.0 + 0.125 * n.x * n.z;
        worstQuad = std::max(worstQuad, std::fabs(irradianceSh(shQuad, n).g - expected));
    }
    MESSAGE("SH irradiance of a quadratic sky: worst error " << worstQuad);
    CHECK(worstQuad < 2e-3);
    // A sky lit only from above: normals facing down see nothing, clamped to exactly 0 rather
    // than the ringing of nine terms below it
    const auto upper = filledSky(64, 32, [](V3f d, int) { return d.y > 0.0f ? 1.0f : 0.0f; });
    const ShIrradiance shUp = projectIrradianceSh({upper->rgb.data(), 64, 32});
    CHECK(irradianceSh(shUp, V3f{0.0f, 1.0f, 0.0f}).r == doctest::Approx(1.0).epsilon(0.1));
    CHECK(irradianceSh(shUp, V3f{0.0f, -1.0f, 0.0f}).r >= 0.0f);
    CHECK(irradianceSh(shUp, V3f{0.0f, -1.0f, 0.0f}).r < 0.05f);
}

TEST_CASE("sky image: prefiltered data is built once per image and dropped with it") {
    const int before = skyLightingCacheSize();
    auto a = noiseSky(16, 8, 1);
    auto copy = std::make_shared<const SkyImage>(*a);  // same pixels, another image
    bool built = false;
    const auto la = cachedSkyLighting(a, 1, &built);
    CHECK(built);
    const auto again = cachedSkyLighting(a, 2, &built);
    CHECK_FALSE(built);
    CHECK(again == la);
    const auto lc = cachedSkyLighting(copy, 1, &built);
    CHECK(built);
    CHECK(lc != la);
    CHECK(skyLightingCacheSize() == before + 2);
    a.reset();
    CHECK(skyLightingCacheSize() == before + 1);
    copy.reset();
    CHECK(skyLightingCacheSize() == before);
    // The levels: the image itself first, then smaller prefiltered ones
    REQUIRE(la->prefiltered.size() == std::size_t(kSkyLevels - 1));
    CHECK(la->prefiltered[0].width <= 16);
    // And through the renderer: two frames, one build, and the pass shows in the stats
    Scene scene = makeBuiltinScene("cornell");
    scene.sky.kind = Sky::Kind::Image;
    scene.sky.image = noiseSky(16, 8, 2);
    RenderSettings rs;
    rs.width = 32;
    rs.height = 16;
    rs.shadowMapSize = 32;
    Frame frame;
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), frame);
    CHECK(skyLightingCacheSize() == before + 1);
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), frame);
    CHECK(skyLightingCacheSize() == before + 1);
    cachedSkyLighting(scene.sky.image, 1, &built);
    CHECK_FALSE(built);
    CHECK(std::any_of(frame.stats.passes.begin(), frame.stats.passes.end(),
                      [](const PassTime& p) { return p.name == "environment"; }));
}

TEST_CASE("sky image: a scene with the image kind but no image is refused") {
    Scene scene = makeBuiltinScene("cornell");
    scene.sky.kind = Sky::Kind::Image;
    CHECK_THROWS_AS(scene.validate(), std::invalid_argument);
    auto broken = std::make_shared<SkyImage>();
    broken->width = 4;
    broken->height = 2;
    broken->rgb.resize(5);
    scene.sky.image = broken;
    CHECK_THROWS_AS(scene.validate(), std::invalid_argument);
}
