// Camera paths: keys are hit exactly, curves are continuous (Catmull-Rom also in its first
// derivative), fovY never overshoots its keys, and frames sample the path evenly end to end.
#include "scenes/camera_path.h"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

using namespace ssrt;

namespace {

// Uneven times and a turn at every key, so a curve that ignored either would show.
CameraPath testPath(PathInterpolation interpolation) {
    CameraPath p;
    p.interpolation = interpolation;
    p.keys = {{0.0, {0.0f, 1.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 40.0f},
              {0.7, {3.0f, 1.5f, 3.0f}, {0.2f, 0.1f, 0.0f}, 30.0f},
              {1.1, {4.0f, 2.0f, -1.0f}, {0.0f, 0.5f, 0.3f}, 55.0f},
              {3.0, {-2.0f, 1.0f, -4.0f}, {0.0f, 0.0f, 0.0f}, 45.0f}};
    return p;
}

double distance(const Camera& a, const Camera& b) {
    return double(glm::length(a.position - b.position)) + glm::length(a.target - b.target) +
           std::fabs(double(a.fovY) - b.fovY) * 0.01;
}

}  // namespace

TEST_CASE("camera path: every key is hit exactly, base fields kept") {
    Camera base;
    base.up = {0.0f, 0.0f, 1.0f};
    base.nearZ = 0.3f;
    for (PathInterpolation interp : {PathInterpolation::CatmullRom, PathInterpolation::Linear}) {
        const CameraPath path = testPath(interp);
        REQUIRE_NOTHROW(path.validate());
        for (const CameraKey& key : path.keys) {
            CAPTURE(key.time);
            const Camera c = path.at(key.time, base);
            CHECK(c.position == key.position);
            CHECK(c.target == key.target);
            CHECK(c.fovY == key.fovY);
            CHECK(c.up == base.up);
            CHECK(c.nearZ == base.nearZ);
        }
        // Before the first key and after the last the camera holds still
        CHECK(path.at(-5.0, base).position == path.keys.front().position);
        CHECK(path.at(99.0, base).position == path.keys.back().position);
    }
}

TEST_CASE("camera path: continuous everywhere, Catmull-Rom also in its slope") {
    const Camera base;
    for (PathInterpolation interp : {PathInterpolation::CatmullRom, PathInterpolation::Linear}) {
        const bool cubic = interp == PathInterpolation::CatmullRom;
        CAPTURE(cubic);
        const CameraPath path = testPath(interp);
        // No jump anywhere: steps of 1e-4 move the camera by little, across segment changes too
        const double step = 1e-4;
        double worst = 0.0;
        for (double t = 0.0; t < 3.0; t += step)
            worst = std::max(worst, distance(path.at(t, base), path.at(t + step, base)));
        MESSAGE("largest move over a step of " << step << ": " << worst);
        CHECK(worst < 0.01);
        // At each interior key: both sides meet, and the slopes on either side agree for
        // Catmull-Rom (a linear path turns a corner there)
        for (std::size_t k = 1; k + 1 < path.keys.size(); ++k) {
            const double tk = path.keys[k].time, h = 1e-3;
            const Camera at = path.at(tk, base);
            const glm::dvec3 p = glm::dvec3(at.position);
            const glm::dvec3 before = (p - glm::dvec3(path.at(tk - h, base).position)) / h;
            const glm::dvec3 after = (glm::dvec3(path.at(tk + h, base).position) - p) / h;
            CHECK(distance(path.at(tk - 1e-7, base), path.at(tk + 1e-7, base)) < 1e-5);
            const double slopeJump = glm::length(after - before);
            CAPTURE(k);
            CAPTURE(slopeJump);
            if (cubic) CHECK(slopeJump < 0.05 * glm::length(after));
            else CHECK(slopeJump > 0.5 * glm::length(after));
        }
    }
}

TEST_CASE("camera path: linear is the straight line, fovY stays within its keys") {
    CameraPath path = testPath(PathInterpolation::Linear);
    const Camera mid = path.at(0.35, Camera{});
    const glm::vec3 expected = (path.keys[0].position + path.keys[1].position) * 0.5f;
    CHECK(glm::length(mid.position - expected) < 1e-6f);
    CHECK(mid.fovY == doctest::Approx(35.0f));
    // A cubic through 10, 10, 80, 80 would dip below 10 on the first segment: clamped
    path.interpolation = PathInterpolation::CatmullRom;
    path.keys[0].fovY = path.keys[1].fovY = 10.0f;
    path.keys[2].fovY = path.keys[3].fovY = 80.0f;
    for (double t = 0.0; t <= 3.0; t += 0.01) {
        const float f = path.at(t, Camera{}).fovY;
        const bool firstSegment = t <= 0.7, lastSegment = t >= 1.1;
        if (firstSegment) REQUIRE(f == 10.0f);
        if (lastSegment) REQUIRE(f == 80.0f);
        REQUIRE(f >= 10.0f);
        REQUIRE(f <= 80.0f);
    }
}

TEST_CASE("camera path: frames sample it evenly from the first key to the last") {
    const CameraPath path = testPath(PathInterpolation::CatmullRom);
    CHECK(path.frameTime(0, 5) == 0.0);
    CHECK(path.frameTime(4, 5) == 3.0);
    CHECK(path.frameTime(2, 5) == doctest::Approx(1.5));
    CHECK(path.frameTime(0, 1) == 0.0);
    CHECK(CameraPath{}.at(1.0, Camera{}).position == Camera{}.position);
}

TEST_CASE("camera path: bad keys are named") {
    CameraPath path = testPath(PathInterpolation::Linear);
    path.keys[2].time = path.keys[1].time;
    CHECK_THROWS_WITH_AS(path.validate(),
                         "camera path key 2: time must be greater than the previous key's",
                         std::invalid_argument);
    path = testPath(PathInterpolation::Linear);
    path.keys[1].target = path.keys[1].position;
    CHECK_THROWS_WITH_AS(path.validate(),
                         "camera path key 1: position and target are the same point",
                         std::invalid_argument);
    path = testPath(PathInterpolation::Linear);
    path.keys[3].fovY = 180.0f;
    CHECK_THROWS_AS(path.validate(), std::invalid_argument);
    path = testPath(PathInterpolation::Linear);
    path.keys[0].position.x = NAN;
    CHECK_THROWS_AS(path.validate(), std::invalid_argument);
}

TEST_CASE("camera path: a cut splits it into paths of their own, the first held up to the cut") {
    const Camera base;
    for (PathInterpolation interp : {PathInterpolation::CatmullRom, PathInterpolation::Linear}) {
        CAPTURE(interp == PathInterpolation::CatmullRom);
        CameraPath path = testPath(interp);
        path.keys[2].cut = true;  // at t = 1.1
        REQUIRE_NOTHROW(path.validate());
        CameraPath before = testPath(interp), after = testPath(interp);
        before.keys.erase(before.keys.begin() + 2, before.keys.end());  // keys 0 and 1
        after.keys.erase(after.keys.begin(), after.keys.begin() + 2);   // keys 2 and 3
        const auto same = [](const Camera& a, const Camera& b) {
            return a.position == b.position && a.target == b.target && a.fovY == b.fovY;
        };
        for (double t = -0.5; t <= 3.5; t += 0.05) {
            CAPTURE(t);
            const Camera c = path.at(t, base);
            if (t < 1.1) CHECK(same(c, before.at(t, base)));  // held at key 1 after 0.7
            else CHECK(same(c, after.at(t, base)));           // bit for bit: no tangent crosses
        }
        CHECK(same(path.at(1.0, base), before.at(0.7, base)));
        CHECK(path.at(1.1, base).position == path.keys[2].position);
        // The whole path without the cut is a different curve near the cut
        const Camera whole = testPath(interp).at(1.0, base);
        CHECK(!same(path.at(1.0, base), whole));
        // Frames between which the cut lies
        CHECK(path.cutBetween(0.9, 1.1));
        CHECK(path.cutBetween(1.0, 2.0));
        CHECK(!path.cutBetween(1.1, 1.5));
        CHECK(!path.cutBetween(0.0, 1.0));
        CHECK(!testPath(interp).cutBetween(-10.0, 10.0));
    }
    CameraPath path = testPath(PathInterpolation::Linear);
    path.keys[0].cut = true;
    CHECK_THROWS_WITH_AS(path.validate(),
                         "camera path key 0: the first key cannot be a cut (nothing comes before "
                         "it to cut from)",
                         std::invalid_argument);
}
