// Textures (scenes/texture.h): the mip chain averages, lookups hit texel centres, wrap modes
// pick the texels glTF says, the level of detail follows the footprint, minification
// averages a checker to grey, and sRGB decoding matches the standard.
#include "scenes/texture.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/color.h"

using ssrt::Texture;
using ssrt::TextureWrap;

namespace {

// Texel (x, y) of a w x h texture whose every texel differs: R = x, G = y, B = x * y, A = 1.
Texture ramp(int w, int h) {
    std::vector<glm::vec4> t;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t.emplace_back(float(x), float(y), float(x * y), 1.0f);
    return Texture("ramp", w, h, t);
}

Texture checker(int n) {
    std::vector<glm::vec4> t;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) t.emplace_back(glm::vec4(float((x + y) % 2)));
    return Texture("checker", n, n, t);
}

glm::vec2 centre(int x, int y, int w, int h) { return {(x + 0.5f) / w, (y + 0.5f) / h}; }

}  // namespace

TEST_CASE("texture: the mip chain halves down to 1x1 and each level averages the one above") {
    const Texture t = ramp(8, 4);
    REQUIRE(t.levels.size() == 4);
    CHECK(t.levels[1].width == 4);
    CHECK(t.levels[1].height == 2);
    CHECK(t.levels[3].width == 1);
    CHECK(t.levels[3].height == 1);
    // Level 1 texel (1, 1) averages level-0 texels x in {2, 3}, y in {2, 3}.
    const glm::vec4 l1 = t.levels[1].at(1, 1);
    CHECK(l1.r == 2.5f);
    CHECK(l1.g == 2.5f);
    CHECK(l1.b == (4.0f + 6.0f + 6.0f + 9.0f) / 4.0f);
    // The last level is the mean of every texel (power-of-two sizes).
    const glm::vec4 last = t.levels.back().at(0, 0);
    CHECK(last.r == 3.5f);
    CHECK(last.g == 1.5f);
    CHECK(last.b == doctest::Approx(3.5 * 1.5));

    SUBCASE("odd sizes fold the last row and column in, so no texel is dropped") {
        const Texture odd = ramp(3, 3);
        REQUIRE(odd.levels.size() == 2);
        CHECK(odd.levels[1].at(0, 0).r == doctest::Approx(1.0));
        CHECK(odd.levels[1].at(0, 0).b == doctest::Approx(1.0));  // mean of x * y over 0..2
        const Texture wide = ramp(5, 1);
        REQUIRE(wide.levels.size() == 3);
        CHECK(wide.levels[1].width == 2);
        CHECK(wide.levels[1].at(1, 0).r == doctest::Approx(3.0));  // texels 2, 3, 4
    }
}

TEST_CASE("texture: bilinear lookups return texels at their centres and blend between them") {
    const Texture t = ramp(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            const glm::vec4 v = t.sampleLevel(0, centre(x, y, 8, 4));
            CHECK(v.r == float(x));
            CHECK(v.g == float(y));
        }
    // Half-way between texels 2 and 3 of row 1.
    const glm::vec4 mid = t.sampleLevel(0, {3.0f / 8.0f, 1.5f / 4.0f});
    CHECK(mid.r == doctest::Approx(2.5));
    CHECK(mid.g == doctest::Approx(1.0));
    // UV (0, 0) is the top-left corner: row 0 is at v = 0.
    CHECK(t.sampleLevel(0, {0.5f / 8, 0.5f / 4}).g == 0.0f);
}

TEST_CASE("texture: wrap modes pick the texels glTF's samplers name") {
    Texture t = ramp(4, 1);
    struct Case {
        TextureWrap mode;
        int texel, expect;
    };
    const Case cases[] = {
        {TextureWrap::Repeat, -1, 3},         {TextureWrap::Repeat, 4, 0},
        {TextureWrap::Repeat, 5, 1},          {TextureWrap::Repeat, -6, 2},
        {TextureWrap::ClampToEdge, -1, 0},    {TextureWrap::ClampToEdge, 4, 3},
        {TextureWrap::ClampToEdge, 9, 3},     {TextureWrap::MirroredRepeat, -1, 0},
        {TextureWrap::MirroredRepeat, -2, 1}, {TextureWrap::MirroredRepeat, 4, 3},
        {TextureWrap::MirroredRepeat, 5, 2},  {TextureWrap::MirroredRepeat, 8, 0},
    };
    for (const Case& c : cases) {
        CAPTURE(int(c.mode));
        CAPTURE(c.texel);
        t.wrapU = c.mode;
        CHECK(t.sampleLevel(0, {(c.texel + 0.5f) / 4.0f, 0.5f}).r == float(c.expect));
    }
    // Vertical wrap is its own setting.
    Texture tall = ramp(1, 4);
    tall.wrapV = TextureWrap::ClampToEdge;
    CHECK(tall.sampleLevel(0, {0.5f, 1.9f}).g == 3.0f);
    tall.wrapV = TextureWrap::Repeat;
    CHECK(tall.sampleLevel(0, {0.5f, 1.0f + 0.5f / 4}).g == 0.0f);
}

