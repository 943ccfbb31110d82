// Ray checks (truth/ray_check.h): every class pinned on a hand-made analytic scene,
// the error values and planes, the same results for every thread count; then the failure
// scenes (`thin`, `offscreen`, `occluded`) rendered with each marcher, their SSR and SSGI rays
// checked, and the failures each scene was built for found.
#include "truth/ray_check.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "renderer/renderer.h"
#include "renderer/resources.h"
#include "scenes/builtin_scenes.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_helpers.h"
#include "thread_counts.h"
#include "trace/march.h"

using namespace ssrt;
using namespace ssrt::helpers;

namespace {

// ---- A hand-made frame ------------------------------------------------------------------
// The camera at the origin looks down -Z (view space = world space). A wall at z = -5, 8 x 8 m
// (wider than the view), and an occluder 1 x 1 m at z = -3 in front of its middle, both
// facing the camera.
constexpr float kWallZ = 5.0f, kOccluderZ = 3.0f, kOccluderHalf = 0.5f, kTanHalf = 0.5f;

Scene wallScene() {
    Scene s;
    const uint32_t mat = addMaterial(s, "grey", glm::vec3(0.5f), 0.0f, 0.5f);
    addInstance(s, addMesh(s, makeQuad({4.0f, 4.0f}, 1)), mat,
                translate({0, 0, -kWallZ}) * rotate(90.0f, {1, 0, 0}));
    addInstance(s, addMesh(s, makeQuad({kOccluderHalf, kOccluderHalf}, 1)), mat,
                translate({0, 0, -kOccluderZ}) * rotate(90.0f, {1, 0, 0}));
    return s;
}

TraceCamera wallCamera(int w, int h) {
    TraceCamera c;
    c.width = w;
    c.height = h;
    c.tanHalfX = kTanHalf;
    c.tanHalfY = kTanHalf * float(h) / float(w);
    // At the world's 0, measured from the scene's origin (as the renderer's cameras are).
    const glm::vec3 origin = wallScene().origin();
    for (int i = 0; i < 3; ++i) {
        c.origin[i] = origin[i];
        c.position[i] = -origin[i];
    }
    return c;
}

// The G-buffer depth of wallScene(): the occluder where it covers the pixel centre, else the
// wall.
PlaneF wallViewZ(const TraceCamera& c) {
    PlaneF z(c.width, c.height, 0.0f);
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const float vx = (2.0f * (float(x) + 0.5f) / float(c.width) - 1.0f) * c.tanHalfX;
            const float vy = (1.0f - 2.0f * (float(y) + 0.5f) / float(c.height)) * c.tanHalfY;
            const bool occluded = std::abs(vx * kOccluderZ) <= kOccluderHalf &&
                                  std::abs(vy * kOccluderZ) <= kOccluderHalf;
            z.at(x, y) = occluded ? kOccluderZ : kWallZ;
        }
    return z;
}

glm::vec2 project(const TraceCamera& c, glm::vec3 p) {
    const float d = -p.z;
    return {(p.x / (d * c.tanHalfX) * 0.5f + 0.5f) * float(c.width),
            (0.5f - p.y / (d * c.tanHalfY) * 0.5f) * float(c.height)};
}

struct Frame1 {
    TraceCamera camera;
    PlaneF viewZ;
    RayBatch rays;
    MarchResult march;
};

Frame1 emptyFrame(int w, int h) {
    Frame1 f;
    f.camera = wallCamera(w, h);
    f.viewZ = wallViewZ(f.camera);
    f.rays.ensureSize(w, h);
    f.march.ensureSize(w, h);
    for (PlaneF* p :
         {&f.rays.ox, &f.rays.oy, &f.rays.oz, &f.rays.dx, &f.rays.dy, &f.rays.dz, &f.rays.pdf,
          &f.march.hit, &f.march.hitX, &f.march.hitY, &f.march.hitZ, &f.march.steps})
        p->fill(0.0f);
    f.march.cause.fill(float(int(MarchEnd::NoRay)));
    return f;
}

void setRay(Frame1& f, int x, int y, glm::vec3 o, glm::vec3 towards) {
    const glm::vec3 d = glm::normalize(towards - o);
    f.rays.ox.at(x, y) = o.x, f.rays.oy.at(x, y) = o.y, f.rays.oz.at(x, y) = o.z;
    f.rays.dx.at(x, y) = d.x, f.rays.dy.at(x, y) = d.y, f.rays.dz.at(x, y) = d.z;
    f.rays.pdf.at(x, y) = 1.0f;
    f.march.cause.at(x, y) = float(int(MarchEnd::StepCap));
}

