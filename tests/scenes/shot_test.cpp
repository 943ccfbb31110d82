// Shot files: every field lands where it should, relative paths resolve against the shot's
// folder, and each kind of bad input gives exactly one expected line naming the file and the
// JSON path of the field.
#include "scenes/shot.h"

#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/shot_settings.h"  // applyShot(shot, RenderSettings&): the render fields
#include "scenes/builtin_scenes.h"
#include "temp_dir.h"

using namespace ssrt;
using test::TempDir;

namespace {

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

const char* const kFullShot = R"({
  "scene": "model.glb",
  "camera": {
    "position": [1, 2, 3], "target": [0, 0.5, -1], "up": [0, 0, 1],
    "fovY": 30, "near": 0.1, "far": 50,
    "path": {
      "interpolation": "linear",
      "keys": [
        { "time": 0.5, "position": [4, 5, 6], "target": [0, 0, 0], "fovY": 20 },
        { "time": 1.5, "position": [7, 8, 9], "cut": true },
        { "cut": false }
      ]
    }
  },
  "light": { "direction": [0, -2, 0], "color": [1, 0.5, 0.25], "intensity": 4 },
  "environment": { "type": "image", "file": "sky/sky.hdr", "intensity": 0.75 },
  "render": {
    "width": 320, "height": 200, "exposure": 1.5, "shadowMapSize": 512, "shadowBias": 0.5,
    "shadowSlopeBias": 1.25, "pcfRadius": 2, "frames": 12, "frame": 7,
    "warmupFrames": 5
  }
})";

}  // namespace

TEST_CASE("shot: every field lands where it is meant to") {
    TempDir dir;
    writeFile(dir.file("model.glb"), "");
    std::filesystem::create_directories(dir.path / "sky");
    writeFile(dir.file("sky/sky.hdr"), "");
    const std::string file = dir.file("shot.json");
    writeFile(file, kFullShot);
    const Shot shot = loadShot(file);

    // Relative paths resolve against the shot file's folder
    REQUIRE(shot.scene);
    CHECK(*shot.scene == dir.file("model.glb"));
    REQUIRE(shot.environment.file);
    CHECK(*shot.environment.file == (dir.path / "sky/sky.hdr").string());

    // Scene: camera, light, environment (the image itself is the caller's to load)
    Scene scene = makeBuiltinScene("cornell");
    applyShot(shot, scene);
    CHECK(scene.camera.position == glm::vec3(1, 2, 3));
    CHECK(scene.camera.target == glm::vec3(0, 0.5f, -1));
    CHECK(scene.camera.up == glm::vec3(0, 0, 1));
    CHECK(scene.camera.fovY == 30.0f);
    CHECK(scene.camera.nearZ == 0.1f);
    CHECK(scene.camera.farZ == 50.0f);
    CHECK(scene.previousCamera.position == scene.camera.position);
    CHECK(scene.light.direction == glm::vec3(0, -1, 0));  // normalised
    CHECK(scene.light.color == glm::vec3(1, 0.5f, 0.25f));
    CHECK(scene.light.intensity == 4.0f);
    CHECK(scene.sky.kind == Sky::Kind::Image);
    CHECK(scene.sky.intensity == 0.75f);

    // Path: missing key fields come from the camera, a missing time is the key's index
    const CameraPath path = shotCameraPath(shot, scene.camera);
    CHECK(path.interpolation == PathInterpolation::Linear);
    REQUIRE(path.keys.size() == 3);
    CHECK(path.keys[0].time == 0.5);
    CHECK(path.keys[0].position == glm::vec3(4, 5, 6));
    CHECK(path.keys[0].target == glm::vec3(0, 0, 0));
    CHECK(path.keys[0].fovY == 20.0f);
    CHECK(path.keys[1].time == 1.5);
    CHECK(path.keys[1].position == glm::vec3(7, 8, 9));
    CHECK(path.keys[1].target == scene.camera.target);
    CHECK(path.keys[1].fovY == 30.0f);
    CHECK(path.keys[2].time == 2.0);  // its index
    CHECK(path.keys[2].position == scene.camera.position);
    CHECK(!path.keys[0].cut);
    CHECK(path.keys[1].cut);
    CHECK(!path.keys[2].cut);

    // Render settings
    RenderSettings s;
    applyShot(shot, s);
    CHECK(s.width == 320);
    CHECK(s.height == 200);
    CHECK(s.exposure == 1.5f);
    CHECK(s.shadowMapSize == 512);
    CHECK(s.shadowBias == 0.5f);
    CHECK(s.shadowSlopeBias == 1.25f);
    CHECK(s.pcfRadius == 2);
    CHECK(shot.render.frame == 7u);
    CHECK(shot.render.frames == 12);
    CHECK(shot.render.warmupFrames == 5);
}

