// The back-face depth layer (raster/back_depth.h) through the real passes: a closed box
// knows its far side, a one-sided wall and a one-sided card in front of the box know none.
#include <doctest/doctest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/renderer.h"
#include "scenes/mesh_builders.h"

namespace ssrt {

namespace {

// Camera at the origin looking down -Z; a box from z -4.5 to -5.5, a wall at z -10 and a card
// at z -3 over the box's right half, the wall and the card one-sided quads facing the camera.
Scene boxWallCard() {
    Scene s;
    s.meshes.push_back(makeBox(glm::vec3(0.5f)));
    s.meshes.push_back(makeQuad(glm::vec2(1.0f), 1));
    s.materials.push_back(Material{});
    const glm::mat4 facingCamera =
        glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    auto instance = [&](uint32_t mesh, const glm::mat4& m) {
        Instance inst;
        inst.mesh = mesh;
        inst.transform = inst.previousTransform = m;
        s.instances.push_back(inst);
    };
    instance(0, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -5.0f}));
    instance(1, glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, -10.0f}) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)) * facingCamera);
    instance(1, glm::translate(glm::mat4(1.0f), {0.45f, 0.0f, -3.0f}) *
                    glm::scale(glm::mat4(1.0f), glm::vec3(0.2f)) * facingCamera);
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    s.previousCamera = s.camera;
    return s;
}

RenderSettings small(bool backFaces) {
    RenderSettings rs;
    rs.width = rs.height = 64;
    rs.threads = 1;
    rs.trace.march.backFaces = backFaces;
    return rs;
}

}  // namespace

TEST_CASE("back-face depth: a box's far side, none behind one-sided surfaces") {
    const Scene scene = boxWallCard();
    const Frame f = Renderer(small(true)).renderWithoutHistory(scene);
    const PlaneF& viewZ = f.gbuffer.viewZ;
    const PlaneF& backZ = f.scratch.backZ;
    REQUIRE(backZ.width() == 64);
    REQUIRE(backZ.height() == 64);
    int box = 0, wall = 0, card = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float z = viewZ.at(x, y), back = backZ.at(x, y);
            if (std::abs(z - 4.5f) < 1e-3f) {
                // Through the front face, out through the back face or a side face.
                ++box;
                CHECK(back > 4.5f);
                CHECK(back <= 5.5f + 1e-4f);
            } else if (z > 9.0f) {
                ++wall;
                CHECK(back == 0.0f);  // a one-sided quad: nothing behind it is known
            } else if (std::abs(z - 3.0f) < 1e-3f) {
                ++card;
                CHECK(back == 0.0f);  // the box's back face is another instance's
            }
        }
    CHECK(box > 100);
    CHECK(wall > 1000);
    CHECK(card > 20);
    // The centre pixel's ray leaves through the back face, perpendicular to it.
    CHECK(backZ.at(28, 32) == doctest::Approx(5.5f).epsilon(1e-5));
}

TEST_CASE("back-face depth: no layer when the marchers do not use it") {
    const Frame f = Renderer(small(false)).renderWithoutHistory(boxWallCard());
    CHECK(f.scratch.backZ.empty());
    CHECK(f.scratch.backVisibility.depth.empty());
}

}  // namespace ssrt
