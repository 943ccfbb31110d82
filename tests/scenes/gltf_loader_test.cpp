// The glTF loader: round trips of small files written here, and a corpus of malformed files
// that must each give one clear SceneLoadError (never a crash, a hang or a partial scene).
#include "scenes/gltf_loader.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/glm.hpp>
#include <limits>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "temp_dir.h"

using ssrt::loadGltf;
using ssrt::SceneLoadError;
using ssrt::test::TempDir;

using ssrt::test::base64;
using ssrt::test::checkRefused;
using ssrt::test::loadError;
using ssrt::test::writeFile;

namespace {

// What a test may change in the one-triangle file that every case starts from.
struct Knobs {
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<uint16_t> indices = {0, 1, 2};  // empty: a non-indexed primitive
    int mode = 4;
    int positionCount = -1;  // -1: the real count
    std::string bufferUri;   // empty: embedded as a data: URI
    std::string nodes = R"([{"mesh": 0}])";
    std::string scenes = R"([{"nodes": [0]}])";
    std::string meshes;  // empty: the triangle's mesh
    std::string extra;   // more top-level members, each starting with a comma
    std::string material = R"(, "material": 0)";
};

std::vector<unsigned char> binOf(const Knobs& k) {
    std::vector<unsigned char> bin(k.positions.size() * 4 + k.indices.size() * 2);
    std::memcpy(bin.data(), k.positions.data(), k.positions.size() * 4);
    std::memcpy(bin.data() + k.positions.size() * 4, k.indices.data(), k.indices.size() * 2);
    while (bin.size() % 4) bin.push_back(0);
    return bin;
}

// uri: "" embeds the buffer, "-" leaves it out (GLB), anything else names a file.
std::string jsonOf(const Knobs& k, const std::string& uri) {
    const std::size_t posBytes = k.positions.size() * 4, idxBytes = k.indices.size() * 2;
    const std::size_t vertices = k.positionCount >= 0 ? k.positionCount : k.positions.size() / 3;
    std::string buffer = R"({"byteLength": )" + std::to_string(binOf(k).size());
    if (uri.empty())
        buffer += R"(, "uri": "data:application/octet-stream;base64,)" + base64(binOf(k)) + "\"";
    else if (uri != "-") buffer += R"(, "uri": ")" + uri + "\"";
    buffer += "}";
    std::string views =
        R"([{"buffer": 0, "byteOffset": 0, "byteLength": )" + std::to_string(posBytes) + "}";
    std::string accessors = R"([{"bufferView": 0, "componentType": 5126, "type": "VEC3", )"
                            R"("count": )" +
                            std::to_string(vertices) + "}";
    std::string indices;
    if (!k.indices.empty()) {
        views += R"(, {"buffer": 0, "byteOffset": )" + std::to_string(posBytes) +
                 R"(, "byteLength": )" + std::to_string(idxBytes) + "}";
        accessors += R"(, {"bufferView": 1, "componentType": 5123, "type": "SCALAR", )"
                     R"("count": )" +
                     std::to_string(k.indices.size()) + "}";
        indices = R"(, "indices": 1)";
    }
    const std::string meshes =
        !k.meshes.empty() ? k.meshes
                          : R"([{"primitives": [{"attributes": {"POSITION": 0}, "mode": )" +
                                std::to_string(k.mode) + indices + k.material + "}]}]";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": )" + k.scenes + R"(, "nodes": )" +
           k.nodes + R"(, "meshes": )" + meshes +
           R"(, "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1],)"
           R"( "metallicFactor": 0.3, "roughnessFactor": 0.7}, "emissiveFactor": [1, 0.5, 0],)"
           R"( "doubleSided": true}], "buffers": [)" +
           buffer + R"(], "bufferViews": )" + views + R"(], "accessors": )" + accessors + "]" +
           k.extra + "}";
}