void setMarchHit(Frame1& f, int x, int y, glm::vec2 pixel, float z) {
    f.march.hit.at(x, y) = 1.0f;
    f.march.hitX.at(x, y) = pixel.x;
    f.march.hitY.at(x, y) = pixel.y;
    f.march.hitZ.at(x, y) = z;
    f.march.cause.at(x, y) = float(int(MarchEnd::Hit));
}

RayClass classAt(const CheckPlanes& p, int x, int y) {
    return RayClass(int(p[kCheckClass].at(x, y)));
}

std::string tableText(const RayCheckTable& t) {
    std::ostringstream s;
    s << t.rays << " rays:";
    for (int c = 1; c < kRayClassCount; ++c)
        s << " " << rayClassName(RayClass(c)) << " " << t.count[c];
    s << "; pixel error p50 " << RayCheckTable::quantile(t.pixelError, 0.5) << " p90 "
      << RayCheckTable::quantile(t.pixelError, 0.9) << ", depth error p50 "
      << RayCheckTable::quantile(t.depthError, 0.5) << "; Embree " << t.embreeHits << " hits";
    if (t.embreeSeconds > 0.0) s << ", " << double(t.rays) / t.embreeSeconds * 1e-6 << " M rays/s";
    return s.str();
}

uint64_t planesHash(const CheckPlanes& p) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const PlaneF& q : p) h = hashPlane(q, h);
    return h;
}

}  // namespace

TEST_CASE("ray check: class names, table sums and quantiles") {
    CHECK(rayClassName(RayClass::NoRay) == "no_ray");
    CHECK(rayClassName(RayClass::Agreed) == "agreed");
    CHECK(rayClassName(RayClass::FalseHit) == "false_hit");
    CHECK(rayClassName(RayClass::MissedOnScreen) == "missed_on_screen");
    CHECK(rayClassName(RayClass::TrueMiss) == "true_miss");
    CHECK(rayClassName(RayClass::OffScreenTruth) == "offscreen_truth");
    RayCheckTable a, b;
    a.rays = 3, a.count[int(RayClass::Agreed)] = 2, a.count[int(RayClass::TrueMiss)] = 1;
    a.pixelError = {3.0f, 1.0f};
    a.depthError = {0.2f, 0.1f};
    a.embreeHits = 2, a.embreeSeconds = 0.5;
    b.rays = 1, b.count[int(RayClass::FalseHit)] = 1;
    b.pixelError = {std::numeric_limits<float>::infinity()};
    b.depthError = {0.0f};
    b.embreeSeconds = 0.25;
    a.add(b);
    a.finish();
    CHECK(a.rays == 4);
    CHECK(a.count[int(RayClass::Agreed)] == 2);
    CHECK(a.count[int(RayClass::FalseHit)] == 1);
    CHECK(a.share(RayClass::Agreed) == 0.5);
    CHECK(RayCheckTable().share(RayClass::Agreed) == 0.0);
    CHECK(a.embreeHits == 2);
    CHECK(a.embreeSeconds == 0.75);
    CHECK(a.pixelError == std::vector<float>{1.0f, 3.0f, std::numeric_limits<float>::infinity()});
    // Nearest rank.
    CHECK(RayCheckTable::quantile(a.pixelError, 0.0) == 1.0f);
    CHECK(RayCheckTable::quantile(a.pixelError, 0.5) == 3.0f);
    CHECK(RayCheckTable::quantile(a.pixelError, 0.34) == 3.0f);
    CHECK(RayCheckTable::quantile(a.pixelError, 0.33) == 1.0f);
    CHECK(std::isinf(RayCheckTable::quantile(a.pixelError, 1.0)));
    CHECK(RayCheckTable::quantile({}, 0.5) == 0.0f);
}

