#include "scenes/failure_scenes.h"

#include <string>

#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"

namespace ssrt {

using namespace helpers;

namespace {

// The mirror of DESIGN.md's scenes: a metal, as smooth as a floor can be polished.
uint32_t addMirror(Scene& scene, const std::string& name, bool doubleSided = false) {
    return addMaterial(scene, name, glm::vec3(0.95f), 1.0f, 0.02f, doubleSided);
}

// Saturated colours, so that a reflection that lands on the wrong object shows at a glance.
constexpr glm::vec3 kPalette[] = {{0.9f, 0.1f, 0.1f},  {0.1f, 0.8f, 0.15f},   {0.15f, 0.3f, 0.95f},
                                  {0.95f, 0.8f, 0.1f}, {0.85f, 0.15f, 0.85f}, {0.1f, 0.8f, 0.85f}};

// A walled strip along -Z: floor, two side walls, a wall across the far end; the near end
// and the top are open (the camera stands in the first, the sun comes through the second).
struct Corridor {
    float halfWidth, height, length;
};

void addCorridorShell(Scene& scene, const Corridor& c) {
    const float halfLength = 0.5f * c.length, midY = 0.5f * c.height;
    const uint32_t floorMat =
        addMaterial(scene, "corridor_floor", glm::vec3(0.6f), 0.0f, 0.1f, true);
    const uint32_t wallMat =
        addMaterial(scene, "corridor_wall", {0.75f, 0.72f, 0.65f}, 0.0f, 0.25f, true);
    const uint32_t endMat =
        addMaterial(scene, "corridor_end", {0.7f, 0.75f, 0.8f}, 0.0f, 0.4f, true);
    // Subdivided along the length so that no triangle spans most of the depth range.
    const uint32_t floorMesh = addMesh(scene, makeQuad({c.halfWidth, halfLength}, 8));
    const uint32_t wallMesh = addMesh(scene, makeQuad({midY, halfLength}, 8));
    const uint32_t endMesh = addMesh(scene, makeQuad({c.halfWidth, midY}, 1));
    addInstance(scene, floorMesh, floorMat, translate({0, 0, -halfLength}));
    addInstance(scene, wallMesh, wallMat,
                translate({-c.halfWidth, midY, -halfLength}) * rotate(-90.0f, {0, 0, 1}));  // +X
    addInstance(scene, wallMesh, wallMat,
                translate({c.halfWidth, midY, -halfLength}) * rotate(90.0f, {0, 0, 1}));  // -X
    addInstance(scene, endMesh, endMat,
                translate({0, midY, -c.length}) * rotate(90.0f, {1, 0, 0}));  // faces +Z
}

}  // namespace

// ---- thin ------------------------------------------------------------------------------
// Slabs 10 cm wide but only millimetres to centimetres deep, in a diagonal row so that none
// hides another: a screen-space march that assumes some depth thickness behind each pixel
// finds hits behind them that are not there (or, with no thickness, misses them).
Scene makeThinScene() {
    Scene scene;
    scene.name = "thin";
    const uint32_t floorMat = addMirror(scene, "mirror_floor");
    addInstance(scene, addMesh(scene, makeQuad({4.0f, 6.0f}, 4)), floorMat,
                translate({0, 0, -2.0f}));
    const float depths[] = {0.003f, 0.006f, 0.012f, 0.02f, 0.03f, 0.05f};
    const float height = 1.0f, width = 0.1f;
    for (int i = 0; i < 6; ++i) {
        const glm::vec3 half(0.5f * width, 0.5f * height, 0.5f * depths[i]);
        const uint32_t mat =
            addMaterial(scene, "post_" + std::to_string(i), kPalette[i], 0.0f, 0.5f);
        const glm::vec3 at(-1.5f + 0.6f * float(i), half.y, -0.5f * float(i));
        addInstance(scene, addMesh(scene, makeBox(half)), mat, translate(at));
    }
    scene.light.direction = lightFrom(30.0f, 40.0f);
    // Low (35 cm) and nearly level: the slabs and their whole mirror images both fit.
    setCamera(scene, makeCamera({0.0f, 0.35f, 4.5f}, {0.0f, 0.0f, -1.0f}, 40.0f));
    return scene;
}

// ---- fence -----------------------------------------------------------------------------
// Poles 2.5 cm square every 15 cm and two 1 cm wires, 1.5 m before a saturated wall, on a
// mirror floor, seen from 4.5 m: at 320x180 a pole is about 1.4 pixels wide and a wire about
// half a pixel high. A march that strides past a pixel steps over them (their reflections
// missed, the wall's light leaking through), and the relative thickness guess (3 % of about
// 4.5 m: 13 cm) makes a pole 2.5 cm deep catch rays that pass behind it.
Scene makeFenceScene() {
    Scene scene;
    scene.name = "fence";
    const uint32_t floorMat = addMirror(scene, "mirror_floor");
    addInstance(scene, addMesh(scene, makeQuad({4.0f, 4.0f}, 4)), floorMat,
                translate({0, 0, -1.0f}));
    const uint32_t wallMat = addMaterial(scene, "fence_wall", kPalette[2], 0.0f, 0.6f);
    addInstance(scene, addMesh(scene, makeQuad({3.0f, 1.0f}, 2)), wallMat,
                translate({0, 1.0f, -2.5f}) * rotate(90.0f, {1, 0, 0}));  // faces +Z
    const uint32_t poleMat = addMaterial(scene, "fence_pole", kPalette[3], 0.0f, 0.5f);
    const uint32_t wireMat = addMaterial(scene, "fence_wire", kPalette[0], 0.0f, 0.5f);
    const float poleHalf = 0.0125f, poleHeight = 1.2f, spacing = 0.15f;
    const int poles = 17;  // 2.4 m of fence, centred
    const uint32_t pole = addMesh(scene, makeBox({poleHalf, 0.5f * poleHeight, poleHalf}));
    for (int i = 0; i < poles; ++i)
        addInstance(scene, pole, poleMat,
                    translate({spacing * float(i - poles / 2), 0.5f * poleHeight, -1.0f}));
    const uint32_t wire = addMesh(scene, makeBox({0.5f * spacing * float(poles), 0.005f, 0.005f}));
    for (float y : {0.45f, 0.95f}) addInstance(scene, wire, wireMat, translate({0, y, -1.0f}));
    scene.light.direction = lightFrom(20.0f, 45.0f);
    // Low (50 cm) and level: the fence and its mirror image both in view.
    setCamera(scene, makeCamera({0.0f, 0.5f, 3.5f}, {0.0f, 0.35f, -1.0f}, 40.0f));
    return scene;
}

// ---- corridor --------------------------------------------------------------------------
// 30 m by 3 m with 3 m walls and no ceiling (else the directional light could not enter).
// Seen along its axis: the floor and walls are met at grazing angles, and a reflection of
// the far end needs a ray that crosses most of the screen's depth range.
Scene makeCorridorScene() {
    Scene scene;
    scene.name = "corridor";
    const Corridor c{1.5f, 3.0f, 30.0f};
    addCorridorShell(scene, c);
    const float r = 0.35f;
    const uint32_t sphere = addMesh(scene, makeUvSphere(r, 48, 24));
    const uint32_t box = addMesh(scene, makeBox({0.3f, 0.6f, 0.3f}));
    // Alternate sides, clear of the middle so the far end stays visible down the axis.
    for (int i = 0; i < 6; ++i) {
        const float z = -4.0f - 4.5f * float(i), x = (i % 2 == 0 ? -0.85f : 0.85f);
        const bool metal = i % 3 == 2;
        const uint32_t mat = addMaterial(scene, "object_" + std::to_string(i), kPalette[i],
                                         metal ? 1.0f : 0.0f, metal ? 0.2f : 0.5f);
        if (i % 2 == 0) addInstance(scene, sphere, mat, translate({x, r, z}));
        else addInstance(scene, box, mat, translate({x, 0.6f, z}));
    }
    // High and nearly along the axis, a little from +X: the sun reaches the floor and
    // lights the left wall, while the right wall throws a narrow shadow.
    scene.light.direction = lightFrom(15.0f, 60.0f);
    setCamera(scene, makeCamera({0.0f, 1.6f, -0.5f}, {0.0f, 1.2f, -29.0f}, 50.0f));
    return scene;
}

// ---- offscreen -------------------------------------------------------------------------
// The camera (1 m high) looks 10 degrees down with a 40 degree field: the top edge is 10
// degrees above the horizon and the bottom 30 below. Emitters 3.2 m up and 9 m ahead sit
// about 12 degrees up (out of view) while their mirror images sit about 28 degrees down
// (in view): every reflection of them needs a ray that leaves the screen.
Scene makeOffscreenScene() {
    Scene scene;
    scene.name = "offscreen";
    const uint32_t floorMat = addMirror(scene, "mirror_floor");
    addInstance(scene, addMesh(scene, makeQuad({6.0f, 7.0f}, 4)), floorMat,
                translate({0, 0, -1.0f}));
    const float r = 0.35f;
    const uint32_t sphere = addMesh(scene, makeUvSphere(r, 48, 24));
    for (int i = 0; i < 5; ++i) {
        const uint32_t mat =
            addMaterial(scene, "lamp_" + std::to_string(i), kPalette[i], 0.0f, 0.5f);
        scene.materials[mat].emissive = 6.0f * kPalette[i];
        addInstance(scene, sphere, mat, translate({-2.0f + float(i), 3.2f, -4.0f}));
    }
    // Something in view to judge the reflections against.
    const uint32_t propMat = addMaterial(scene, "prop", glm::vec3(0.7f), 0.0f, 0.5f);
    addInstance(scene, addMesh(scene, makeBox({0.4f, 0.4f, 0.4f})), propMat,
                translate({-1.2f, 0.4f, -1.0f}));
    addInstance(scene, sphere, propMat, translate({1.2f, r, -0.5f}));
    scene.light.direction = lightFrom(-30.0f, 50.0f);
    // tan(10 deg) * 5.67 m = 1 m: the target on the floor puts the view axis 10 deg down.
    setCamera(scene, makeCamera({0.0f, 1.0f, 5.0f}, {0.0f, 0.0f, -0.67f}, 40.0f));
    return scene;
}

// ---- occluded --------------------------------------------------------------------------
// Seen from above (x right, z toward the camera): the camera at z = 6 looks down -Z; a box
// at z = 1.5 hides a sphere at z = -1; a mirror wall at x = 1.6 facing -X sees the sphere's
// right side and shows it to the camera at about z = 2.5, a path that passes the box on
// both legs. No pixel holds the sphere, so a screen-space reflection has nothing to find.
Scene makeOccludedScene() {
    Scene scene;
    scene.name = "occluded";
    const uint32_t floorMat = addMaterial(scene, "floor", glm::vec3(0.5f), 0.0f, 0.6f);
    addInstance(scene, addMesh(scene, makeQuad({3.0f, 6.0f}, 2)), floorMat,
                translate({0, 0, 0.5f}));
    // Double-sided: the sun comes from its back, and the shadow pass must still find it.
    const uint32_t mirrorMat = addMirror(scene, "mirror_wall", true);
    const float wallHalfHeight = 1.25f;
    addInstance(scene, addMesh(scene, makeQuad({wallHalfHeight, 4.0f}, 1)), mirrorMat,
                translate({1.6f, wallHalfHeight, 0.0f}) * rotate(90.0f, {0, 0, 1}));  // -X
    const glm::vec3 boxHalf(0.55f, 0.7f, 0.3f);
    const uint32_t occluderMat = addMaterial(scene, "occluder", {0.3f, 0.4f, 0.6f}, 0.0f, 0.7f);
    addInstance(scene, addMesh(scene, makeBox(boxHalf)), occluderMat,
                translate({0.0f, boxHalf.y, 1.5f}));
    const float r = 0.45f;
    const uint32_t hiddenMat = addMaterial(scene, "hidden", {0.95f, 0.45f, 0.05f}, 0.0f, 0.4f);
    addInstance(scene, addMesh(scene, makeUvSphere(r, 48, 24)), hiddenMat,
                translate({0.0f, r, -1.0f}));
    // From the front right, high: the sphere's side that faces the mirror is lit.
    scene.light.direction = lightFrom(20.0f, 60.0f);
    setCamera(scene, makeCamera({0.0f, 1.4f, 6.0f}, {0.6f, 0.6f, -1.0f}, 45.0f));
    return scene;
}

}  // namespace ssrt