std::string writeGltf(const TempDir& dir, const std::string& name, const Knobs& k) {
    const std::string path = dir.file(name);
    if (!k.bufferUri.empty()) {
        const std::vector<unsigned char> bin = binOf(k);
        writeFile(dir.file(k.bufferUri), std::string(bin.begin(), bin.end()));
    }
    writeFile(path, jsonOf(k, k.bufferUri));
    return path;
}

// The knobs' file as a GLB (the buffer in its BIN chunk).
std::string glbOf(const Knobs& k) { return ssrt::test::glbOf(jsonOf(k, "-"), binOf(k)); }

// The hierarchy, material, camera and light that the round trips check.
Knobs richKnobs() {
    Knobs k;
    // Node 0 translates; its child 1 moves by +Z, turns 90 degrees about +Y and scales by 2.
    k.nodes = R"([{"translation": [1, 2, 3], "children": [1]},)"
              R"( {"translation": [0, 0, 1], "rotation": [0, 0.70710678, 0, 0.70710678],)"
              R"(  "scale": [2, 2, 2], "mesh": 0},)"
              R"( {"translation": [0, 0, 5], "camera": 0},)"
              R"( {"rotation": [-0.70710678, 0, 0, 0.70710678],)"
              R"(  "extensions": {"KHR_lights_punctual": {"light": 0}}}])";
    k.scenes = R"([{"nodes": [0, 2, 3]}])";
    k.extra = R"(, "cameras": [{"type": "perspective", "perspective": )"
              R"({"yfov": 0.8, "znear": 0.1, "zfar": 50, "aspectRatio": 1.5}}],)"
              R"( "extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual":)"
              R"( {"lights": [{"type": "directional", "color": [1, 0.9, 0.8], "intensity": 4}]}})";
    return k;
}

void closeTo(glm::vec3 a, glm::vec3 b) {
    CHECK(a.x == doctest::Approx(b.x).epsilon(1e-5));
    CHECK(a.y == doctest::Approx(b.y).epsilon(1e-5));
    CHECK(a.z == doctest::Approx(b.z).epsilon(1e-5));
}

void checkRichScene(const ssrt::Scene& s) {
    REQUIRE(s.meshes.size() == 1);
    REQUIRE(s.instances.size() == 1);
    closeTo(s.meshes[0].positions[1], {1, 0, 0});
    CHECK(s.meshes[0].indices == std::vector<uint32_t>{0, 1, 2});
    // (1,0,0): scaled to (2,0,0), turned about +Y to (0,0,-2), moved by (0,0,1), then (1,2,3).
    const ssrt::Instance& inst = s.instances[0];
    closeTo(glm::vec3(inst.transform * glm::vec4(1, 0, 0, 1)), {1, 2, 2});
    CHECK(inst.previousTransform == inst.transform);
    const ssrt::Material& m = s.materials[inst.material];
    closeTo(m.baseColor, {0.2f, 0.4f, 0.6f});
    CHECK(m.metallic == doctest::Approx(0.3));
    CHECK(m.roughness == doctest::Approx(0.7));
    closeTo(m.emissive, {1, 0.5f, 0});
    CHECK(m.doubleSided);
    closeTo(s.camera.position, {0, 0, 5});
    // Looking down -Z (the look-at point lies as far out as the camera is from 0).
    closeTo(glm::normalize(s.camera.target - s.camera.position), {0, 0, -1});
    closeTo(s.camera.up, {0, 1, 0});
    CHECK(s.camera.fovY == doctest::Approx(0.8 * 180.0 / 3.14159265358979));
    CHECK(s.camera.nearZ == doctest::Approx(0.1));
    CHECK(s.camera.farZ == doctest::Approx(50));
    closeTo(s.previousCamera.position, s.camera.position);
    // The light node turns -Z (the way glTF lights shine) to straight down.
    closeTo(s.light.direction, {0, -1, 0});
    closeTo(s.light.color, {1, 0.9f, 0.8f});
    CHECK(s.light.intensity == doctest::Approx(4));
}

}  // namespace

