// Normal, occlusion and emissive textures in the pixels: a normal map tilting a quad's
// normals toward the sun brightens it and bends the G-buffer normal as glTF's tangent frame
// says (with the TANGENT attribute or generated tangents alike); an occlusion texture darkens
// the sky-lit part by its texel and leaves the sun-lit part alone; an emissive texture's
// light reaches a neighbouring floor through SSGI.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "plane_compare.h"
#include "renderer/renderer.h"
#include "screen_quad.h"

using namespace ssrt;
using test::sameBits;

namespace {

constexpr int kSize = 48;

// The screen-filling quad (screen_quad.h), a rough dielectric lit by the sun from the right
// (+x) and in front.
Scene quadScene() {
    Material m;
    m.baseColor = glm::vec3(0.8f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    Scene s = test::screenQuadScene(m);
    s.light.direction = glm::normalize(glm::vec3(-1.0f, 0.0f, -1.0f));  // towards -x, -z
    s.sky.kind = Sky::Kind::Constant;
    s.sky.zenith = glm::vec3(1.0f);
    s.sky.intensity = 0.3f;
    return s;
}

// One texel of value v everywhere (a 2x2 texture).
int32_t addConstantTexture(Scene& s, glm::vec4 v) {
    s.textures.emplace_back("constant", 2, 2, std::vector<glm::vec4>(4, v));
    return int32_t(s.textures.size() - 1);
}

Frame render(const Scene& scene, bool trace = false, int size = kSize, Isa isa = Isa::Scalar) {
    RenderSettings rs;
    rs.width = rs.height = size;
    rs.shadowMapSize = 256;
    rs.threads = 2;
    rs.isa = isa;
    rs.trace.ssr = rs.trace.ssgi = trace;
    return Renderer(rs).renderWithoutHistory(scene);
}

// The world x of pixel (x, y)'s surface through the frame's camera, as the wall's u.
float wallU(const Frame& f, int x, int y) {
    const float viewZ = f.gbuffer.viewZ.at(x, y);
    const float ndcX = (float(x) + 0.5f) * 2.0f / float(f.width) - 1.0f;
    const float ndcY = 1.0f - (float(y) + 0.5f) * 2.0f / float(f.height);
    const float* r = f.camera.viewToWorld;
    const glm::vec3 d(ndcX * f.camera.tanHalfX, ndcY * f.camera.tanHalfY, -1.0f);
    const float worldX = f.camera.position[0] + (r[0] * d.x + r[3] * d.y + r[6] * d.z) * viewZ;
    return worldX / 4.0f + 0.5f;
}

glm::vec3 normalAt(const Frame& f, int x, int y) {
    return {f.gbuffer.normal[0].at(x, y), f.gbuffer.normal[1].at(x, y),
            f.gbuffer.normal[2].at(x, y)};
}

void closeTo(glm::vec3 a, glm::vec3 b, double eps = 1e-5) {
    for (int c = 0; c < 3; ++c) CHECK(a[c] == doctest::Approx(b[c]).epsilon(eps));
}

}  // namespace

TEST_CASE("normal map: tilting the normals toward the sun brightens the quad as n.l says") {
    Scene flat = quadScene();
    Scene tilted = flat;
    // (0.85, 0.5, 1): tangent-space (0.7, 0, 1) leans along +u, which is +x, toward the sun.
    tilted.materials[0].normalTexture = addConstantTexture(tilted, {0.85f, 0.5f, 1.0f, 1.0f});
    const Frame f0 = render(flat), f1 = render(tilted);
    const glm::vec3 expected = glm::normalize(glm::vec3(0.7f, 0.0f, 1.0f));
    const int c = kSize / 2;
    closeTo(normalAt(f0, c, c), {0, 0, 1});
    closeTo(normalAt(f1, c, c), expected);
    // The sun's Lambert term grows from n.l = cos 45 to expected . l: direct light brightens by
    // about that ratio (the sky term is the same constant sky either way, but irradiance of a
    // constant sky does not depend on the normal).
    const glm::vec3 l = -flat.light.direction;
    CHECK(glm::dot(expected, l) > glm::dot(glm::vec3(0, 0, 1), l) + 0.1f);
    for (int y = 4; y < kSize; y += 8)
        for (int x = 4; x < kSize; x += 8) {
            CAPTURE(x);
            CAPTURE(y);
            CHECK(f1.rgb(Res::Color)[0].at(x, y) > f0.rgb(Res::Color)[0].at(x, y) * 1.1f);
        }

    SUBCASE("+Y of the map leans up the image (glTF: along -v), scale multiplies X and Y") {
        Scene up = flat;
        up.materials[0].normalTexture = addConstantTexture(up, {0.5f, 0.85f, 1.0f, 1.0f});
        up.materials[0].normalScale = 0.5f;
        closeTo(normalAt(render(up), c, c), glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)));
    }
    SUBCASE("the TANGENT attribute and generated tangents agree on a plain UV quad") {
        Scene attr = tilted;
        attr.meshes[0].tangents.assign(4, glm::vec4(1, 0, 0, 1));
        CHECK(sameBits(render(attr).gbuffer.normal[0], f1.gbuffer.normal[0]));
        // A tangent that says otherwise turns the tilt with it: along -y (w irrelevant to X).
        attr.meshes[0].tangents.assign(4, glm::vec4(0, -1, 0, 1));
        closeTo(normalAt(render(attr), c, c), glm::normalize(glm::vec3(0.0f, -0.7f, 1.0f)));
    }
    SUBCASE("seen from behind (double-sided), the whole frame turns over with the normal") {
        Scene back = tilted;
        back.materials[0].doubleSided = true;
        back.camera.position = {0, 0, -4};
        back.camera.target = {0, 0, 0};
        back.previousCamera = back.camera;
        // The quad is seen from -z: the pixel at image x shows world x mirrored.
        const Frame fb = render(back);
        closeTo(normalAt(fb, kSize - 1 - c, c), -expected);
    }
}