TEST_CASE("shot: an empty shot changes nothing") {
    const Shot shot = parseShot("{}", "empty.json");
    Scene scene = makeBuiltinScene("spheres");
    const Scene before = makeBuiltinScene("spheres");
    applyShot(shot, scene);
    CHECK(scene.camera.position == before.camera.position);
    CHECK(scene.camera.fovY == before.camera.fovY);
    CHECK(scene.light.direction == before.light.direction);
    CHECK(scene.sky.kind == before.sky.kind);
    CHECK(scene.sky.intensity == before.sky.intensity);
    RenderSettings s;
    applyShot(shot, s);
    CHECK(s.width == RenderSettings{}.width);
    CHECK(shotCameraPath(shot, scene.camera).empty());
    CHECK_FALSE(shot.scene);
}

TEST_CASE("shot: the environment type decides the sky") {
    Scene scene = makeBuiltinScene("cornell");
    applyShot(parseShot(R"({"environment": {"type": "constant", "color": [0.5, 1, 2]}})", "c.json"),
              scene);
    CHECK(scene.sky.kind == Sky::Kind::Constant);
    CHECK(scene.sky.zenith == glm::vec3(0.5f, 1, 2));
    applyShot(parseShot(R"({"environment": {"type": "gradient", "zenith": [1, 2, 3],
                            "ground": [0, 0, 1], "intensity": 2}})",
                        "g.json"),
              scene);
    CHECK(scene.sky.kind == Sky::Kind::Gradient);
    CHECK(scene.sky.zenith == glm::vec3(1, 2, 3));
    CHECK(scene.sky.ground == glm::vec3(0, 0, 1));
    CHECK(scene.sky.intensity == 2.0f);
    // Without a type only the intensity changes, on the scene's own sky
    applyShot(parseShot(R"({"environment": {"intensity": 0.25}})", "i.json"), scene);
    CHECK(scene.sky.kind == Sky::Kind::Gradient);
    CHECK(scene.sky.intensity == 0.25f);
}