TEST_CASE("texture: the level of detail is log2 of the larger footprint in texels") {
    const Texture t = ramp(64, 32);
    CHECK(t.lod({1.0f / 64, 0}, {0, 1.0f / 32}) == doctest::Approx(0.0).epsilon(1e-5));
    CHECK(t.lod({4.0f / 64, 0}, {0, 1.0f / 32}) == doctest::Approx(2.0).epsilon(1e-5));
    CHECK(t.lod({0, 0}, {0, 8.0f / 32}) == doctest::Approx(3.0).epsilon(1e-5));
    CHECK(t.lod({3.0f / 64, 4.0f / 32}, {0, 0}) == doctest::Approx(std::log2(5.0)).epsilon(1e-5));
    CHECK(t.lod({0.25f / 64, 0}, {0, 0}) == doctest::Approx(-2.0).epsilon(1e-5));
    // Degenerate derivatives never give NaN: zero and NaN read level 0, infinite the last.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    CHECK(t.lod({0, 0}, {0, 0}) == 0.0f);
    CHECK(t.lod({nan, 0}, {0, nan}) == 0.0f);
    CHECK(t.lod({inf, 0}, {0, 0}) >= float(t.levels.size() - 1));
    for (glm::vec2 uv : {glm::vec2(nan, 0.5f), glm::vec2(inf, -inf), glm::vec2(1e30f, -1e30f)}) {
        const glm::vec4 v = t.sample(uv, {inf, nan}, {nan, 0});
        CHECK(std::isfinite(v.r));
        CHECK(std::isfinite(v.g));
    }
}

TEST_CASE("texture: minification averages a checker to grey -- magnification keeps its texels") {
    const Texture t = checker(64);
    // Sixteen texels per pixel: level 4, whose texels each average a 16x16 block.
    for (float u : {0.1f, 0.37f, 0.5f, 0.93f}) {
        const glm::vec4 v = t.sample({u, 0.41f}, {16.0f / 64, 0}, {0, 16.0f / 64});
        CHECK(v.r == doctest::Approx(0.5).epsilon(1e-6));
    }
    // Between levels, the blend of two grey levels is still grey.
    CHECK(t.sample({0.3f, 0.6f}, {24.0f / 64, 0}, {0, 0}).r == doctest::Approx(0.5).epsilon(1e-6));
    // A footprint of one texel or less reads level 0: black and white texels survive.
    for (int x : {0, 1, 17, 40})
        CHECK(t.sample(centre(x, 3, 64, 64), {0.5f / 64, 0}, {0, 0.5f / 64}).r ==
              float((x + 3) % 2));
}

TEST_CASE("texture: sRGB decoding follows IEC 61966-2-1") {
    CHECK(ssrt::srgbToLinear(0.0f) == 0.0f);
    CHECK(ssrt::srgbToLinear(1.0f) == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(ssrt::srgbToLinear(0.04f) == doctest::Approx(0.04 / 12.92).epsilon(1e-6));
    CHECK(ssrt::srgbToLinear(0.5f) == doctest::Approx(0.21404114).epsilon(1e-5));
    float previous = -1.0f;
    for (int i = 0; i <= 255; ++i) {
        const float v = ssrt::srgbToLinear(float(i) / 255.0f);
        const double expected =
            i / 255.0 <= 0.04045 ? i / 255.0 / 12.92 : std::pow((i / 255.0 + 0.055) / 1.055, 2.4);
        CHECK(v == doctest::Approx(expected).epsilon(2e-6));
        CHECK(v > previous);
        previous = v;
    }
    CHECK(ssrt::srgbToLinear(std::numeric_limits<float>::quiet_NaN()) == 0.0f);
}

TEST_CASE("texture: bad sizes and texels are refused") {
    CHECK_THROWS_AS(Texture("t", 0, 4, {}), std::invalid_argument);
    CHECK_THROWS_AS(Texture("t", 2, 2, std::vector<glm::vec4>(3)), std::invalid_argument);
    std::vector<glm::vec4> texels(4, glm::vec4(1.0f));
    texels[2].g = std::numeric_limits<float>::infinity();
    CHECK_THROWS_AS(Texture("t", 2, 2, texels), std::invalid_argument);
}
