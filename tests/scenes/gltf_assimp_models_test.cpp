// Every glTF 2.0 file of Debian's assimp-testmodels (/usr/share/assimp/models/glTF2) either
// renders (64x36, default settings, finite colour) or is refused with a SceneLoadError that
// names the file and the problem. The files expected to be refused are listed below with a
// piece of their reason; every other file must render, so a new file in the package that is
// neither listed nor renders fails the test, and so does a listed file that now loads.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "renderer/renderer.h"
#include "scenes/gltf_loader.h"

namespace {

namespace fs = std::filesystem;

const char* const kModels = "/usr/share/assimp/models/glTF2";

// Relative path -> a piece of the refusal. Most of these files exist to test a loader's
// errors; the others hold nothing ssrt can draw.
const std::map<std::string, std::string> kRefused = {
    {"BoxTextured-glTF-techniqueWebGL/BoxTextured.gltf",
     "extension KHR_technique_webgl is required but not supported"},
    {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite"},
    {"IncorrectVertexArrays/Cube.gltf", "vertices is not a multiple of 3"},
    {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "out of range"},
    {"IndexOutOfRange/IndexOutOfRange.gltf", "out of range"},
    {"MissingBin/BoxTextured.gltf", "File not found"},
    {"RecursiveNodes/RecursiveNodes.gltf", "no meshes"},
    // Meant to test "scene" of the wrong type; its buffer file is not in the package either,
    // and that is found first.
    {"SchemaFailures/sceneWrongType.gltf", "File not found"},
    {"TestNoRootNode/NoScene.gltf", "no meshes"},
    {"TestNoRootNode/SceneWithoutNodes.gltf", "no meshes"},
    // Points and lines only: skipped, which leaves no triangles.
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf", "no triangles"},
    {"glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf", "no triangles"},
    // A mesh whose "primitives" is an object: tinygltf reads no primitives.
    {"wrongTypes/badArray.gltf", "no triangles"},
    {"wrongTypes/badNumber.gltf", "'index' property is missing"},
};

std::vector<std::string> modelFiles() {
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(kModels)) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb"))
            files.push_back(fs::relative(e.path(), kModels).string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

bool finiteColour(const ssrt::Frame& f) {
    for (const ssrt::PlaneF& plane : f.rgb(ssrt::Res::Color))
        for (int y = 0; y < plane.height(); ++y)
            for (int x = 0; x < plane.width(); ++x)
                if (!std::isfinite(plane.at(x, y))) return false;
    return true;
}

}  // namespace

TEST_CASE("gltf assimp-testmodels: every glTF 2.0 file renders or is refused with its reason") {
    if (!fs::is_directory(kModels)) {
        MESSAGE("skipped: assimp-testmodels is not installed (" << kModels << ")");
        return;
    }
    ssrt::RenderSettings rs;
    rs.width = 64;
    rs.height = 36;
    const ssrt::Renderer renderer(rs);
    const std::vector<std::string> files = modelFiles();
    std::size_t rendered = 0, refused = 0;
    for (const std::string& file : files) {
        const std::string path = std::string(kModels) + "/" + file;
        CAPTURE(path);
        const auto expected = kRefused.find(file);
        try {
            const ssrt::Scene scene = ssrt::loadGltf(path);
            CHECK_MESSAGE(expected == kRefused.end(), "loads, but is listed as refused");
            CHECK(finiteColour(renderer.renderWithoutHistory(scene)));
            ++rendered;
        } catch (const ssrt::SceneLoadError& e) {
            const std::string msg = e.what();
            CAPTURE(msg);
            CHECK(msg.rfind(path + ": ", 0) == 0);
            CHECK(msg.find('\n') == std::string::npos);
            if (expected == kRefused.end()) {
                FAIL_CHECK("refused, but not listed as refused");
            } else {
                CHECK(msg.find(expected->second) != std::string::npos);
                ++refused;
            }
        }
    }
    for (const auto& listed : kRefused) {
        const std::string& file = listed.first;  // a structured binding: clang 14 cannot CAPTURE
        CAPTURE(file);
        CHECK(std::find(files.begin(), files.end(), file) != files.end());
    }
    MESSAGE(files.size() << " files: " << rendered << " rendered, " << refused << " refused");
    CHECK(rendered + refused == files.size());
}
