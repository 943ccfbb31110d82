// Alpha cut-outs (glTF alphaMode MASK, and BLEND drawn as MASK) in the rasterizer: a quad with
// a checkerboard of holes before a red wall shows the wall through its holes and itself at its
// solid texels (the visibility pass); over a floor it lets the sun through under its holes
// only (the shadow map); the cutoff's boundary (alpha >= cutoff is drawn); a MASK material
// without a texture (its factor alone); BLEND as MASK; the UV transform; and alpha ignored
// where the mode is OPAQUE.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "renderer/renderer.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"
#include "screen_quad.h"

using namespace ssrt;
using namespace ssrt::helpers;

namespace {

constexpr int kTexels = 8;          // per side of the checker
constexpr int kPixelsPerTexel = 9;  // odd: no pixel centre lies on a texel edge
constexpr int kSize = kTexels * kPixelsPerTexel;
const glm::vec3 kGreen(0.0f, 1.0f, 0.0f), kRed(1.0f, 0.0f, 0.0f);

// Texel (x, y) is solid (alpha 1) where x + y is even, a hole (alpha 0) elsewhere; green.
bool solid(int x, int y) { return (x + y) % 2 == 0; }

Texture checker(float solidAlpha = 1.0f, float holeAlpha = 0.0f) {
    std::vector<glm::vec4> texels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x)
            texels.emplace_back(kGreen, solid(x, y) ? solidAlpha : holeAlpha);
    return Texture("checker", kTexels, kTexels, texels);
}

// A quad at z = -2 that fills the 90-degree view of a camera at the origin looking down -Z
// (screen_quad.h), material 0: white, MASK, the checker;
// a red wall at z = -4 behind it, material 1.
Scene cutOutScene() {
    Scene s;
    const Mesh quad = test::screenQuadMesh();
    Mesh wall = quad;
    for (glm::vec3& p : wall.positions) p = {p.x * 3.0f, p.y * 3.0f, -4.0f};
    s.meshes = {quad, wall};
    s.textures.push_back(checker());
    const uint32_t cut = addMaterial(s, "cut-out", glm::vec3(1.0f), 0.0f, 1.0f);
    s.materials[cut].alphaMode = Material::AlphaMode::Mask;
    s.materials[cut].baseColorTexture = 0;
    const uint32_t red = addMaterial(s, "wall", kRed, 0.0f, 1.0f);
    addInstance(s, 0, cut, glm::mat4(1.0f));
    addInstance(s, 1, red, glm::mat4(1.0f));
    s.camera = makeCamera({0, 0, 0}, {0, 0, -1}, 90.0f);
    s.previousCamera = s.camera;
    return s;
}

Frame render(const Scene& scene, int size, Isa isa = Isa::Scalar, int threads = 2) {
    RenderSettings rs;
    rs.width = rs.height = size;
    rs.shadowMapSize = 512;
    rs.threads = threads;
    rs.isa = isa;
    rs.trace.ssr = rs.trace.ssgi = false;
    return Renderer(rs).renderWithoutHistory(scene);
}

// Every pixel shows the quad (material 0, green) where `quadAt(tx, ty)` for the texel under
// its centre, else the wall (material 1, red). Returns the pixels that do not.
template <class QuadAt>
int wrongPixels(const Frame& f, QuadAt quadAt) {
    int wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool quad = quadAt(x / kPixelsPerTexel, y / kPixelsPerTexel);
            const glm::vec3 albedo(f.gbuffer.albedo[0].at(x, y), f.gbuffer.albedo[1].at(x, y),
                                   f.gbuffer.albedo[2].at(x, y));
            const bool ok = f.gbuffer.materialId.at(x, y) == (quad ? 0.0f : 1.0f) &&
                            albedo == (quad ? kGreen : kRed);
            wrong += !ok;
        }
    return wrong;
}

constexpr auto kEverywhere = [](int, int) { return true; };
constexpr auto kNowhere = [](int, int) { return false; };

}  // namespace

