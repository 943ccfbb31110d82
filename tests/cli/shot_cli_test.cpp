// ssrt render --shot and --frames, driven in-process: flags override the shot, a bad shot is
// one line naming the file and field with exit 3 and no file, and a sequence writes exactly
// its numbered files with motion vectors that follow the camera path.
#include <doctest/doctest.h>

#include "cli/cli_run.h"
#include "temp_dir.h"

#ifdef SSRT_CLI_LIB

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/glm.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/render_command.h"
#include "cli/shot_settings.h"
#include "io/image_io.h"
#include "scenes/builtin_scenes.h"
#include "scenes/shot.h"

using namespace ssrt;
using test::TempDir;

namespace {

using Result = test::CliResult;
using test::contains;

Result run(std::vector<std::string> args) { return test::runSsrt(std::move(args)); }

long lines(const std::string& text) { return std::count(text.begin(), text.end(), '\n'); }

using test::writeFile;

// World-space direction of the ray through the centre of pixel (x, y), scaled so that its
// view-space depth is 1 (tests/raster/gbuffer_test.cpp does the same).
glm::dvec3 pixelRay(const Camera& cam, int w, int h, int x, int y) {
    const double tanY = std::tan(glm::radians(double(cam.fovY)) * 0.5);
    const double ndcX = (x + 0.5) * 2.0 / w - 1.0, ndcY = 1.0 - (y + 0.5) * 2.0 / h;
    const glm::dvec3 f = glm::normalize(glm::dvec3(cam.target - cam.position));
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
    const glm::dvec3 u = glm::cross(r, f);
    return r * (ndcX * tanY * w / h) + u * (ndcY * tanY) + f;
}

// A three-key path through the cornell box: the camera slides, turns and zooms.
const char* const kPathShot = R"({
  "scene": "cornell",
  "camera": {
    "path": {
      "keys": [
        { "time": 0, "position": [0.0, 1.15, 3.2], "target": [0.0, 0.85, 0.0], "fovY": 40 },
        { "time": 1, "position": [0.3, 1.25, 3.0], "target": [0.1, 0.8, 0.0], "fovY": 38 },
        { "time": 3, "position": [0.5, 1.2, 2.9], "target": [0.2, 0.9, 0.0], "fovY": 42 }
      ]
    }
  },
  "render": { "width": 64, "height": 40, "shadowMapSize": 128, "frames": 3 }
})";

}  // namespace

TEST_CASE("cli shot: the output names of a sequence") {
    CHECK(cli::sequenceFileName("out.png", 0, 1) == "out.png");
    CHECK(cli::sequenceFileName("out.png", 0, 3) == "out_0000.png");
    CHECK(cli::sequenceFileName("out.png", 2, 3) == "out_0002.png");
    CHECK(cli::sequenceFileName("dir/a.b.exr", 7, 10) == "dir/a.b_0007.exr");
    CHECK(cli::sequenceFileName("out.png", 12345, 20000) == "out_12345.png");
    CHECK(cli::sequenceFileName("out.png", 5, 10001) == "out_00005.png");
}

