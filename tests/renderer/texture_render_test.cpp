// Textures in the G-buffer: a quad that fills the view shows its texture's texels at the
// pixels they cover (magnified, level 0), a fine checker seen from afar averages to grey
// (minified, through the mips), and the metallic-roughness texture lands in its planes.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "plane_compare.h"
#include "raster/resolve_kernel.h"
#include "renderer/renderer.h"
#include "screen_quad.h"

using namespace ssrt;

namespace {

constexpr int kTexels = 8;          // per side of the magnified texture
constexpr int kPixelsPerTexel = 9;  // odd, so a pixel centre falls on each texel centre
constexpr int kSize = kTexels * kPixelsPerTexel;
// The pixel whose centre is texel t's centre (along either axis).
constexpr int texelCentre(int t) { return t * kPixelsPerTexel + kPixelsPerTexel / 2; }

// A texel value that differs from every neighbour's by at least 1/8 in some channel.
glm::vec4 texel(int x, int y) {
    return {0.05f + x / 8.0f, 0.05f + y / 8.0f, 0.05f + float((3 * x + 5 * y) % 8) / 8.0f, 1.0f};
}

// The screen-filling quad (screen_quad.h), white metal.
Scene quadScene() {
    Material m;
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.roughness = 1.0f;
    return test::screenQuadScene(m);
}

Frame render(const Scene& scene, int size, Isa isa = Isa::Scalar) {
    RenderSettings rs;
    rs.width = rs.height = size;
    rs.shadowMapSize = 256;
    rs.threads = 2;
    rs.isa = isa;
    return Renderer(rs).renderWithoutHistory(scene);
}

}  // namespace

TEST_CASE("texture render: a magnified texture shows its texels at the pixels they cover") {
    Scene scene = quadScene();
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) texels.push_back(texel(x, y));
    scene.textures.emplace_back("colours", kTexels, kTexels, texels);
    scene.materials[0].baseColorTexture = 0;
    // Metallic-roughness from the same texels: roughness = G, metallic = B.
    scene.textures.emplace_back("mr", kTexels, kTexels, texels);
    scene.materials[0].metallicRoughnessTexture = 1;
    scene.materials[0].baseColor = glm::vec3(1.0f, 0.5f, 1.0f);  // the factor multiplies

    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        const Frame f = render(scene, kSize, isa);
        for (int ty = 0; ty < kTexels; ++ty)
            for (int tx = 0; tx < kTexels; ++tx) {
                CAPTURE(tx);
                CAPTURE(ty);
                const int px = texelCentre(tx);
                const int py = texelCentre(ty);
                const glm::vec4 t = texel(tx, ty);
                CHECK(f.gbuffer.albedo[0].at(px, py) == doctest::Approx(t.r).epsilon(1e-4));
                CHECK(f.gbuffer.albedo[1].at(px, py) == doctest::Approx(0.5 * t.g).epsilon(1e-4));
                CHECK(f.gbuffer.albedo[2].at(px, py) == doctest::Approx(t.b).epsilon(1e-4));
                CHECK(f.gbuffer.roughness.at(px, py) == doctest::Approx(t.g).epsilon(1e-4));
                CHECK(f.gbuffer.metallic.at(px, py) == doctest::Approx(t.b).epsilon(1e-4));
            }
    }
}

TEST_CASE("texture render: a minified checker averages to grey -- without a texture, the factor") {
    Scene scene = quadScene();
    // Nine texels per pixel: lod log2(9), between mip levels 3 and 4, both grey. Level 0
    // alone would read one black or white texel per pixel (centres coincide).
    constexpr int kChecker = 288, kImage = 32;
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kChecker; ++y)
        for (int x = 0; x < kChecker; ++x) texels.emplace_back(glm::vec4(float((x + y) % 2)));
    scene.textures.emplace_back("checker", kChecker, kChecker, texels);
    scene.materials[0].baseColorTexture = 0;
    const Frame f = render(scene, kImage);
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) {
            CAPTURE(x);
            CAPTURE(y);
            REQUIRE(f.gbuffer.albedo[0].at(x, y) == doctest::Approx(0.5).epsilon(1e-4));
        }

    scene.materials[0].baseColorTexture = -1;
    const Frame plain = render(scene, kImage);
    CHECK(plain.gbuffer.albedo[0].at(kImage / 2, kImage / 2) == 1.0f);
    CHECK(plain.gbuffer.roughness.at(kImage / 2, kImage / 2) == 1.0f);
}