TEST_CASE("normal map: every ISA gives the same bits, and no normal map no tangent planes") {
    Scene s = quadScene();
    std::vector<glm::vec4> texels;
    for (int i = 0; i < 64; ++i)
        texels.emplace_back(0.2f + 0.6f * float(i % 8) / 7.0f, 0.8f - 0.6f * float(i / 8) / 7.0f,
                            0.9f, 1.0f);
    s.textures.emplace_back("bumps", 8, 8, texels);
    s.materials[0].normalTexture = 0;
    const Frame ref = render(s, true);
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        const Frame f = render(s, true, kSize, isa);
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(sameBits(f.gbuffer.normal[ch], ref.gbuffer.normal[ch]));
            CHECK(sameBits(f.rgb(Res::Color)[ch], ref.rgb(Res::Color)[ch]));
        }
    }
    CHECK(!ref.scratch.tangent[0].empty());
    CHECK(ref.gbuffer.emission[0].empty());  // no emissive texture: no emission plane
    CHECK(ref.gbuffer.occlusion.empty());
    CHECK(render(quadScene(), true).scratch.tangent[0].empty());
}

TEST_CASE("occlusion texture: the sky-lit part darkens by the texel, the sun-lit part does not") {
    // Left half of the texture R = 0.2, right half R = 1; strength 0.75 gives 0.4 and 1.
    Scene plain = quadScene();
    plain.materials[0].roughness = 0.5f;  // some sky specular too
    Scene occluded = plain;
    std::vector<glm::vec4> texels;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) texels.emplace_back(x < 2 ? 0.2f : 1.0f, 0.0f, 0.0f, 1.0f);
    occluded.textures.emplace_back("ao", 4, 2, texels);
    occluded.materials[0].occlusionTexture = 0;
    occluded.materials[0].occlusionStrength = 0.75f;
    const float darkAo = 1.0f + 0.75f * (0.2f - 1.0f);
    const int left = kSize / 8, right = kSize - 1 - kSize / 8, y = kSize / 2;
    for (bool trace : {false, true}) {
        CAPTURE(trace);
        // Sky only: every term is indirect, so the whole colour scales by the occlusion.
        Scene skyPlain = plain, skyOcc = occluded;
        skyPlain.light.intensity = skyOcc.light.intensity = 0.0f;
        const Frame a = render(skyPlain, trace), b = render(skyOcc, trace);
        CHECK(b.gbuffer.occlusion.at(left, y) == doctest::Approx(darkAo));
        CHECK(b.gbuffer.occlusion.at(right, y) == 1.0f);
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(a.rgb(Res::Color)[ch].at(left, y) > 0.01f);
            CHECK(b.rgb(Res::Color)[ch].at(left, y) ==
                  doctest::Approx(darkAo * a.rgb(Res::Color)[ch].at(left, y)).epsilon(1e-5));
            CHECK(b.rgb(Res::Color)[ch].at(right, y) ==
                  doctest::Approx(a.rgb(Res::Color)[ch].at(right, y)).epsilon(1e-6));
        }
        // Sun only (a black sky): occlusion changes nothing.
        Scene sunPlain = plain, sunOcc = occluded;
        sunPlain.sky.intensity = sunOcc.sky.intensity = 0.0f;
        const Frame c = render(sunPlain, trace), d = render(sunOcc, trace);
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(c.rgb(Res::Color)[ch].at(left, y) > 0.01f);
            CHECK(d.rgb(Res::Color)[ch].at(left, y) == c.rgb(Res::Color)[ch].at(left, y));
        }
    }
}