TEST_CASE("cli shot: flags override the shot, the shot overrides the defaults") {
    TempDir shots, dir;
    const std::string shot = shots.file("shot.json");
    writeFile(shot, R"({"scene": "spheres", "render": {"width": 40, "height": 30, "frames": 2,
                        "shadowMapSize": 64}})");
    const std::string out = dir.file("out.exr");
    // The shot alone: its size, its scene, its two frames
    Result r = run({"render", "--shot", shot, "-o", out, "--threads", "1"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(contains(r.err, "rendering spheres 40x30, 2 frames"));
    int w = 0, h = 0;
    readChannel(dir.file("out_0001.exr"), "viewZ", w, h);
    CHECK(w == 40);
    CHECK(h == 30);
    // Flags win: width, scene and frame count
    r = run({"render", "--shot", shot, "--width", "24", "--scene", "cornell", "--frames", "1", "-o",
             out, "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    readChannel(out, "viewZ", w, h);
    CHECK(w == 24);
    CHECK(h == 30);
    // settingsFrom starts from the shot's settings and applies only the flags given
    cli::RenderOptions o;
    o.settings["height"] = "50";
    RenderSettings base;
    applyShot(loadShot(shot), base);
    const RenderSettings s = cli::settingsFrom(o, base);
    CHECK(s.width == 40);
    CHECK(s.height == 50);
    CHECK(s.shadowMapSize == 64);
}

TEST_CASE("cli shot: a bad shot is one line naming file and field, exit 3, no file") {
    TempDir shots, dir;
    const std::string shot = shots.file("shot.json");
    const std::vector<std::pair<std::string, std::string>> cases{
        {R"({"camera": {"fovY": 200}})", "camera.fovY: expected a number in (0, 180)"},
        {R"({"render": {"widht": 64}})", "render.widht: unknown key"},
        {R"({"light": {"direction": [0, 0, 0]}})", "light.direction: expected an array of 3"},
        {R"({"environment": {"type": "image", "file": "nope.hdr"}})",
         "environment.file: no such file"},
        {R"({"camera": {"position": [0, 1, 0], "target": [0, 1, 0]}})",
         "camera: position and target are the same point"},
    };
    // (no structured binding: clang 14 cannot capture one in CAPTURE's lambda)
    for (const auto& entry : cases) {
        const std::string& text = entry.first;
        const std::string& expected = entry.second;
        CAPTURE(text);
        writeFile(shot, text);
        const Result r = run({"render", "--shot", shot, "-o", dir.file("out.png")});
        CHECK(r.code == cli::kExitFailure);
        CHECK(r.err.rfind("ssrt: error: " + shot + ": ", 0) == 0);
        CHECK(contains(r.err, shot + ": " + expected));
        CHECK(lines(r.err) == 1);
        CHECK(dir.empty());
    }
    // A missing shot file too
    const Result r = run({"render", "--shot", shots.file("missing.json"), "-o", dir.file("o.png")});
    CHECK(r.code == cli::kExitFailure);
    CHECK(lines(r.err) == 1);
    CHECK(contains(r.err, "missing.json"));
    // A bad --frames is a usage error like any other flag
    const Result f = run({"render", "--frames", "0", "-o", dir.file("o.png")});
    CHECK(f.code == cli::kExitUsage);
    CHECK(contains(f.err, "--frames: invalid value '0'"));
    CHECK(dir.empty());
}

TEST_CASE("cli shot: a 3-frame sequence writes 3 files whose motion follows the path") {
    TempDir shots, dir;
    const std::string shotFile = shots.file("path.json");
    writeFile(shotFile, kPathShot);
    const Result r = run({"render", "--shot", shotFile, "-o", dir.file("seq.exr"), "-j", "2"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    // Exactly the three files (no temporaries, nothing else), one progress line per frame
    CHECK(dir.listing() ==
          std::vector<std::string>{"seq_0000.exr", "seq_0001.exr", "seq_0002.exr"});
    CHECK(lines(r.err) == 4);
    for (int i = 1; i <= 3; ++i)
        CHECK(contains(r.err, "frame " + std::to_string(i) + "/3: wrote " +
                                  dir.file("seq_000" + std::to_string(i - 1) + ".exr")));
    // Each frame's line but the last's ends with the time left (estimated from the time taken).
    for (const char* file : {"seq_0000.exr", "seq_0001.exr"})
        CHECK(contains(r.err, dir.file(file) + ", "));
    CHECK(contains(r.err, "frame 3/3: wrote " + dir.file("seq_0002.exr") + "\n"));

    // The cameras the sequence used: the path at times 0, 1.5 and 3
    const Shot shot = loadShot(shotFile);
    Scene scene = makeBuiltinScene("cornell");
    applyShot(shot, scene);
    const CameraPath path = shotCameraPath(shot, scene.camera);
    std::vector<Camera> cams;
    for (int i = 0; i < 3; ++i) cams.push_back(path.at(path.frameTime(i, 3), scene.camera));
    CHECK(path.frameTime(1, 3) == 1.5);

    for (int i = 0; i < 3; ++i) {
        CAPTURE(i);
        const std::string file = dir.file("seq_000" + std::to_string(i) + ".exr");
        int w = 0, h = 0;
        const std::vector<float> viewZ = readChannel(file, "viewZ", w, h);
        const std::vector<float> mx = readChannel(file, "motion.X", w, h);
        const std::vector<float> my = readChannel(file, "motion.Y", w, h);
        REQUIRE(w == 64);
        REQUIRE(h == 40);
        // Frame i's previous camera is frame i - 1's (frame 0's is itself): project each
        // visible point, rebuilt from viewZ, through it.
        const Camera& cam = cams[i];
        const Camera& prev = cams[i > 0 ? i - 1 : 0];
        const glm::dmat4 prevVp =
            glm::dmat4(prev.projection(float(w) / float(h))) * glm::dmat4(prev.view());
        double worst = 0.0, largest = 0.0;
        int visible = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float z = viewZ[std::size_t(y) * w + x];
                if (z <= 0.0f) continue;
                ++visible;
                const glm::dvec3 p =
                    glm::dvec3(cam.position) + pixelRay(cam, w, h, x, y) * double(z);
                const glm::dvec4 c = prevVp * glm::dvec4(p, 1.0);
                const double ex = (c.x / c.w * 0.5 + 0.5) * w - (x + 0.5);
                const double ey = (0.5 - c.y / c.w * 0.5) * h - (y + 0.5);
                const double gx = mx[std::size_t(y) * w + x], gy = my[std::size_t(y) * w + x];
                worst = std::max({worst, std::fabs(ex - gx), std::fabs(ey - gy)});
                largest = std::max(largest, std::hypot(ex, ey));
            }
        MESSAGE("frame " << i << ": motion error " << worst << " px, largest motion " << largest
                         << " px over " << visible << " pixels");
        CHECK(visible > w * h / 2);
        CHECK(worst < 2e-3);
        if (i == 0) CHECK(largest < 1e-3);  // a still frame: only rounding
        else CHECK(largest > 2.0);  // the camera really moved, so the bound above means something
    }
}

TEST_CASE("cli shot: frames without a path repeat the still camera") {
    TempDir dir;
    // Without the screen-space passes a frame has no random numbers: the frames are equal.
    Result r =
        run({"render", "--frames", "2", "--width", "16", "--height", "16", "--shadow-map-size",
             "64", "--no-ssr", "--no-ssgi", "-o", dir.file("still.exr"), "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(r.err.empty());
    CHECK(dir.listing() == std::vector<std::string>{"still_0000.exr", "still_0001.exr"});
    int w = 0, h = 0;
    CHECK(readChannel(dir.file("still_0000.exr"), "color.R", w, h) ==
          readChannel(dir.file("still_0001.exr"), "color.R", w, h));
    // With them, each frame index draws its own rays: the G-buffer repeats, the colour not.
    r = run({"render", "--frames", "2", "--width", "16", "--height", "16", "--shadow-map-size",
             "64", "-o", dir.file("traced.exr"), "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(readChannel(dir.file("traced_0000.exr"), "viewZ", w, h) ==
          readChannel(dir.file("traced_0001.exr"), "viewZ", w, h));
    CHECK(readChannel(dir.file("traced_0000.exr"), "ssgi.R", w, h) !=
          readChannel(dir.file("traced_0001.exr"), "ssgi.R", w, h));
    const std::vector<float> motion = readChannel(dir.file("still_0001.exr"), "motion.X", w, h);
    CHECK(std::all_of(motion.begin(), motion.end(), [](float m) { return std::fabs(m) < 1e-3f; }));
}

#endif