TEST_CASE("gltf: an embedded-buffer .gltf round-trips transforms, material, camera, light") {
    TempDir dir("gltf");
    checkRichScene(loadGltf(writeGltf(dir, "rich.gltf", richKnobs())));
}

TEST_CASE("gltf: an external buffer file loads the same") {
    TempDir dir("gltf");
    Knobs k = richKnobs();
    k.bufferUri = "rich.bin";
    checkRichScene(loadGltf(writeGltf(dir, "rich.gltf", k)));
}

TEST_CASE("gltf: a hand-written .glb round-trips the same") {
    TempDir dir("gltf");
    writeFile(dir.file("rich.glb"), glbOf(richKnobs()));
    checkRichScene(loadGltf(dir.file("rich.glb")));
}

TEST_CASE("gltf: strips and fans become the triangles the spec lists") {
    TempDir dir("gltf");
    Knobs k;
    k.indices.clear();
    k.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    k.mode = 5;
    CHECK(loadGltf(writeGltf(dir, "strip.gltf", k)).meshes[0].indices ==
          std::vector<uint32_t>{0, 1, 2, 1, 3, 2});
    k.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    k.mode = 6;
    const ssrt::Scene fan = loadGltf(writeGltf(dir, "fan.gltf", k));
    CHECK(fan.meshes[0].indices == std::vector<uint32_t>{1, 2, 0, 2, 3, 0});
    // Both keep the counter-clockwise winding, so computed normals face +Z.
    for (const glm::vec3& n : fan.meshes[0].normals) closeTo(n, {0, 0, 1});
}

TEST_CASE("gltf: missing normals are computed, unit length, facing the front side") {
    TempDir dir("gltf");
    Knobs k;
    const ssrt::Scene front = loadGltf(writeGltf(dir, "front.gltf", k));
    REQUIRE(front.meshes[0].normals.size() == 3);
    for (const glm::vec3& n : front.meshes[0].normals) closeTo(n, {0, 0, 1});
    k.indices = {0, 2, 1};  // clockwise seen from +Z: the front faces -Z
    const ssrt::Scene back = loadGltf(writeGltf(dir, "back.gltf", k));
    for (const glm::vec3& n : back.meshes[0].normals) closeTo(n, {0, 0, -1});
}

TEST_CASE("gltf: no material gives glTF's default -- no camera gives one fitted to the bounds") {
    TempDir dir("gltf");
    Knobs k;
    k.material.clear();
    const ssrt::Scene s = loadGltf(writeGltf(dir, "plain.gltf", k));
    const ssrt::Material& m = s.materials[s.instances[0].material];
    CHECK(m.metallic == 1.0f);
    CHECK(m.roughness == 1.0f);
    closeTo(m.baseColor, {1, 1, 1});
    // The fitted camera looks at the centre of the bounds from in front.
    closeTo(s.camera.target, {0.5f, 0.5f, 0});
    CHECK(s.camera.position.z > 0.0f);
    CHECK(s.camera.nearZ < glm::length(s.camera.position - s.camera.target) - 0.71f);
    CHECK(s.camera.farZ > glm::length(s.camera.position - s.camera.target) + 0.71f);
    closeTo(s.previousCamera.position, s.camera.position);
}

