// The failure-mode scenes (thin, fence, corridor, offscreen, occluded): each renders cleanly, and
// each is built so that its failure mode is really there (checked by projecting bounds and
// reading the G-buffer, not by looking at pictures).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

constexpr int kWidth = 128, kHeight = 72;
constexpr float kAspect = float(kWidth) / float(kHeight);
const char* const kFailureScenes[] = {"thin", "fence", "corridor", "offscreen", "occluded"};

using Corners = std::array<glm::vec3, 8>;

Frame renderSmall(const Scene& scene) {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.shadowMapSize = 512;
    return Renderer(settings).renderWithoutHistory(scene);
}

// Instances whose material's name starts with `prefix`, in scene order.
std::vector<uint32_t> instancesOf(const Scene& scene, const std::string& prefix) {
    std::vector<uint32_t> found;
    for (uint32_t i = 0; i < scene.instances.size(); ++i)
        if (scene.materials[scene.instances[i].material].name.rfind(prefix, 0) == 0)
            found.push_back(i);
    return found;
}

uint32_t onlyInstanceOf(const Scene& scene, const std::string& name) {
    const std::vector<uint32_t> found = instancesOf(scene, name);
    REQUIRE(found.size() == 1);
    return found[0];
}

// The corners of an instance's world-space bounding box.
Corners worldCorners(const Scene& scene, uint32_t instance) {
    const Instance& inst = scene.instances[instance];
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : scene.meshes[inst.mesh].positions) {
        const glm::vec3 w = glm::vec3(inst.transform * glm::vec4(p, 1.0f));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    Corners c;
    for (int i = 0; i < 8; ++i)
        c[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    return c;
}

glm::vec3 centre(const Corners& c) { return 0.5f * (c[0] + c[7]); }
glm::vec3 extent(const Corners& c) { return c[7] - c[0]; }

// Mirror images about the plane where coordinate `axis` equals `at`.
glm::vec3 mirrored(glm::vec3 p, int axis, float at) {
    p[axis] = 2.0f * at - p[axis];
    return p;
}
Corners mirrored(Corners c, int axis, float at) {
    for (glm::vec3& p : c) p = mirrored(p, axis, at);
    return c;
}

glm::vec4 toClip(const Camera& camera, glm::vec3 p) {
    return camera.projection(kAspect) * camera.view() * glm::vec4(p, 1.0f);
}

bool inView(const Camera& camera, glm::vec3 p) {
    const glm::vec4 c = toClip(camera, p);
    return c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w;
}

bool allInView(const Camera& camera, const Corners& corners) {
    for (const glm::vec3& p : corners)
        if (!inView(camera, p)) return false;
    return true;
}

// True when one side plane of the frustum (or the camera plane) has every corner beyond
// it: then the whole box, not only its corners, is out of view.
bool whollyOutOfView(const Camera& camera, const Corners& corners) {
    int beyond[5] = {};  // x > w, x < -w, y > w, y < -w, behind the camera
    for (const glm::vec3& p : corners) {
        const glm::vec4 c = toClip(camera, p);
        beyond[0] += c.x > c.w;
        beyond[1] += c.x < -c.w;
        beyond[2] += c.y > c.w;
        beyond[3] += c.y < -c.w;
        beyond[4] += c.w <= 0.0f;
    }
    for (int n : beyond)
        if (n == 8) return true;
    return false;
}

// The pixel that a point in view lands in (row 0 at the top).
glm::ivec2 pixelOf(const Camera& camera, glm::vec3 p) {
    const glm::vec4 c = toClip(camera, p);
    const float x = (c.x / c.w * 0.5f + 0.5f) * float(kWidth);
    const float y = (0.5f - c.y / c.w * 0.5f) * float(kHeight);
    return {int(std::floor(x)), int(std::floor(y))};
}

float instanceAt(const Frame& frame, glm::ivec2 px) {
    REQUIRE(px.x >= 0);
    REQUIRE(px.x < kWidth);
    REQUIRE(px.y >= 0);
    REQUIRE(px.y < kHeight);
    return frame.gbuffer.instanceId.at(px.x, px.y);
}

}  // namespace

