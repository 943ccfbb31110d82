// Direct light against simple answers: emission adds exactly, a surface facing away from the
// light gets none of it, and the background is the sky.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "core/tiles.h"
#include "plane_compare.h"
#include "renderer/direct_lighting.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "shading/direct_kernel.h"

using namespace ssrt;

namespace {

// A wall facing +z at z = -4, seen head-on by a camera at the origin.
Scene wallScene(const Material& m, glm::vec3 lightDir) {
    Scene s;
    Mesh mesh;
    mesh.positions = {{-50, -50, -4}, {50, -50, -4}, {50, 50, -4}, {-50, 50, -4}};
    mesh.normals.assign(4, {0, 0, 1});
    mesh.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(mesh);
    s.materials.push_back(m);
    s.instances.push_back(Instance{});
    s.light.direction = lightDir;
    s.camera.position = {0, 0, 0};
    s.camera.target = {0, 0, -1};
    s.previousCamera = s.camera;
    return s;
}

RenderSettings tiny() {
    RenderSettings rs;
    rs.width = 64;
    rs.height = 48;
    rs.shadowMapSize = 64;
    return rs;
}

}  // namespace

TEST_CASE("emission adds to the lit colour exactly") {
    Material plain;
    Material glowing = plain;
    glowing.emissive = {2.0f, 0.0f, 0.5f};
    const glm::vec3 light = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
    const Frame a = Renderer(tiny()).renderWithoutHistory(wallScene(plain, light));
    const Frame b = Renderer(tiny()).renderWithoutHistory(wallScene(glowing, light));
    CHECK(b.rgb(Res::Color)[0].at(30, 20) - a.rgb(Res::Color)[0].at(30, 20) ==
          doctest::Approx(2.0f).epsilon(1e-5));
    CHECK(b.rgb(Res::Color)[1].at(30, 20) == a.rgb(Res::Color)[1].at(30, 20));
    CHECK(b.rgb(Res::Color)[2].at(30, 20) - a.rgb(Res::Color)[2].at(30, 20) ==
          doctest::Approx(0.5f).epsilon(1e-5));
}

TEST_CASE("a surface facing away from the light gets only sky light") {
    Material m;
    const Frame lit = Renderer(tiny()).renderWithoutHistory(wallScene(m, {0.0f, 0.0f, -1.0f}));
    const Frame unlit = Renderer(tiny()).renderWithoutHistory(wallScene(m, {0.0f, 0.0f, 1.0f}));
    CHECK(lit.plane(Res::Shadow).at(30, 20) == 1.0f);
    CHECK(unlit.plane(Res::Shadow).at(30, 20) == 0.0f);
    CHECK(unlit.rgb(Res::Color)[0].at(30, 20) < lit.rgb(Res::Color)[0].at(30, 20));
    CHECK(unlit.rgb(Res::Color)[0].at(30, 20) > 0.0f);  // the sky term
}

// The shadow map's block bounds only let pixels skip taps whose answer they prove: a frame
// shaded with them and without is the same bits. IfTheyPay makes them for a frame with at least
// a quarter as many pixels as the map has texels.
TEST_CASE("direct light: the same bits with the shadow map's bounds and without") {
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings rs;
    rs.width = 96;
    rs.height = 54;
    rs.shadowMapSize = 512;
    rs.threads = 2;
    const Frame frame = Renderer(rs).renderWithoutHistory(scene);
    const auto shade = [&](ShadowBoundsUse use) {
        DirectLighting lighting;
        setDirectLighting(scene, rs, frame.scratch.shadow, nullptr, lighting, use);
        DirectArgs& a = lighting.args;
        CHECK((a.shadowBounds != nullptr) == (use == ShadowBoundsUse::Always));
        setDirectGBuffer(frame.gbuffer, a);
        const TileGrid grid(frame.width, frame.height);
        a.width = frame.width;
        a.height = frame.height;
        a.tilesX = grid.tilesX;
        a.tanHalfX = frame.camera.tanHalfX;
        a.tanHalfY = frame.camera.tanHalfY;
        std::copy_n(frame.camera.viewToWorld, 9, a.viewToWorld);
        std::copy_n(frame.camera.position, 3, a.camPos);
        std::vector<PlaneF> out(4);
        for (PlaneF& p : out) p.ensureSize(frame.width, frame.height);
        for (int c = 0; c < 3; ++c) a.color[c] = out[c].row(0);
        a.shadow = out[3].row(0);
        a.outStride = out[0].stride();
        const auto kernel = SSRT_DISPATCH(supportedIsas().back(), shadeTile);
        for (int t = 0; t < grid.count(); ++t) kernel(a, t);
        return out;
    };
    const std::vector<PlaneF> with = shade(ShadowBoundsUse::Always);
    const std::vector<PlaneF> without = shade(ShadowBoundsUse::Never);
    for (int p = 0; p < 4; ++p) CHECK(test::sameBits(with[p], without[p]));
    int shadowed = 0, lit = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            shadowed += with[3].at(x, y) == 0.0f;
            lit += with[3].at(x, y) == 1.0f;
        }
    CHECK(shadowed > 0);  // (a frame with both lit and shadowed pixels; a wrong "lit" from
    CHECK(lit > 0);       // the bounds was seen to fail the check above)
    // The rule: a quarter as many pixels as texels.
    CHECK(shadowBoundsPay(1920, 1080, 2048));
    CHECK(!shadowBoundsPay(1280, 720, 2048));
    CHECK(shadowBoundsPay(1024, 1024, 2048));
    CHECK(!shadowBoundsPay(1023, 1024, 2048));
}