TEST_CASE("gltf: malformed files each give one clear error naming the file and the problem") {
    TempDir dir("gltf-bad");
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    Knobs k;

    SUBCASE("index out of range") {
        k.indices = {0, 1, 7};
        checkRefused(writeGltf(dir, "index.gltf", k), "accessor 1 (indices): index 7 out of range");
    }
    SUBCASE("accessor count overruns its buffer view") {
        k.positionCount = 4;
        checkRefused(writeGltf(dir, "overrun.gltf", k), "overruns");
    }
    SUBCASE("NaN position") {
        k.positions[4] = nan;
        checkRefused(writeGltf(dir, "nan.gltf", k), "accessor 0 (POSITION): non-finite");
    }
    SUBCASE("infinite position") {
        k.positions[8] = -inf;
        checkRefused(writeGltf(dir, "inf.gltf", k), "accessor 0 (POSITION): non-finite");
    }
    SUBCASE("missing buffer file") {
        const std::string path = dir.file("nobuffer.gltf");
        writeFile(path, jsonOf(k, "missing.bin"));
        checkRefused(path, "missing.bin");
    }
    SUBCASE("wrong JSON type") {
        k.meshes = "5";
        checkRefused(writeGltf(dir, "type.gltf", k), "\"meshes\" must be a JSON array");
        writeFile(dir.file("type.glb"), glbOf(k));
        checkRefused(dir.file("type.glb"), "\"meshes\" must be a JSON array");
    }
    SUBCASE("wrong JSON type inside an object (reported by tinygltf)") {
        std::string json = jsonOf(k, "");
        json.replace(json.find(R"("count": 3)"), 10, R"("count": "3")");
        writeFile(dir.file("count.gltf"), json);
        checkRefused(dir.file("count.gltf"), "count");
    }
    SUBCASE("a node that is its own child") {
        k.nodes = R"([{"mesh": 0, "children": [0]}])";
        checkRefused(writeGltf(dir, "self.gltf", k), "its own ancestor");
    }
    SUBCASE("a node that is its own grandparent") {
        k.nodes = R"([{"mesh": 0, "children": [1]}, {"children": [0]}])";
        checkRefused(writeGltf(dir, "cycle.gltf", k), "node 0 is its own ancestor");
    }
    SUBCASE("scene index out of range") {
        k.extra = R"(, "scene": 3)";
        checkRefused(writeGltf(dir, "scene.gltf", k), "scene");
    }
    SUBCASE("zero meshes") {
        k.meshes = "[]";
        k.nodes = "[{}]";
        checkRefused(writeGltf(dir, "empty.gltf", k), "no meshes");
    }
    SUBCASE("only POINTS: no triangles") {
        k.mode = 0;
        checkRefused(writeGltf(dir, "points.gltf", k),
                     "no triangles (1 point or line primitive skipped");
    }
    SUBCASE("only LINES: no triangles") {
        k.mode = 1;
        checkRefused(writeGltf(dir, "lines.gltf", k),
                     "no triangles (1 point or line primitive skipped");
    }
    SUBCASE("a texture whose image file does not exist is refused") {
        k.extra = R"(, "textures": [{"source": 0}], "images": [{"uri": "nope.png"}])";
        std::string json = jsonOf(k, "");
        const std::string factor = R"("baseColorFactor")";
        json.replace(json.find(factor), 0, R"("baseColorTexture": {"index": 0}, )");
        writeFile(dir.file("texture.gltf"), json);
        checkRefused(dir.file("texture.gltf"), "nope.png");
    }
    SUBCASE("a file that does not exist") {
        checkRefused(dir.file("absent.gltf"), "cannot open file (No such file or directory)");
    }
    SUBCASE("not JSON at all") {
        writeFile(dir.file("garbage.gltf"), "{\"asset\": [1, 2");
        loadError(dir.file("garbage.gltf"));
    }
    SUBCASE("a truncated .glb") {
        const std::string glb = glbOf(k);
        for (std::size_t cut : {4u, 12u, 20u, 40u, unsigned(glb.size() - 3)}) {
            writeFile(dir.file("cut.glb"), glb.substr(0, cut));
            loadError(dir.file("cut.glb"));
        }
    }
}

// ---------------------------------------------------------------------------------------
// Warnings: what a file holds beyond what ssrt renders is one line per kind, never a silent
// drop; --strict (GltfLoadOptions::strict) makes the first an error.