TEST_CASE("alpha cut-out: the holes show the wall, the solid texels the quad, on every ISA") {
    const Scene scene = cutOutScene();
    for (Isa isa : supportedIsas())
        for (int threads : {1, 3}) {
            CAPTURE(isaName(isa));
            CAPTURE(threads);
            const Frame f = render(scene, kSize, isa, threads);
            CHECK(wrongPixels(f, solid) == 0);
            // Both quad triangles went through the alpha test, which cut out the holes' half.
            CHECK(f.stats.visibility.trianglesMasked == 2);
            CHECK(f.stats.visibility.pixelsCutOut == uint64_t(kSize * kSize / 2));
        }
}

TEST_CASE("alpha cut-out: OPAQUE ignores alpha, and opaque triangles skip the test") {
    Scene scene = cutOutScene();
    scene.materials[0].alphaMode = Material::AlphaMode::Opaque;
    const Frame f = render(scene, kSize);
    CHECK(wrongPixels(f, kEverywhere) == 0);
    CHECK(f.stats.visibility.trianglesMasked == 0);
    CHECK(f.stats.visibility.pixelsCutOut == 0);
    CHECK(f.stats.shadow.trianglesMasked == 0);
}

TEST_CASE("alpha cut-out: BLEND is drawn as MASK, to the bit") {
    Scene scene = cutOutScene();
    const Frame mask = render(scene, kSize);
    scene.materials[0].alphaMode = Material::AlphaMode::Blend;
    const Frame blend = render(scene, kSize);
    CHECK(wrongPixels(blend, solid) == 0);
    const auto a = mask.layers(), b = blend.layers();
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        CAPTURE(a[i].name);
        CHECK(hashPlane(*a[i].plane) == hashPlane(*b[i].plane));
    }
}

TEST_CASE("alpha cut-out: alpha equal to the cutoff is drawn, just below it is cut out") {
    const float above = std::nextafter(0.5f, 1.0f);
    SUBCASE("textured: the texel's alpha against the cutoff, per pixel") {
        Scene scene = cutOutScene();
        scene.textures[0] = checker(0.5f, 0.5f);  // every texel alpha 0.5
        CHECK(wrongPixels(render(scene, kSize), kEverywhere) == 0);
        scene.materials[0].alphaCutoff = above;
        const Frame cut = render(scene, kSize);
        CHECK(wrongPixels(cut, kNowhere) == 0);
        CHECK(cut.stats.visibility.pixelsCutOut == uint64_t(kSize * kSize));
    }
    SUBCASE("the factor multiplies the texel") {
        Scene scene = cutOutScene();
        // Alpha 0.5 at the solid texels' centres, 0 at the holes': half of it at the edges.
        scene.materials[0].baseColorAlpha = 0.5f;
        scene.materials[0].alphaCutoff = 0.25f;
        CHECK(wrongPixels(render(scene, kSize), solid) == 0);
        scene.materials[0].alphaCutoff = above;
        CHECK(wrongPixels(render(scene, kSize), kNowhere) == 0);
    }
    SUBCASE("without a texture: the factor alone, the triangles whole or not at all") {
        Scene scene = cutOutScene();
        scene.materials[0].baseColorTexture = -1;
        scene.materials[0].baseColor = kGreen;
        scene.materials[0].baseColorAlpha = 0.5f;
        const Frame drawn = render(scene, kSize);
        CHECK(wrongPixels(drawn, kEverywhere) == 0);
        CHECK(drawn.stats.visibility.trianglesMasked == 0);  // no per-pixel work
        CHECK(drawn.stats.visibility.trianglesCutOut == 0);
        scene.materials[0].alphaCutoff = above;
        const Frame gone = render(scene, kSize);
        CHECK(wrongPixels(gone, kNowhere) == 0);
        CHECK(gone.stats.visibility.trianglesCutOut == 2);
        CHECK(gone.stats.shadow.trianglesCutOut == 2);
        CHECK(gone.stats.visibility.trianglesSetUp == 2);  // the wall's
    }
}

