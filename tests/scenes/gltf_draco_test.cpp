// KHR_draco_mesh_compression: the committed Draco box (tests/scenes/data/draco_box.gltf,
// written by gen_draco_box.cpp) decodes to the box it was made from, accessors that disagree
// with the decoded mesh are refused naming the primitive, and Debian's assimp-testmodels copy
// of 2CylinderEngine renders like its uncompressed copy.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>

#include "renderer/renderer.h"
#include "scenes/gltf_loader.h"
#include "scenes/gltf_test_files.h"
#include "temp_dir.h"
#include "truth/image_error.h"

using ssrt::loadGltf;
using ssrt::SceneLoadError;
using ssrt::test::TempDir;

using ssrt::test::checkRefused;
using ssrt::test::loadError;

namespace {

const std::string kBox = SSRT_SOURCE_DIR "/tests/scenes/data/draco_box.gltf";

// The box file with `from` replaced by `to` (which must occur once), written to `dir`.
std::string editedBox(const TempDir& dir, const std::string& from, const std::string& to) {
    std::string text = ssrt::test::readFile(kBox);
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(text.find(from, at + 1) == std::string::npos);
    text.replace(at, from.size(), to);
    const std::string path = dir.file("edited.gltf");
    ssrt::test::writeFile(path, text);
    return path;
}

// Instanced triangles with three different vertex indices.
std::size_t drawnTriangles(const ssrt::Scene& s) {
    std::size_t n = 0;
    for (const ssrt::Instance& inst : s.instances) {
        const std::vector<uint32_t>& i = s.meshes[inst.mesh].indices;
        for (std::size_t t = 0; t + 2 < i.size(); t += 3)
            n += i[t] != i[t + 1] && i[t + 1] != i[t + 2] && i[t] != i[t + 2];
    }
    return n;
}

}  // namespace

TEST_CASE("gltf draco: the committed box decodes to 12 outward triangles with normals and UVs") {
    ssrt::GltfLoadReport report;
    const ssrt::Scene s = loadGltf(kBox, {.strict = true}, &report);
    CHECK(report.warnings.empty());
    REQUIRE(s.meshes.size() == 1);
    const ssrt::Mesh& m = s.meshes[0];
    REQUIRE(m.positions.size() == 24);
    REQUIRE(m.normals.size() == 24);
    REQUIRE(m.uvs.size() == 24);
    REQUIRE(m.indices.size() == 36);
    // 14-bit positions over a range of 1 are within 1e-4 of the corners; 10-bit normals
    // within 1e-2 of the axes; 12-bit UVs within 1e-3 of 0 and 1.
    for (std::size_t v = 0; v < 24; ++v) {
        const glm::vec3 p = m.positions[v], n = m.normals[v];
        for (int c = 0; c < 3; ++c) CHECK(std::abs(std::abs(p[c]) - 0.5f) < 1e-4f);
        int axis = 0;
        for (int c = 1; c < 3; ++c)
            if (std::abs(n[c]) > std::abs(n[axis])) axis = c;
        CHECK(std::abs(std::abs(n[axis]) - 1.0f) < 1e-2f);
        CHECK(n[axis] * p[axis] > 0.0f);  // the normal points out of its face
        for (int c = 0; c < 2; ++c)
            CHECK(std::min(std::abs(m.uvs[v][c]), std::abs(m.uvs[v][c] - 1.0f)) < 1e-3f);
    }
    // The faces keep their winding: each triangle's counter-clockwise normal is its vertices'.
    for (std::size_t t = 0; t < 12; ++t) {
        const uint32_t* i = &m.indices[3 * t];
        const glm::vec3 face = glm::normalize(glm::cross(m.positions[i[1]] - m.positions[i[0]],
                                                         m.positions[i[2]] - m.positions[i[0]]));
        for (int k = 0; k < 3; ++k) CHECK(glm::dot(face, m.normals[i[k]]) > 0.99f);
    }
}