namespace {

std::vector<std::string> warningsOf(const std::string& path) {
    ssrt::GltfLoadReport report;
    loadGltf(path, {}, &report);
    return report.warnings;
}

// The triangle, then a POINTS and a LINES primitive over the same vertices.
Knobs mixedPrimitives() {
    Knobs k;
    k.meshes = R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0},)"
               R"( {"attributes": {"POSITION": 0}, "mode": 0},)"
               R"( {"attributes": {"POSITION": 0}, "indices": 1, "mode": 1}]}])";
    return k;
}

// Node 0 the mesh; nodes 1.. each place one light (of `lights`) or camera (of `cameras`).
Knobs withLights(const std::string& lights, int count) {
    Knobs k;
    k.nodes = R"([{"mesh": 0})";
    k.scenes = R"([{"nodes": [0)";
    for (int i = 0; i < count; ++i) {
        k.nodes +=
            R"(, {"extensions": {"KHR_lights_punctual": {"light": )" + std::to_string(i) + "}}}";
        k.scenes += ", " + std::to_string(i + 1);
    }
    k.nodes += "]";
    k.scenes += "]}]";
    k.extra = R"(, "extensionsUsed": ["KHR_lights_punctual"], "extensions": )"
              R"({"KHR_lights_punctual": {"lights": )" +
              lights + "}}";
    return k;
}

}  // namespace

TEST_CASE("gltf warnings: a plain file, or one with everything ssrt supports, warns of nothing") {
    TempDir dir("gltf-warn");
    CHECK(warningsOf(writeGltf(dir, "plain.gltf", Knobs{})).empty());
    CHECK(warningsOf(writeGltf(dir, "rich.gltf", richKnobs())).empty());
    Knobs k = richKnobs();
    k.extra += R"(, "extensionsRequired": ["KHR_lights_punctual"])";
    CHECK(warningsOf(writeGltf(dir, "required.gltf", k)).empty());
}

TEST_CASE("gltf warnings: points and lines are skipped with one line, the triangles load") {
    TempDir dir("gltf-warn");
    const std::string path = writeGltf(dir, "mixed.gltf", mixedPrimitives());
    ssrt::GltfLoadReport report;
    const ssrt::Scene s = loadGltf(path, {}, &report);
    REQUIRE(s.meshes.size() == 1);
    CHECK(s.meshes[0].indices == std::vector<uint32_t>{0, 1, 2});
    CHECK(s.instances.size() == 1);
    CHECK(s.triangleCount() == 1);
    CHECK(report.warnings ==
          std::vector<std::string>{path + ": 2 point and line primitives skipped (only triangles, "
                                          "strips and fans are rendered)"});
    // The old entry point loads the same scene and says nothing.
    CHECK(loadGltf(path).triangleCount() == 1);
}

// A camera under a node that mirrors and stretches its Z by 2 (scenes/gltf_camera.h): it
// keeps an orthonormal view, scales znear and zfar by 2, and each departure is a warning.
TEST_CASE("gltf warnings: a camera under a scaled, mirroring node is placed and each change said") {
    TempDir dir("gltf-warn");
    Knobs k = richKnobs();
    k.nodes = R"([{"mesh": 0}, {"scale": [1, 1, -2], "children": [2]},)"
              R"( {"translation": [0, 0, 5], "camera": 0}])";
    k.scenes = R"([{"nodes": [0, 1]}])";
    const std::string path = writeGltf(dir, "mirror.gltf", k);
    ssrt::GltfLoadReport report;
    const ssrt::Scene s = loadGltf(path, {}, &report);
    // At (0, 0, -10), its -Z turned to +Z by the mirror: it faces the triangle at z = 0.
    closeTo(s.camera.position, {0, 0, -10});
    closeTo(glm::normalize(s.camera.target - s.camera.position), {0, 0, 1});
    closeTo(s.camera.up, {0, 1, 0});
    CHECK(s.camera.nearZ == doctest::Approx(0.2));
    CHECK(s.camera.farZ == doctest::Approx(100));
    const std::string cam = path + ": camera 0: its node ";
    CHECK(report.warnings ==
          std::vector<std::string>{
              cam + "scales by 2 along the view axis: znear and zfar are scaled with it "
                    "(0.1 -> 0.2, 50 -> 100), where glTF ignores a camera's scale",
              cam + "scales unevenly or shears: the view is orthonormalised (along its -Z, up "
                    "from its +Y)",
              cam + "mirrors: the mirror is ignored (the image is not flipped)"});
}