namespace {

// The magnified quad with its base colour through `uv` and its metallic-roughness texture
// (the same texels) untransformed, checked at each screen texel's centre: albedo shows
// texel expected(tx, ty), roughness the untransformed texel (tx, ty).
template <class Expected>
void checkTransformed(const UvTransform& uv, Expected expected) {
    Scene scene = quadScene();
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) texels.push_back(texel(x, y));
    scene.textures.emplace_back("colours", kTexels, kTexels, texels);
    scene.materials[0].baseColorTexture = 0;
    scene.materials[0].baseColorUv = uv;
    scene.materials[0].metallicRoughnessTexture = 0;
    const Frame f = render(scene, kSize);
    for (int ty = 0; ty < kTexels; ++ty)
        for (int tx = 0; tx < kTexels; ++tx) {
            CAPTURE(tx);
            CAPTURE(ty);
            const int px = texelCentre(tx);
            const int py = texelCentre(ty);
            const glm::ivec2 e = expected(tx, ty);
            const glm::vec4 t = texel(e.x, e.y);
            CHECK(f.gbuffer.albedo[0].at(px, py) == doctest::Approx(t.r).epsilon(1e-4));
            CHECK(f.gbuffer.albedo[1].at(px, py) == doctest::Approx(t.g).epsilon(1e-4));
            CHECK(f.gbuffer.albedo[2].at(px, py) == doctest::Approx(t.b).epsilon(1e-4));
            CHECK(f.gbuffer.roughness.at(px, py) == doctest::Approx(texel(tx, ty).g).epsilon(1e-4));
        }
}

int wrap8(int i) { return ((i % kTexels) + kTexels) % kTexels; }

}  // namespace

// KHR_texture_transform, hand-computed: uv' = R S uv + offset with R = [cos sin; -sin cos]
// (rows), texels repeating. A screen texel (tx, ty) has uv = ((tx + 0.5) / 8, (ty + 0.5) / 8).
TEST_CASE("texture render: a UV transform moves the texels, per texture slot") {
    SUBCASE("rotation 90 degrees: uv' = (v, -u), texel (ty, 7 - tx)") {
        UvTransform t;
        t.row0 = {0.0f, 1.0f};
        t.row1 = {-1.0f, 0.0f};
        checkTransformed(t, [](int tx, int ty) { return glm::ivec2(ty, kTexels - 1 - tx); });
    }
    SUBCASE("scale 3 and offset (0.25, 0.5): texel (3 tx + 1 + 2, 3 ty + 1 + 4) mod 8") {
        UvTransform t;
        t.row0 = {3.0f, 0.0f};
        t.row1 = {0.0f, 3.0f};
        t.offset = {0.25f, 0.5f};
        checkTransformed(
            t, [](int tx, int ty) { return glm::ivec2(wrap8(3 * tx + 3), wrap8(3 * ty + 5)); });
    }
    SUBCASE("all three: uv' = (3 v + 0.25, -3 u + 0.5), texel (3 ty + 3, 2 - 3 tx) mod 8") {
        UvTransform t;
        t.row0 = {0.0f, 3.0f};
        t.row1 = {-3.0f, 0.0f};
        t.offset = {0.25f, 0.5f};
        checkTransformed(
            t, [](int tx, int ty) { return glm::ivec2(wrap8(3 * ty + 3), wrap8(2 - 3 * tx)); });
    }
}