TEST_CASE("gltf draco: accessors that disagree with the decoded mesh are refused") {
    TempDir dir("gltf-draco");
    const std::string primitive = "mesh 0 primitive 0: KHR_draco_mesh_compression";
    SUBCASE("POSITION count") {
        checkRefused(editedBox(dir, R"("count": 24, "type": "VEC3", "min")",
                               R"("count": 23, "type": "VEC3", "min")"),
                     primitive +
                         " POSITION: accessor 0 has count 23 but the Draco mesh has 24 "
                         "points");
    }
    SUBCASE("NORMAL type") {
        checkRefused(
            editedBox(dir, R"("count": 24, "type": "VEC3"})", R"("count": 24, "type": "VEC4"})"),
            primitive + " NORMAL: accessor 1 has 4 components but Draco attribute 1 has 3");
    }
    SUBCASE("indices count") {
        checkRefused(editedBox(dir, R"("count": 36)", R"("count": 30)"),
                     primitive +
                         ": accessor 3 (indices) has count 30 but the Draco mesh has 12 "
                         "triangles (36 indices)");
    }
    SUBCASE("a unique id the stream does not hold") {
        checkRefused(editedBox(dir, R"("TEXCOORD_0": 2}}})", R"("TEXCOORD_0": 7}}})"),
                     primitive + " TEXCOORD_0: the Draco mesh has no attribute with unique id 7");
    }
    SUBCASE("an attribute the primitive does not have") {
        checkRefused(editedBox(dir, R"("TEXCOORD_0": 2}}})", R"("TEXCOORD_0": 2, "COLOR_0": 1}}})"),
                     primitive + ": attribute COLOR_0 is not among the primitive's attributes");
    }
    SUBCASE("a truncated stream") {
        checkRefused(editedBox(dir, R"("bufferViews": [{"buffer": 0, "byteLength": 213})",
                               R"("bufferViews": [{"buffer": 0, "byteLength": 100})"),
                     primitive + ": Draco cannot decode bufferView 0: ");
    }
    SUBCASE("a missing bufferView") {
        checkRefused(editedBox(dir, R"({"bufferView": 0, )", "{"),
                     primitive + ": bufferView must be a non-negative integer");
    }
    SUBCASE("a strip") {
        checkRefused(editedBox(dir, R"("mode": 4)", R"("mode": 5)"),
                     primitive + ": TRIANGLE_STRIP is not supported");
    }
}

TEST_CASE("gltf draco: a Draco point primitive is skipped like any other") {
    TempDir dir("gltf-draco");
    checkRefused(editedBox(dir, R"("mode": 4)", R"("mode": 0)"),
                 "the scene has no triangles (1 point or line primitive skipped");
}

// Debian's assimp-testmodels ships the Khronos sample 2CylinderEngine twice: Draco-compressed
// (draco/, a .gltf with a .bin) and plain (a .glb).
TEST_CASE("gltf draco: 2CylinderEngine renders like its uncompressed copy (assimp-testmodels)") {
    const std::string dir = "/usr/share/assimp/models/glTF2/";
    const std::string draco = dir + "draco/2CylinderEngine.gltf";
    const std::string plain = dir + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    if (!std::filesystem::exists(draco) || !std::filesystem::exists(plain)) {
        MESSAGE("skipped: assimp-testmodels is not installed (" << draco << ")");
        return;
    }
    ssrt::GltfLoadReport report;
    const ssrt::Scene a = loadGltf(draco, {.strict = true}, &report);
    const ssrt::Scene b = loadGltf(plain);
    CHECK(report.warnings.empty());
    // Draco's encoder drops triangles that repeat a vertex index (they cover no pixel): the
    // plain copy has 11,160 of them among its 121,496 instanced triangles. It also merges
    // vertices of equal values, which leaves 6 more of the plain copy's triangles (in five
    // meshes) degenerate and dropped: 110,336 against 110,342.
    CHECK(drawnTriangles(a) == a.triangleCount());
    CHECK(a.triangleCount() <= drawnTriangles(b));
    CHECK(a.triangleCount() + 10 >= drawnTriangles(b));
    CHECK(a.instances.size() == b.instances.size());
    CHECK(a.meshes.size() == b.meshes.size());

    ssrt::RenderSettings rs;
    rs.width = 160;
    rs.height = 90;
    const ssrt::Renderer renderer(rs);
    const ssrt::Frame fa = renderer.renderWithoutHistory(a), fb = renderer.renderWithoutHistory(b);
    const auto iaRgb = fa.rgb(ssrt::Res::Color);
    const ssrt::PlaneF* ia[3] = {&iaRgb[0], &iaRgb[1], &iaRgb[2]};
    const auto ibRgb = fb.rgb(ssrt::Res::Color);
    const ssrt::PlaneF* ib[3] = {&ibRgb[0], &ibRgb[1], &ibRgb[2]};
    const ssrt::ImageError e = ssrt::imageError(ia, ib);
    MESSAGE("2CylinderEngine Draco against plain, 160x90: relMSE " << e.relMse);
    CHECK(e.nonFinite == 0);
    // Every layer finite: its creases once gave the SSGI upsample weights in the denormals and
    // NaN and infinite pixels (hidden in the colour by the denoiser then).
    for (const ssrt::PlaneRef& layer : fb.layers()) {
        CAPTURE(std::string(layer.name));
        int nonFinite = 0;
        for (int y = 0; y < layer.plane->height(); ++y)
            for (int x = 0; x < layer.plane->width(); ++x)
                nonFinite += std::isfinite(layer.plane->at(x, y)) ? 0 : 1;
        CHECK(nonFinite == 0);
    }
    CHECK(e.relMse < 0.03);  // 0.0122 measured
}