// What the far plane hides is said, not dropped in silence: every pass leaves it off screen.
TEST_CASE("gltf warnings: triangles wholly beyond the camera's far plane are counted") {
    TempDir dir("gltf-warn");
    Knobs k = richKnobs();
    k.nodes = R"([{"mesh": 0}, {"translation": [0, 0, 5], "camera": 0}])";
    k.scenes = R"([{"nodes": [0, 1]}])";
    k.extra = R"(, "cameras": [{"type": "perspective", "perspective": )"
              R"({"yfov": 0.8, "znear": 0.1, "zfar": 4}}])";
    const std::string path = writeGltf(dir, "far.gltf", k);
    CHECK(warningsOf(path) ==
          std::vector<std::string>{path + ": camera 0: 1 of 1 triangles lie wholly beyond its far "
                                          "plane (4 scene units) and are not drawn"});
}

TEST_CASE("gltf warnings: a required extension ssrt cannot honour is an error naming it") {
    TempDir dir("gltf-warn");
    Knobs k;
    k.extra = R"(, "extensionsUsed": ["KHR_materials_sheen"],)"
              R"( "extensionsRequired": ["KHR_materials_sheen"])";
    checkRefused(writeGltf(dir, "sheen.gltf", k),
                 "extension KHR_materials_sheen is required but not supported");
    // Volume is not applied, so a file that requires it is refused too.
    k.extra = R"(, "extensionsUsed": ["KHR_materials_volume", "KHR_materials_transmission"],)"
              R"( "extensionsRequired": ["KHR_materials_volume", "KHR_materials_transmission",)"
              R"( "KHR_materials_emissive_strength", "KHR_texture_transform",)"
              R"( "KHR_draco_mesh_compression", "EXT_meshopt_compression"])";
    checkRefused(writeGltf(dir, "two.gltf", k),
                 "extensions KHR_materials_volume and KHR_materials_transmission are "
                 "required but not supported");
}

TEST_CASE("gltf warnings: an extension used but not supported is one line naming each") {
    TempDir dir("gltf-warn");
    Knobs k;
    k.extra = R"(, "extensionsUsed": ["KHR_materials_clearcoat"])";
    std::string path = writeGltf(dir, "clearcoat.gltf", k);
    CHECK(warningsOf(path) ==
          std::vector<std::string>{path + ": extension KHR_materials_clearcoat is used but not "
                                          "supported: ignored"});
    k.extra = R"(, "extensionsUsed": ["KHR_materials_sheen", "KHR_lights_punctual",)"
              R"( "KHR_texture_transform", "KHR_materials_clearcoat"])";
    path = writeGltf(dir, "two.gltf", k);
    CHECK(warningsOf(path) ==
          std::vector<std::string>{path + ": extensions KHR_materials_sheen and "
                                          "KHR_materials_clearcoat are used but not supported: "
                                          "ignored"});
}