TEST_CASE("texture render: a UV scale scales the derivatives, so the level of detail") {
    // One checker texel per pixel, centres on centres: level 0 reads black or white. Scaled
    // by 9, nine texels per pixel: grey from the mips (untransformed derivatives would read
    // level 0 at uv * 9, a texel centre again, black or white).
    constexpr int kChecker = 32;
    Scene scene = quadScene();
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kChecker; ++y)
        for (int x = 0; x < kChecker; ++x) texels.emplace_back(glm::vec4(float((x + y) % 2)));
    scene.textures.emplace_back("checker", kChecker, kChecker, texels);
    scene.materials[0].baseColorTexture = 0;
    const Frame plain = render(scene, kChecker);
    CHECK(plain.gbuffer.albedo[0].at(3, 4) == doctest::Approx(1.0).epsilon(1e-4));
    CHECK(plain.gbuffer.albedo[0].at(4, 4) == doctest::Approx(0.0).epsilon(1e-4));
    scene.materials[0].baseColorUv.row0 = {9.0f, 0.0f};
    scene.materials[0].baseColorUv.row1 = {0.0f, 9.0f};
    const Frame scaled = render(scene, kChecker);
    for (int y = 0; y < kChecker; ++y)
        for (int x = 0; x < kChecker; ++x) {
            CAPTURE(x);
            CAPTURE(y);
            REQUIRE(scaled.gbuffer.albedo[0].at(x, y) == doctest::Approx(0.5).epsilon(1e-4));
        }
}

TEST_CASE("texture render: a texture on the second UV set samples by it, on every ISA") {
    // Set 1 is set 0 transposed: the base colour (set 1) shows texel (ty, tx), the
    // metallic-roughness texture (set 0) texel (tx, ty).
    Scene scene = quadScene();
    scene.meshes[0].uvs1 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) texels.push_back(texel(x, y));
    scene.textures.emplace_back("colours", kTexels, kTexels, texels);
    scene.materials[0].baseColorTexture = 0;
    scene.materials[0].baseColorUv.set = 1;
    scene.materials[0].metallicRoughnessTexture = 0;
    const Frame ref = render(scene, kSize);
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        const Frame f = render(scene, kSize, isa);
        for (int ty = 0; ty < kTexels; ++ty)
            for (int tx = 0; tx < kTexels; ++tx) {
                CAPTURE(tx);
                CAPTURE(ty);
                const int px = texelCentre(tx);
                const int py = texelCentre(ty);
                const glm::vec4 t = texel(ty, tx);
                CHECK(f.gbuffer.albedo[0].at(px, py) == doctest::Approx(t.r).epsilon(1e-4));
                CHECK(f.gbuffer.albedo[1].at(px, py) == doctest::Approx(t.g).epsilon(1e-4));
                CHECK(f.gbuffer.albedo[2].at(px, py) == doctest::Approx(t.b).epsilon(1e-4));
                CHECK(f.gbuffer.roughness.at(px, py) ==
                      doctest::Approx(texel(tx, ty).g).epsilon(1e-4));
            }
        // The same bits as the scalar copy.
        for (int c = 0; c < 3; ++c)
            CHECK(test::sameBits(f.gbuffer.albedo[c], ref.gbuffer.albedo[c]));
        CHECK(test::sameBits(f.gbuffer.roughness, ref.gbuffer.roughness));
        for (int s = 0; s < kResolveUvSets; ++s)
            for (int i = 0; i < kResolveUvOutputs; ++i)
                CHECK(test::sameBits(f.scratch.uv[s][i], ref.scratch.uv[s][i]));
    }
    CHECK(ref.scratch.uv[1][kUvU].width() == kSize);
    // Without a texture on set 1, set 1 is neither resolved nor given planes.
    scene.materials[0].baseColorUv.set = 0;
    CHECK(render(scene, kSize).scratch.uv[1][kUvU].width() == 0);
}