TEST_CASE("alpha cut-out: the alpha is read through the base colour's UV transform") {
    Scene scene = cutOutScene();
    // One texel to the right: texel (x, y) of the quad reads texel (x + 1, y), whose parity
    // is the other one.
    scene.materials[0].baseColorUv.offset = {1.0f / kTexels, 0.0f};
    CHECK(wrongPixels(render(scene, kSize), [](int x, int y) { return !solid(x, y); }) == 0);
    // The second UV set, the first transposed: texel (x, y) reads (y, x), the same parity.
    scene.materials[0].baseColorUv = UvTransform{};
    scene.materials[0].baseColorUv.set = 1;
    for (const glm::vec2& uv : scene.meshes[0].uvs) scene.meshes[0].uvs1.emplace_back(uv.y, uv.x);
    scene.materials[0].baseColorUv.offset = {1.0f / kTexels, 0.0f};  // (y + 1, x)
    CHECK(wrongPixels(render(scene, kSize), [](int x, int y) { return !solid(y, x); }) == 0);
}

namespace {

// The floor under a cut-out roof: a white floor (y = 0, 4 x 4) and the checker roof (y = 1,
// 2 x 2, UV u along +X and v along +Z, texels a quarter unit) under a sun straight down; the
// camera between them at y = 0.8 looking down (right = +X, image down = +Z), so the roof is
// behind it and only its shadow is seen.
Scene roofScene() {
    Scene s;
    s.textures.push_back(checker());
    const uint32_t white = addMaterial(s, "floor", glm::vec3(1.0f), 0.0f, 1.0f);
    const uint32_t cut = addMaterial(s, "roof", glm::vec3(1.0f), 0.0f, 1.0f, true);
    s.materials[cut].alphaMode = Material::AlphaMode::Mask;
    s.materials[cut].baseColorTexture = 0;
    addInstance(s, addMesh(s, makeQuad({2.0f, 2.0f}, 1)), white, glm::mat4(1.0f));
    addInstance(s, addMesh(s, makeQuad({1.0f, 1.0f}, 1)), cut, translate({0, 1, 0}));
    s.light.direction = {0, -1, 0};
    s.camera = makeCamera({0, 0.8f, 0}, {0, 0, 0}, 90.0f);
    s.camera.up = {0, 0, -1};
    s.previousCamera = s.camera;
    return s;
}

// The pixel whose centre is nearest the floor point (x, 0, z), for roofScene()'s camera.
glm::ivec2 floorPixel(float x, float z, int size) {
    return {int(std::floor((x / 0.8f + 1.0f) * 0.5f * float(size))),
            int(std::floor((z / 0.8f + 1.0f) * 0.5f * float(size)))};
}

}  // namespace

TEST_CASE("alpha cut-out: the sun through the cut-out lights the floor under the holes only") {
    constexpr int kImage = 128;
    Scene scene = roofScene();
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        const Frame f = render(scene, kImage, isa);
        CHECK(f.stats.shadow.trianglesMasked == 2);
        CHECK(f.stats.shadow.pixelsCutOut > 0);
        // Under the centre of every roof texel in view (texels 1 to 6 of 8 along each axis).
        for (int j = 1; j < kTexels - 1; ++j)
            for (int i = 1; i < kTexels - 1; ++i) {
                CAPTURE(i);
                CAPTURE(j);
                const glm::ivec2 p =
                    floorPixel((i + 0.5f) / 4.0f - 1.0f, (j + 0.5f) / 4.0f - 1.0f, kImage);
                CHECK(f.plane(Res::Shadow).at(p.x, p.y) == (solid(i, j) ? 0.0f : 1.0f));
            }
    }
    // An opaque roof shadows all of it.
    scene.materials[1].alphaMode = Material::AlphaMode::Opaque;
    const Frame opaque = render(scene, kImage);
    for (int y = 0; y < kImage; ++y)
        for (int x = 0; x < kImage; ++x) REQUIRE(opaque.plane(Res::Shadow).at(x, y) == 0.0f);
}

TEST_CASE("alpha cut-out: a non-finite alpha or cutoff is refused, not drawn as nothing") {
    Scene scene = cutOutScene();
    CHECK_NOTHROW(scene.validate());
    scene.materials[0].alphaCutoff = std::nanf("");
    CHECK_THROWS_AS(scene.validate(), std::invalid_argument);
    CHECK_THROWS_AS(render(scene, 8), std::invalid_argument);
    scene.materials[0].alphaCutoff = 0.5f;
    scene.materials[0].baseColorAlpha = INFINITY;
    CHECK_THROWS_AS(scene.validate(), std::invalid_argument);
}