TEST_CASE("failure scenes: registered, valid, still, and render with finite planes") {
    for (const char* name : kFailureScenes) {
        CAPTURE(name);
        const Scene scene = makeBuiltinScene(name);
        CHECK(scene.name == name);
        CHECK_NOTHROW(scene.validate());
        CHECK(scene.previousCamera.position == scene.camera.position);
        CHECK(scene.previousCamera.target == scene.camera.target);
        for (const Instance& inst : scene.instances)
            CHECK(inst.previousTransform == inst.transform);
        bool listed = false;
        for (const BuiltinSceneInfo& info : builtinScenes()) listed |= info.name == name;
        CHECK(listed);

        const Frame frame = renderSmall(scene);
        for (const PlaneRef& p : frame.layers()) {
            int bad = 0;
            for (int y = 0; y < p.plane->height(); ++y)
                for (int x = 0; x < p.plane->width(); ++x) bad += !std::isfinite(p.plane->at(x, y));
            CAPTURE(p.name);
            CHECK(bad == 0);
        }
    }
}

TEST_CASE("thin scene: thin slabs on a mirror floor, their mirror images wholly in view") {
    const Scene scene = makeBuiltinScene("thin");
    const uint32_t floor = onlyInstanceOf(scene, "mirror_floor");
    const Material& floorMat = scene.materials[scene.instances[floor].material];
    CHECK(floorMat.metallic == 1.0f);
    CHECK(floorMat.roughness <= 0.05f);
    const float floorY = worldCorners(scene, floor)[0].y;
    const std::vector<uint32_t> posts = instancesOf(scene, "post_");
    REQUIRE(posts.size() >= 4);
    float thinnest = INFINITY;
    for (uint32_t post : posts) {
        const Corners c = worldCorners(scene, post);
        const glm::vec3 size = extent(c);
        CAPTURE(post);
        CHECK(size.z <= 0.05f + 1e-5f);  // thin in depth, as the camera (looking down -Z) sees it
        CHECK(size.y >= 0.9f);
        CHECK(c[0].y == doctest::Approx(floorY));  // standing on the mirror
        CHECK(allInView(scene.camera, c));
        CHECK(allInView(scene.camera, mirrored(c, 1, floorY)));
        thinnest = std::min(thinnest, size.z);
    }
    CHECK(thinnest <= 0.005f);
    // Low down: the camera's eye is below the posts' middle, so the view grazes the floor.
    CHECK(scene.camera.position.y < 0.5f);
}

// How many pixels a box spans along screen axis `axis` (0: x, 1: y) at 320x180, the ray
// check's size (tests/truth/ray_check_scenes_test.cpp).
float pixelsAcross(const Camera& camera, const Corners& c, int axis) {
    float lo = INFINITY, hi = -INFINITY;
    for (const glm::vec3& p : c) {
        const glm::vec4 clip = toClip(camera, p);
        const float ndc = (axis == 0 ? clip.x : clip.y) / clip.w;
        lo = std::min(lo, ndc);
        hi = std::max(hi, ndc);
    }
    return 0.5f * (hi - lo) * (axis == 0 ? 320.0f : 180.0f);
}

TEST_CASE("fence scene: poles and wires about a pixel across before a wall, mirrored in view") {
    const Scene scene = makeBuiltinScene("fence");
    const uint32_t floor = onlyInstanceOf(scene, "mirror_floor");
    const Material& floorMat = scene.materials[scene.instances[floor].material];
    CHECK(floorMat.metallic == 1.0f);
    CHECK(floorMat.roughness <= 0.05f);
    const float floorY = worldCorners(scene, floor)[0].y;
    const Corners wall = worldCorners(scene, onlyInstanceOf(scene, "fence_wall"));
    const std::vector<uint32_t> poles = instancesOf(scene, "fence_pole");
    const std::vector<uint32_t> wires = instancesOf(scene, "fence_wire");
    REQUIRE(poles.size() >= 10);
    REQUIRE(wires.size() == 2);
    for (uint32_t pole : poles) {
        const Corners c = worldCorners(scene, pole);
        CAPTURE(pole);
        CHECK(c[0].y == doctest::Approx(floorY));
        CHECK(c[0].z > wall[7].z + 1.0f);  // a metre or more before the wall
        CHECK(allInView(scene.camera, c));
        CHECK(allInView(scene.camera, mirrored(c, 1, floorY)));
        // 1.6 pixels on the axis; off it the box's depth adds to its width.
        CHECK(pixelsAcross(scene.camera, c, 0) <= 2.5f);
        CHECK(extent(c).z <= 0.03f);  // far thinner than the thickness guess at its depth
    }
    for (uint32_t wire : wires) {
        const Corners c = worldCorners(scene, wire);
        CHECK(allInView(scene.camera, c));
        CHECK(pixelsAcross(scene.camera, c, 1) <= 1.0f);  // under a pixel high
    }
    // Between two poles, away from the wires, the wall shows through.
    const Frame frame = renderSmall(scene);
    const glm::vec3 gap =
        0.5f * (centre(worldCorners(scene, poles[0])) + centre(worldCorners(scene, poles[1])));
    CHECK(instanceAt(frame, pixelOf(scene.camera, {gap.x, 0.7f, gap.z})) ==
          float(onlyInstanceOf(scene, "fence_wall")));
}