TEST_CASE("shot: each bad input is one line naming the file and the field") {
    TempDir dir;
    const std::string file = dir.file("shot.json");
    const std::string missing = dir.file("missing.glb"), missingSky = dir.file("sky.hdr");
    const std::vector<std::pair<std::string, std::string>> cases{
        // Unknown keys (typos), at every level
        {R"({"camra": {}})",
         "camra: unknown key; did you mean camera? (expected one of: scene, camera, light, "
         "environment, render)"},
        {R"({"camera": {"fovy": 40}})",
         "camera.fovy: unknown key; did you mean fovY? (expected one of: position, "
         "target, up, fovY, near, far, path)"},
        {R"({"camera": {"path": {"keys": [{"tme": 1}]}}})",
         "camera.path.keys[0].tme: unknown key; did you mean time? (expected one of: time, "
         "position, target, fovY, "
         "cut)"},
        {R"({"environment": {"color": [1, 1, 1]}})",
         "environment.color: unknown key (expected one of: type, intensity)"},
        {R"({"environment": {"type": "gradient", "color": [1, 1, 1]}})",
         "environment.color: unknown key (expected one of: type, zenith, horizon, ground, "
         "intensity)"},
        {R"({"render": {"samples": 4}})",
         "render.samples: unknown key (expected one of: width, height, shadowMapSize, "
         "shadowBias, shadowSlopeBias, pcfRadius, exposure, idPlanes, gbufferPlanes, tracePlanes, "
         "debugPlanes, ssr, ssgi, "
         "ssrMethod, "
         "marcher, ssrSpp, ssgiSpp, traceHidden, ssgiFeedback, ssrLayout, ssrTrace, ssgiTrace, "
         "ssrSparseFrames, "
         "ssgiLayout, maxSteps, "},
        // Wrong types
        {R"([1, 2])", "expected a JSON object at the top level"},
        {R"({"camera": "front"})", "camera: expected an object"},
        {R"({"camera": {"position": [1, 2]}})",
         "camera.position: expected an array of 3 finite numbers"},
        {R"({"camera": {"position": "here"}})",
         "camera.position: expected an array of 3 finite numbers"},
        {R"({"camera": {"target": [1, "2", 3]}})",
         "camera.target: expected an array of 3 finite numbers"},
        {R"({"camera": {"fovY": "40"}})", "camera.fovY: expected a number in (0, 180)"},
        {R"({"render": {"width": 1280.0}})", "render.width: expected an integer from 1 to 8192"},
        {R"({"render": {"width": true}})", "render.width: expected an integer from 1 to 8192"},
        {R"({"scene": 5})", "scene: expected a non-empty string"},
        {R"({"camera": {"path": {"keys": {}}}})",
         "camera.path.keys: expected an array of at least one key"},
        // NaN and infinity (JSON has no literal for either; overflow is caught)
        {R"({"render": {"exposure": NaN}})", "not valid JSON: line 1, column "},
        {R"({"render": {"exposure": 1e999}})",
         "render.exposure: expected a finite number (it overflows)"},
        {R"({"camera": {"position": [1, -1e999, 0]}})",
         "camera.position[1]: expected a finite number (it overflows)"},
        {R"({"light": {"intensity": 1e39}})", "light.intensity: expected a finite number >= 0"},
        // Zero-length vectors
        {R"({"light": {"direction": [0, 0, 0]}})",
         "light.direction: expected an array of 3 finite numbers, not all 0"},
        {R"({"camera": {"up": [0, 1e-50, 0]}})",
         "camera.up: expected an array of 3 finite numbers, not all 0"},
        // Out-of-range values
        {R"({"camera": {"fovY": 180}})", "camera.fovY: expected a number in (0, 180)"},
        {R"({"camera": {"fovY": 0}})", "camera.fovY: expected a number in (0, 180)"},
        {R"({"camera": {"near": 1, "far": 0.5}})",
         "camera.far: expected a number greater than near (1)"},
        {R"({"render": {"width": 0}})", "render.width: expected an integer from 1 to 8192"},
        {R"({"render": {"height": 8193}})", "render.height: expected an integer from 1 to 8192"},
        {R"({"render": {"width": 99999999999999999999}})",
         "render.width: expected an integer from 1 to 8192"},
        {R"({"render": {"frames": 0}})", "render.frames: expected an integer from 1 to 100000"},
        {R"({"render": {"warmupFrames": -1}})",
         "render.warmupFrames: expected an integer from 0 to 100000"},
        {R"({"render": {"warmupFrames": 2.5}})",
         "render.warmupFrames: expected an integer from 0 to 100000"},
        {R"({"camera": {"path": {"keys": [{}, {"cut": 1}]}}})",
         "camera.path.keys[1].cut: expected true or false"},
        {R"({"camera": {"path": {"keys": [{"cut": true}, {}]}}})",
         "camera.path.keys[0].cut: the first key cannot be a cut"},
        {R"({"render": {"frame": 4294967296}})",
         "render.frame: expected an integer from 0 to 4294967295"},
        {R"({"render": {"shadowMapSize": 8}})",
         "render.shadowMapSize: expected an integer from 16 to 8192"},
        {R"({"render": {"exposure": 0}})", "render.exposure: expected a finite number > 0"},
        {R"({"light": {"color": [1, -0.1, 1]}})",
         "light.color: expected an array of 3 finite numbers >= 0"},
        {R"({"environment": {"intensity": -1}})",
         "environment.intensity: expected a finite number >= 0"},
        {R"({"camera": {"path": {"keys": [{"time": 1}, {"time": 0.5}]}}})",
         "camera.path.keys[1].time: expected a time greater than the previous key's (1)"},
        {R"({"camera": {"path": {"interpolation": "cubic", "keys": [{}]}}})",
         "camera.path.interpolation: expected \"catmull-rom\" or \"linear\""},
        // Names and files
        {R"({"scene": "teapot"})",
         "scene: unknown scene 'teapot' (known: " + builtinScenes().front().name},
        {R"({"scene": "missing.glb"})", "scene: no such file '" + missing + "'"},
        {R"({"environment": {"type": "image"}})",
         "environment.file: required when type is \"image\""},
        {R"({"environment": {"type": "image", "file": "sky.hdr"}})",
         "environment.file: no such file '" + missingSky + "'"},
        {R"({"environment": {"type": "sky"}})",
         "environment.type: expected \"constant\", \"gradient\" or \"image\""},
        // Syntax and duplicates
        {R"({"camera": {"fovY": 40,}})", "not valid JSON: line 1, column "},
        {R"({"camera": {"fovY": 40, "fovY": 50}})", "camera.fovY: duplicate key"},
        {R"({"camera": {"path": {"keys": [{"time": 0}, {"time": 1, "time": 2}]}}})",
         "camera.path.keys[1].time: duplicate key"},
    };
    // (no structured binding: clang 14 cannot capture one in CAPTURE's lambda)
    for (const auto& entry : cases) {
        const std::string& text = entry.first;
        const std::string& expected = entry.second;
        CAPTURE(text);
        writeFile(file, text);
        std::string message;
        try {
            // The render settings are checked as they are applied (cli/shot_settings.h).
            RenderSettings settings;
            applyShot(loadShot(file), settings);
        } catch (const ShotError& e) {
            message = e.what();
        }
        CHECK(message.rfind(file + ": " + expected, 0) == 0);
        CHECK(message.find('\n') == std::string::npos);
        if (message.rfind(file + ": " + expected, 0) != 0) MESSAGE("got: " << message);
    }
}

