// Direct light against simple answers: emission adds exactly, a surface facing away from the
// light gets none of it, and the background is the sky.
#include <doctest/doctest.h>

#include "renderer/renderer.h"

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