TEST_CASE("emissive texture: its light reaches a neighbouring floor through SSGI") {
    // A floor (y = 0) and a wall behind it (z = -1) whose emissive texture is bright on its
    // left half and black on the right; no sun, black sky: the floor's only light is SSGI's
    // from the wall, more in front of the bright half.
    Scene s;
    Mesh floor;
    floor.positions = {{-2, 0, -1}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -1}};
    floor.normals.assign(4, {0, 1, 0});
    floor.indices = {0, 1, 2, 0, 2, 3};
    Mesh wall;
    wall.positions = {{-2, 2, -1}, {-2, 0, -1}, {2, 0, -1}, {2, 2, -1}};
    wall.normals.assign(4, {0, 0, 1});
    wall.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    wall.indices = {0, 1, 2, 0, 2, 3};
    s.meshes = {floor, wall};
    Material floorMat;
    floorMat.baseColor = glm::vec3(0.8f);
    floorMat.roughness = 1.0f;
    Material wallMat = floorMat;
    wallMat.baseColor = glm::vec3(0.0f);
    wallMat.emissive = glm::vec3(4.0f);
    std::vector<glm::vec4> texels;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            texels.push_back(x < 2 ? glm::vec4(1.0f, 0.5f, 0.25f, 1.0f) : glm::vec4(0.0f));
    s.textures.emplace_back("glow", 4, 2, texels);
    s.textures[0].wrapU = TextureWrap::ClampToEdge;  // u = 0 does not blend in the black end
    wallMat.emissiveTexture = 0;
    s.materials = {floorMat, wallMat};
    s.instances = {Instance{0, 0}, Instance{1, 1}};
    s.camera.position = {0, 1.2f, 2.5f};
    s.camera.target = {0, 0.6f, 0};
    s.camera.fovY = 60.0f;
    s.previousCamera = s.camera;
    s.light.intensity = 0.0f;
    s.sky.kind = Sky::Kind::Constant;
    s.sky.intensity = 0.0f;
    RenderSettings rs;
    rs.width = 96;
    rs.height = 64;
    rs.shadowMapSize = 256;
    rs.threads = 2;
    rs.trace.ssr = false;
    rs.trace.ssgiSpp = 8;
    // The light itself, not the denoiser's spread of it across the floor (tests/denoise/).
    rs.trace.denoise.enabled = false;
    const Frame f = Renderer(rs).renderWithoutHistory(s);
    // The wall's pixels carry factor x texel: (4, 2, 1) on the left, 0 on the right.
    double floorLeft = 0.0, floorRight = 0.0;
    int wallLeft = 0, wallRight = 0, floorPixels = 0;
    for (int y = 0; y < rs.height; ++y)
        for (int x = 0; x < rs.width; ++x) {
            const float id = f.gbuffer.materialId.at(x, y);
            const float e = f.gbuffer.emission[0].at(x, y);
            // (Texel centres at u = 0.125, 0.375, ...: u below 0.375 reads the bright pair
            // alone, above 0.625 the black pair; the wall's u is the world x / 4 + 0.5.)
            const float u = wallU(f, x, y);
            if (id == 1.0f && u < 0.35f) {
                ++wallLeft;
                CHECK(e == doctest::Approx(4.0f).epsilon(1e-6));
                CHECK(f.gbuffer.emission[1].at(x, y) == doctest::Approx(2.0f).epsilon(1e-6));
            } else if (id == 1.0f && u > 0.65f) {
                ++wallRight;
                CHECK(e == 0.0f);
            } else if (id == 0.0f) {
                ++floorPixels;
                CHECK(e == 0.0f);
                const double c = f.rgb(Res::Color)[0].at(x, y);
                (x < rs.width / 2 ? floorLeft : floorRight) += c;
            }
        }
    REQUIRE(wallLeft > 100);
    REQUIRE(wallRight > 100);
    REQUIRE(floorPixels > 500);
    MESSAGE("floor light, left half " << floorLeft << ", right half " << floorRight);
    CHECK(floorLeft > 0.0);
    CHECK(floorLeft > 2.0 * floorRight);

    // The same wall with a black texture lights nothing.
    s.textures[0] = Texture("black", 2, 2, std::vector<glm::vec4>(4, glm::vec4(0.0f)));
    const Frame dark = Renderer(rs).renderWithoutHistory(s);
    for (int y = 0; y < rs.height; ++y)
        for (int x = 0; x < rs.width; ++x)
            if (dark.gbuffer.materialId.at(x, y) == 0.0f)
                REQUIRE(dark.rgb(Res::Color)[0].at(x, y) == 0.0f);
}