TEST_CASE("gltf warnings: point and spot lights are one line -- the directional light is used") {
    TempDir dir("gltf-warn");
    const std::string path = writeGltf(
        dir, "lights.gltf",
        withLights(R"([{"type": "point"}, {"type": "spot", "spot": {}}, {"type": "point"},)"
                   R"( {"type": "directional", "intensity": 3}, {"type": "directional"}])",
                   5));
    ssrt::GltfLoadReport report;
    const ssrt::Scene s = loadGltf(path, {}, &report);
    CHECK(s.light.intensity == doctest::Approx(3));
    CHECK(report.warnings ==
          std::vector<std::string>{
              path + ": 2 point lights and 1 spot light ignored (only directional lights are "
                     "supported)",
              path + ": 1 directional light after the first ignored (one directional light is "
                     "used)"});
}

TEST_CASE("gltf warnings: cameras other than the first perspective one are named") {
    TempDir dir("gltf-warn");
    Knobs k;
    k.nodes = R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]}, {"camera": 1},)"
              R"( {"camera": 2}, {"camera": 3}])";
    k.scenes = R"([{"nodes": [0, 1, 2, 3, 4]}])";
    const std::string persp =
        R"({"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}})";
    k.extra = R"(, "cameras": [{"type": "orthographic", "orthographic": )"
              R"({"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}, )" +
              persp + ", " + persp + ", " + persp + "]";
    const std::string path = writeGltf(dir, "cameras.gltf", k);
    ssrt::GltfLoadReport report;
    const ssrt::Scene s = loadGltf(path, {}, &report);
    closeTo(s.camera.position, {0, 0, 0});  // camera 1's node, not camera 0's
    CHECK(report.warnings ==
          std::vector<std::string>{
              path + ": cameras 2 and 3 ignored (the first perspective camera, camera 1, is used)",
              path + ": orthographic camera 0 ignored (only perspective cameras are supported)"});
}

// BLEND is not blended: the one line says what is drawn instead and counts the materials.
TEST_CASE("gltf warnings: alphaMode BLEND says what is drawn, once, counting the materials") {
    TempDir dir("gltf-warn");
    std::string json = jsonOf(Knobs{}, "");
    const std::string material =
        R"({"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1],)"
        R"( "metallicFactor": 0.3, "roughnessFactor": 0.7}, "emissiveFactor": [1, 0.5, 0],)"
        R"( "doubleSided": true})";
    REQUIRE(json.find(material) != std::string::npos);
    // Materials 0 and 2 of four blend; the triangle uses material 0.
    json.replace(json.find(material), material.size(),
                 R"({"alphaMode": "BLEND"}, {"alphaMode": "MASK"}, {"alphaMode": "BLEND"}, {})");
    const std::string path = dir.file("blend.gltf");
    writeFile(path, json);
    CHECK(warningsOf(path) ==
          std::vector<std::string>{
              path + ": alphaMode BLEND is drawn as MASK with alphaCutoff 0.5, not blended: where "
                     "alpha is 0.5 or more the surface is opaque, elsewhere it is not drawn (2 "
                     "materials: 0 and 2)"});
}

TEST_CASE("gltf warnings: strict makes the first warning an error, with no scene") {
    TempDir dir("gltf-warn");
    const std::string path = writeGltf(dir, "mixed.gltf", mixedPrimitives());
    ssrt::GltfLoadReport report;
    report.warnings = {"stale"};
    try {
        loadGltf(path, ssrt::GltfLoadOptions{true}, &report);
        FAIL("strict mode loaded a file with a warning");
    } catch (const SceneLoadError& e) {
        const std::string msg = e.what();
        INFO(msg);
        CHECK(msg.rfind(path + ": 2 point and line primitives skipped", 0) == 0);
        CHECK(msg.find("strict") != std::string::npos);
    }
    CHECK(report.warnings.empty());
    // A file without warnings loads the same in strict mode.
    CHECK(loadGltf(writeGltf(dir, "plain.gltf", Knobs{}), ssrt::GltfLoadOptions{true}, nullptr)
              .triangleCount() == 1);
}