TEST_CASE("shot: a camera that cannot look anywhere is named") {
    Scene scene = makeBuiltinScene("cornell");
    const auto fails = [&](const std::string& text, const std::string& expected) {
        CAPTURE(text);
        const Shot shot = parseShot(text, "s.json");
        std::string message;
        try {
            Scene copy = scene;
            applyShot(shot, copy);
            shotCameraPath(shot, copy.camera);
        } catch (const ShotError& e) {
            message = e.what();
        }
        CHECK(message == "s.json: " + expected);
    };
    fails(R"({"camera": {"position": [1, 1, 1], "target": [1, 1, 1]}})",
          "camera: position and target are the same point");
    fails(R"({"camera": {"position": [0, 0, 0], "target": [0, 2, 0]}})",
          "camera: up is parallel to the view direction");
    fails(R"({"camera": {"target": [0, 0, 0], "path": {"keys": [{"position": [0, 0, 0]}]}}})",
          "camera.path.keys[0]: position and target are the same point");
    fails(R"({"camera": {"far": 0.01}})", "camera: far (0.01) must be greater than near (0.05)");
}

TEST_CASE("shot: a missing or unreadable shot file is one line") {
    TempDir dir;
    for (const std::string& path : {dir.file("nope.json"), dir.path.string()}) {
        CAPTURE(path);
        std::string message;
        try {
            loadShot(path);
        } catch (const ShotError& e) {
            message = e.what();
        }
        CHECK(message.rfind(path + ": ", 0) == 0);
        CHECK(message.find('\n') == std::string::npos);
    }
}
