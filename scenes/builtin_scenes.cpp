#include "scenes/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/suggest.h"
#include "scenes/bunny_scene.h"
#include "scenes/failure_scenes.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"
#include "scenes/scene_names.h"

namespace ssrt {

using namespace helpers;

namespace {

// ---- cornell ---------------------------------------------------------------------------
// The box spans x in [-1.5, 1.5] (wider than tall, to fill a 16:9 frame), y in [0, 2],
// z in [-1, 1]; the front (+Z) and the top are open so that the directional light, which
// has no ceiling lamp to stand in for, reaches the floor.
constexpr float kHalfWidth = 1.5f, kHeight = 2.0f, kHalfDepth = 1.0f;

void addCornellWalls(Scene& scene) {
    const glm::vec3 white(0.73f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
    // Thin single quads: double-sided so that the shadow pass, which sees the walls from
    // the light's side, still finds them.
    const uint32_t floorMat = addMaterial(scene, "floor_glossy", white, 0.0f, 0.15f, true);
    const uint32_t whiteMat = addMaterial(scene, "wall_white", white, 0.0f, 0.9f, true);
    const uint32_t redMat = addMaterial(scene, "wall_red", red, 0.0f, 0.9f, true);
    const uint32_t greenMat = addMaterial(scene, "wall_green", green, 0.0f, 0.9f, true);
    // makeQuad faces +Y; rotations turn that front toward the inside of the box.
    const uint32_t wide = addMesh(scene, makeQuad({kHalfWidth, kHalfDepth}, 1));
    const uint32_t side = addMesh(scene, makeQuad({kHeight * 0.5f, kHalfDepth}, 1));
    const uint32_t back = addMesh(scene, makeQuad({kHalfWidth, kHeight * 0.5f}, 1));
    const float midY = kHeight * 0.5f;
    addInstance(scene, wide, floorMat, glm::mat4(1.0f));
    addInstance(scene, back, whiteMat,
                translate({0, midY, -kHalfDepth}) * rotate(90.0f, {1, 0, 0}));  // +Y -> +Z
    addInstance(scene, side, redMat,
                translate({-kHalfWidth, midY, 0}) * rotate(-90.0f, {0, 0, 1}));  // +Y -> +X
    addInstance(scene, side, greenMat,
                translate({kHalfWidth, midY, 0}) * rotate(90.0f, {0, 0, 1}));  // +Y -> -X
}

Scene makeCornell() {
    Scene scene;
    scene.name = "cornell";
    addCornellWalls(scene);
    const uint32_t boxMat = addMaterial(scene, "box_white", glm::vec3(0.73f), 0.0f, 0.6f);
    const uint32_t mirrorMat = addMaterial(scene, "mirror", glm::vec3(0.95f), 1.0f, 0.02f);
    const glm::vec3 tallHalf(0.3f, 0.65f, 0.3f);
    const uint32_t tall = addMesh(scene, makeBox(tallHalf));
    addInstance(scene, tall, boxMat,
                translate({-0.55f, tallHalf.y, -0.35f}) * rotate(15.0f, {0, 1, 0}));
    const float r = 0.35f;
    const uint32_t sphere = addMesh(scene, makeUvSphere(r, 64, 32));
    addInstance(scene, sphere, mirrorMat, translate({0.55f, r, 0.25f}));
    // From above, front and a little right: the box and sphere throw shadows back and to
    // the left across the floor; the green wall shades a strip of floor beside it.
    scene.light.direction = lightFrom(20.0f, 55.0f);
    // Close enough that at 16:9 the side walls reach past the frame's edges; a little above
    // the middle, looking down, so that the floor and its shadows show.
    setCamera(scene, makeCamera({0.0f, 1.15f, 3.2f}, {0.0f, 0.85f, 0.0f}, 40.0f));
    return scene;
}

// ---- spheres ---------------------------------------------------------------------------
Scene makeSpheres() {
    Scene scene;
    scene.name = "spheres";
    const uint32_t groundMat = addMaterial(scene, "ground", glm::vec3(0.5f), 0.0f, 0.2f);
    addInstance(scene, addMesh(scene, makeQuad({8.0f, 6.0f}, 1)), groundMat, glm::mat4(1.0f));
    const float r = 0.4f, spacing = 1.0f;
    const uint32_t sphere = addMesh(scene, makeUvSphere(r, 64, 32));
    constexpr int kCount = 6;  // roughness 0, 0.2, ..., 1
    // Dielectric row in front, metal row behind (the camera looks down over both).
    const struct {
        const char* name;
        glm::vec3 color;
        float metallic, z;
    } rows[] = {{"dielectric", {0.8f, 0.15f, 0.1f}, 0.0f, 0.6f},
                {"metal", {1.0f, 0.78f, 0.34f}, 1.0f, -0.6f}};
    for (const auto& row : rows) {
        for (int i = 0; i < kCount; ++i) {
            const float roughness = float(i) / float(kCount - 1);
            const std::string name = std::string(row.name) + "_r" + std::to_string(i);
            const uint32_t mat = addMaterial(scene, name, row.color, row.metallic, roughness);
            const float x = (float(i) - 0.5f * float(kCount - 1)) * spacing;
            addInstance(scene, sphere, mat, translate({x, r, row.z}));
        }
    }
    scene.light.direction = lightFrom(35.0f, 45.0f);
    setCamera(scene, makeCamera({0.0f, 2.4f, 5.5f}, {0.0f, 0.3f, 0.0f}, 40.0f));
    return scene;
}

}  // namespace

const std::vector<BuiltinSceneInfo>& builtinScenes() {
    static const std::vector<BuiltinSceneInfo> scenes = {
        {"cornell",
         "Cornell box, open front and no ceiling (so the sun reaches the floor): glossy floor, "
         "red/green walls, a tall box and a mirror sphere; reflections, color bleed, shadows"},
        {"spheres",
         "two rows of spheres, roughness 0 to 1, dielectric in front and metal behind, on a "
         "glossy ground; tests the GGX lobe across roughness"},
        {"thin", kThinDescription},
        {"corridor", kCorridorDescription},
        {"offscreen", kOffscreenDescription},
        {"occluded", kOccludedDescription},
        {"bunny", kBunnyDescription},
        {"fence", kFenceDescription},
    };
    return scenes;
}

Scene makeBuiltinScene(const std::string& name) {
    if (name == "cornell") return makeCornell();
    if (name == "spheres") return makeSpheres();
    if (name == "thin") return makeThinScene();
    if (name == "corridor") return makeCorridorScene();
    if (name == "offscreen") return makeOffscreenScene();
    if (name == "occluded") return makeOccludedScene();
    if (name == "bunny") return makeBunnyScene();
    if (name == "fence") return makeFenceScene();
    throw std::invalid_argument("unknown scene '" + name + "'" +
                                didYouMean(name, knownSceneNames()) +
                                " (built-in scenes: " + knownScenes() + ")");
}

Scene makeKnotScene(int triangles) {
    // The ground is 2 triangles; the knot gets the rest, 2 * segments * sides of them.
    // A (2, 3) knot's curve is about 8 times as long as its tube's girth, so segments =
    // 8 * sides keeps the triangles near square.
    constexpr int kMinTriangles = 2 + 2 * 8 * 3 * 3;
    if (triangles < kMinTriangles)
        throw std::invalid_argument("knot scene needs at least " + std::to_string(kMinTriangles) +
                                    " triangles (got " + std::to_string(triangles) + ")");
    const double cells = double(triangles - 2) / 2.0;
    const int sides = std::max(3, int(std::lround(std::sqrt(cells / 8.0))));
    const int segments = std::max(3, int(std::lround(cells / sides)));

    Scene scene;
    scene.name = "knot" + std::to_string(triangles);
    const uint32_t groundMat = addMaterial(scene, "ground", glm::vec3(0.5f), 0.0f, 0.3f);
    const uint32_t knotMat = addMaterial(scene, "knot", {0.9f, 0.6f, 0.2f}, 1.0f, 0.3f);
    addInstance(scene, addMesh(scene, makeQuad({5.0f, 5.0f}, 1)), groundMat, glm::mat4(1.0f));
    // radius 1, tube 0.3: the knot spans +-1.8 across and +-0.8 in height.
    const uint32_t knot = addMesh(scene, makeTorusKnot(2, 3, 1.0f, 0.3f, segments, sides));
    addInstance(scene, knot, knotMat, translate({0.0f, 1.1f, 0.0f}));  // floats: a clear shadow
    scene.light.direction = lightFrom(30.0f, 45.0f);
    setCamera(scene, makeCamera({0.0f, 2.4f, 3.4f}, {0.0f, 0.8f, 0.0f}, 45.0f));
    return scene;
}

}  // namespace ssrt