TEST_CASE("gltf materials: KHR_materials_emissive_strength multiplies emissiveFactor") {
    TempDir dir("gltf-emissive");
    const auto withStrength = [&](const std::string& ext) {
        std::string json = jsonOf(Knobs{}, "");
        const std::string at = R"("doubleSided")";
        json.replace(json.find(at), 0,
                     R"("extensions": {"KHR_materials_emissive_strength": )" + ext + "}, ");
        const std::string path = dir.file("strength.gltf");
        writeFile(path, json);
        return path;
    };
    const ssrt::Scene s = loadGltf(withStrength(R"({"emissiveStrength": 4})"));
    CHECK(s.materials[s.instances[0].material].emissive == glm::vec3(4.0f, 2.0f, 0.0f));
    const ssrt::Scene d = loadGltf(withStrength("{}"));
    CHECK(d.materials[d.instances[0].material].emissive == glm::vec3(1.0f, 0.5f, 0.0f));
    checkRefused(withStrength(R"({"emissiveStrength": -1})"), "emissiveStrength");
}

TEST_CASE("gltf materials: alphaMode, alphaCutoff and baseColorFactor's alpha are read") {
    TempDir dir("gltf-alpha");
    // The one-triangle file with `members` in its material and baseColorFactor's alpha `a`.
    const auto withAlpha = [&](const std::string& members, const std::string& a = "1") {
        std::string json = jsonOf(Knobs{}, "");
        const std::string factor = "[0.2, 0.4, 0.6, 1]";
        json.replace(json.find(factor), factor.size(), "[0.2, 0.4, 0.6, " + a + "]");
        json.replace(json.find(R"("doubleSided")"), 0, members);
        const std::string path = dir.file("alpha.gltf");
        writeFile(path, json);
        return path;
    };
    const auto materialOf = [](const ssrt::Scene& s) {
        return s.materials[s.instances[0].material];
    };
    using Mode = ssrt::Material::AlphaMode;

    const ssrt::Scene opaque = loadGltf(withAlpha("", "0.25"));
    CHECK(materialOf(opaque).alphaMode == Mode::Opaque);
    CHECK(materialOf(opaque).baseColorAlpha == 0.25f);
    CHECK(materialOf(opaque).alphaCutoff == 0.5f);

    ssrt::GltfLoadReport report;
    const ssrt::Scene mask =
        loadGltf(withAlpha(R"("alphaMode": "MASK", "alphaCutoff": 0.75, )"), {}, &report);
    CHECK(materialOf(mask).alphaMode == Mode::Mask);
    CHECK(materialOf(mask).alphaCutoff == 0.75f);
    CHECK(materialOf(mask).baseColorAlpha == 1.0f);
    CHECK(report.warnings.empty());  // MASK is honoured: no warning
    // The cutoff defaults to 0.5.
    CHECK(materialOf(loadGltf(withAlpha(R"("alphaMode": "MASK", )"))).alphaCutoff == 0.5f);

    // BLEND: drawn as MASK at 0.5 whatever alphaCutoff says (the spec has it ignored), with
    // one warning line.
    const std::string blend = withAlpha(R"("alphaMode": "BLEND", "alphaCutoff": 0.9, )");
    const ssrt::Scene b = loadGltf(blend, {}, &report);
    CHECK(materialOf(b).alphaMode == Mode::Blend);
    CHECK(materialOf(b).alphaTested());
    CHECK(materialOf(b).alphaCutoff == 0.5f);
    CHECK(report.warnings ==
          std::vector<std::string>{blend + ": alphaMode BLEND is drawn as MASK with alphaCutoff "
                                           "0.5, not blended: where alpha is 0.5 or more the "
                                           "surface is opaque, elsewhere it is not drawn (1 "
                                           "material: 0)"});

    checkRefused(withAlpha(R"("alphaMode": "ADD", )"),
                 "alphaMode 'ADD' is not OPAQUE, MASK or BLEND");
    checkRefused(withAlpha(R"("alphaMode": "MASK", "alphaCutoff": -0.5, )"), "alphaCutoff");
}