TEST_CASE("ray check: one ray of each class on a hand-made wall scene") {
    const Scene scene = wallScene();
    const EmbreeScene embree(scene);
    Frame1 f = emptyFrame(80, 70);
    const TraceCamera& c = f.camera;
    const glm::vec3 o(0.0f, 0.0f, -1.0f);
    // Visible wall points (clear of the occluder) and one behind it.
    const glm::vec3 w1(1.5f, 1.0f, -kWallZ), w2(-1.5f, -1.0f, -kWallZ), w3(-1.5f, 0.6f, -kWallZ);
    const glm::vec3 hidden(0.2f, 0.1f, -kWallZ), offFrame(3.5f, 0.0f, -kWallZ);
    const glm::vec3 behindOccluder(1.0f, 0.0f, -4.0f);  // the wall is in reach, the occluder not

    // Agreed: 1 pixel off (0.6, 0.8) and 1 % deep.
    setRay(f, 10, 10, o, w1);
    setMarchHit(f, 10, 10, project(c, w1) + glm::vec2(0.6f, 0.8f), 1.01f * kWallZ);
    // False hits: at the wrong place; with no truth (a ray back past the camera into the
    // void); at the right place of a truth the camera cannot see.
    setRay(f, 20, 10, o, w2);
    setMarchHit(f, 20, 10, {30.5f, 30.5f}, kWallZ);
    setRay(f, 30, 10, o, o + glm::vec3(0, 0, 1));
    setMarchHit(f, 30, 10, {40.5f, 35.5f}, kWallZ);
    setRay(f, 35, 10, behindOccluder, hidden);
    setMarchHit(f, 35, 10, project(c, hidden), kWallZ);
    // Missed on screen, true miss, off-screen truths (hidden, off the frame).
    setRay(f, 40, 10, o, w3);
    setRay(f, 50, 10, o, o + glm::vec3(0, 0, 1));
    setRay(f, 60, 10, behindOccluder, hidden);
    setRay(f, 70, 10, o, offFrame);
    // A pixel of the last tile row and column, so partial 4x4 blocks are traced: missed.
    setRay(f, 79, 69, o, w3);

    CheckPlanes planes;
    RayCheckTable t = checkRays(embree, c, f.viewZ, f.rays, f.march, {}, planes.data(), 1);
    t.finish();
    MESSAGE(tableText(t));
    CHECK(t.rays == 9);
    CHECK(t.count[int(RayClass::NoRay)] == 0);
    CHECK(t.count[int(RayClass::Agreed)] == 1);
    CHECK(t.count[int(RayClass::FalseHit)] == 3);
    CHECK(t.count[int(RayClass::MissedOnScreen)] == 2);
    CHECK(t.count[int(RayClass::TrueMiss)] == 1);
    CHECK(t.count[int(RayClass::OffScreenTruth)] == 2);
    CHECK(t.embreeHits == 7);
    // Planes: the class of each ray, NoRay elsewhere.
    const std::pair<int, RayClass> expect[] = {
        {10, RayClass::Agreed},         {20, RayClass::FalseHit},       {30, RayClass::FalseHit},
        {35, RayClass::FalseHit},       {40, RayClass::MissedOnScreen}, {50, RayClass::TrueMiss},
        {60, RayClass::OffScreenTruth}, {70, RayClass::OffScreenTruth}};
    for (auto [x, cls] : expect) CHECK(classAt(planes, x, 10) == cls);
    CHECK(classAt(planes, 79, 69) == RayClass::MissedOnScreen);
    CHECK(classAt(planes, 11, 10) == RayClass::NoRay);
    CHECK(classAt(planes, 0, 0) == RayClass::NoRay);
    // True distances, 0 without a true hit.
    CHECK(planes[kCheckTrueT].at(10, 10) == doctest::Approx(glm::length(w1 - o)).epsilon(1e-5));
    CHECK(planes[kCheckTrueT].at(60, 10) ==
          doctest::Approx(glm::length(hidden - behindOccluder)).epsilon(1e-5));
    CHECK(planes[kCheckTrueT].at(30, 10) == 0.0f);
    CHECK(planes[kCheckTrueT].at(50, 10) == 0.0f);
    CHECK(planes[kCheckTrueT].at(11, 10) == 0.0f);
    // Errors where both hit (agreed, wrong place, hidden truth): pixels and relative depth.
    const float wrong = glm::length(glm::vec2(30.5f, 30.5f) - project(c, w2));
    CHECK(planes[kCheckPixelError].at(10, 10) == doctest::Approx(1.0f).epsilon(1e-4));
    CHECK(planes[kCheckDepthError].at(10, 10) == doctest::Approx(0.01f).epsilon(1e-3));
    CHECK(planes[kCheckPixelError].at(20, 10) == doctest::Approx(wrong).epsilon(1e-5));
    CHECK(planes[kCheckPixelError].at(35, 10) < 1e-3f);
    CHECK(planes[kCheckPixelError].at(30, 10) == 0.0f);  // no truth: no error
    REQUIRE(t.pixelError.size() == 3);
    REQUIRE(t.depthError.size() == 3);
    CHECK(t.pixelError[0] < 1e-3f);
    CHECK(t.pixelError[1] == doctest::Approx(1.0f).epsilon(1e-4));
    CHECK(t.pixelError[2] == doctest::Approx(wrong).epsilon(1e-5));
    CHECK(t.depthError[2] == doctest::Approx(0.01f).epsilon(1e-3));
    CHECK(t.depthError[0] < 1e-5f);
    CHECK(t.depthError[1] < 1e-5f);

    // Tighter tolerances turn the agreed ray into a false hit.
    RayCheckSettings tight;
    tight.pixelTolerance = 0.9f;
    CHECK(checkRays(embree, c, f.viewZ, f.rays, f.march, tight, nullptr, 1)
              .count[int(RayClass::FalseHit)] == 4);
    tight = {};
    tight.depthTolerance = 0.009f;
    CHECK(checkRays(embree, c, f.viewZ, f.rays, f.march, tight, nullptr, 1)
              .count[int(RayClass::Agreed)] == 0);
    // A maximum distance short of the wall: every truth is gone.
    tight = {};
    tight.maxDistance = 1.0f;
    const RayCheckTable shortRays =
        checkRays(embree, c, f.viewZ, f.rays, f.march, tight, nullptr, 1);
    CHECK(shortRays.count[int(RayClass::TrueMiss)] == 5);
    CHECK(shortRays.count[int(RayClass::FalseHit)] == 4);
}