TEST_CASE("corridor scene: long and narrow, no ceiling, far end visible down the middle") {
    const Scene scene = makeBuiltinScene("corridor");
    const Corners floor = worldCorners(scene, onlyInstanceOf(scene, "corridor_floor"));
    const glm::vec3 size = extent(floor);
    CHECK(size.z / size.x > 8.0f);
    CHECK(size.z >= 25.0f);
    const std::vector<uint32_t> walls = instancesOf(scene, "corridor_wall");
    REQUIRE(walls.size() == 2);
    const float wallTop = worldCorners(scene, walls[0])[7].y;
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    CHECK(hi.y <= wallTop + 1e-5f);  // nothing above the walls: open to the sun
    const Frame frame = renderSmall(scene);
    const float centreZ = frame.gbuffer.viewZ.at(kWidth / 2, kHeight / 2);
    CHECK(centreZ > 20.0f);
    CHECK(instanceAt(frame, {kWidth / 2, kHeight / 2}) ==
          float(onlyInstanceOf(scene, "corridor_end")));
}

TEST_CASE("offscreen scene: bright emitters out of view, their reflections on the floor") {
    const Scene scene = makeBuiltinScene("offscreen");
    const uint32_t floor = onlyInstanceOf(scene, "mirror_floor");
    const float floorY = worldCorners(scene, floor)[0].y;
    const std::vector<uint32_t> lamps = instancesOf(scene, "lamp_");
    REQUIRE(lamps.size() >= 3);
    const Frame frame = renderSmall(scene);
    for (uint32_t lamp : lamps) {
        CAPTURE(lamp);
        const Material& m = scene.materials[scene.instances[lamp].material];
        const float brightest = std::max({m.emissive.r, m.emissive.g, m.emissive.b});
        const float dimmest = std::min({m.emissive.r, m.emissive.g, m.emissive.b});
        CHECK(brightest >= 2.0f);
        CHECK(dimmest <= 0.5f * brightest);  // saturated
        const Corners c = worldCorners(scene, lamp);
        CHECK(whollyOutOfView(scene.camera, c));
        const Corners image = mirrored(c, 1, floorY);
        CHECK(allInView(scene.camera, image));
        // The mirror image lands on the floor, not on a prop that hides the reflection.
        CHECK(instanceAt(frame, pixelOf(scene.camera, centre(image))) == float(floor));
    }
}

TEST_CASE("occluded scene: the mirror shows a sphere that the camera cannot see") {
    const Scene scene = makeBuiltinScene("occluded");
    const uint32_t mirror = onlyInstanceOf(scene, "mirror_wall");
    const uint32_t hidden = onlyInstanceOf(scene, "hidden");
    const uint32_t occluder = onlyInstanceOf(scene, "occluder");
    const Corners wall = worldCorners(scene, mirror);
    REQUIRE(extent(wall).x == doctest::Approx(0.0f));  // a wall across x, facing -X
    const float wallX = wall[0].x;
    const Corners sphere = worldCorners(scene, hidden);
    const Frame frame = renderSmall(scene);
    // The sphere's centre and its bounds' corners are in the frame but behind the box.
    CHECK(allInView(scene.camera, sphere));
    for (const glm::vec3& p : sphere)
        CHECK(instanceAt(frame, pixelOf(scene.camera, p)) == float(occluder));
    CHECK(instanceAt(frame, pixelOf(scene.camera, centre(sphere))) == float(occluder));
    // Its mirror image is seen through the mirror: the reflection is on screen.
    const glm::vec3 image = mirrored(centre(sphere), 0, wallX);
    CHECK(instanceAt(frame, pixelOf(scene.camera, image)) == float(mirror));
    // No pixel anywhere holds the sphere: a screen-space reflection has nothing to hit.
    int sphereSeen = 0;
    const PlaneF& ids = frame.gbuffer.instanceId;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) sphereSeen += ids.at(x, y) == float(hidden);
    CHECK(sphereSeen == 0);
}