TEST_CASE("ray check: the check planes' channels are the resource table's, in its order") {
    for (Res id : {Res::SsrCheck, Res::SsgiCheck}) {
        checkChannelCount(id, kCheckChannels);
        const std::string base(resourceDecl(id).name);
        CHECK(channelName(id, kCheckClass) == base + ".class");
        CHECK(channelName(id, kCheckPixelError) == base + ".pixelError");
        CHECK(channelName(id, kCheckDepthError) == base + ".depthError");
        CHECK(channelName(id, kCheckTrueT) == base + ".trueT");
        CHECK(resourceDecl(id).group == LayerGroup::Truth);
    }
}

TEST_CASE("ray check: planes of the wrong size are refused") {
    const Scene scene = wallScene();
    const EmbreeScene embree(scene);
    Frame1 f = emptyFrame(16, 8);
    const PlaneF wrongZ(8, 8, 1.0f);
    CHECK_THROWS_WITH_AS(checkRays(embree, f.camera, wrongZ, f.rays, f.march, {}, nullptr, 1),
                         "checkRays: viewZ is 8x8, not 16x8", std::invalid_argument);
    MarchResult small;
    small.ensureSize(16, 4);
    CHECK_THROWS_WITH_AS(checkRays(embree, f.camera, f.viewZ, f.rays, small, {}, nullptr, 1),
                         "checkRays: march.hit is 16x4, not 16x8", std::invalid_argument);
}

TEST_CASE("ray check: the same table and planes for 1, 2 and 8 threads") {
    const Scene scene = wallScene();
    const EmbreeScene embree(scene);
    // Several tiles with partial ones at the edges; a ray on every pixel, from its wall or
    // occluder point in random directions, and a march that hits at random places half the
    // time.
    Frame1 f = emptyFrame(200, 150);
    uint64_t state = 1;
    auto next = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(uint32_t(state >> 40)) / float(1u << 24);
    };
    for (int y = 0; y < f.camera.height; ++y)
        for (int x = 0; x < f.camera.width; ++x) {
            const float z = f.viewZ.at(x, y);
            const glm::vec3 p(
                (2.0f * (float(x) + 0.5f) / float(f.camera.width) - 1.0f) * f.camera.tanHalfX * z,
                (1.0f - 2.0f * (float(y) + 0.5f) / float(f.camera.height)) * f.camera.tanHalfY * z,
                -z);
            setRay(f, x, y, p,
                   p + glm::vec3(2.0f * next() - 1.0f, 2.0f * next() - 1.0f, 2.0f * next() - 1.0f));
            if (next() < 0.5f)
                setMarchHit(f, x, y, {next() * 200.0f, next() * 150.0f}, 3.0f + 2.0f * next());
        }
    CheckPlanes reference;
    const RayCheckTable first =
        checkRays(embree, f.camera, f.viewZ, f.rays, f.march, {}, reference.data(), 1);
    RayCheckTable sorted = first;  // the error lists of `first` stay in tile order
    sorted.finish();
    MESSAGE(tableText(sorted));
    uint64_t sum = 0;
    for (uint64_t n : first.count) sum += n;
    CHECK(sum == first.rays);
    CHECK(first.rays == 200u * 150u);
    // A random march hit seldom lands on the truth: every class but Agreed turns up.
    for (RayClass c : {RayClass::FalseHit, RayClass::MissedOnScreen, RayClass::TrueMiss,
                       RayClass::OffScreenTruth})
        CHECK(first.count[int(c)] > 0);
    for (int threads : testThreadCounts({2, 8})) {
        CAPTURE(threads);
        CheckPlanes planes;
        const RayCheckTable t =
            checkRays(embree, f.camera, f.viewZ, f.rays, f.march, {}, planes.data(), threads);
        CHECK(t.rays == first.rays);
        CHECK(t.count == first.count);
        CHECK(t.embreeHits == first.embreeHits);
        CHECK(t.pixelError == first.pixelError);  // unsorted: the tile order itself
        CHECK(t.depthError == first.depthError);
        CHECK(planesHash(planes) == planesHash(reference));
    }
}
