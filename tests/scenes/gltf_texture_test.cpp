// glTF textures: a textured quad written here with its image as an external PNG, a data URI
// and a .glb buffer view; each gives the same texels, the sampler's wrap modes, sRGB decoding
// for base colour only, and one clear error for what cannot be loaded.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/color.h"
#include "gltf_test_files.h"
#include "image_files.h"
#include "io/texture_io.h"
#include "renderer/renderer.h"
#include "scenes/gltf_loader.h"
#include "temp_dir.h"

using namespace ssrt;
using test::TempDir;

using test::base64;
using test::checkRefused;
using test::loadError;

namespace {

constexpr int kTexW = 4, kTexH = 2;

// Texel bytes that differ in every channel of every texel.
std::vector<uint8_t> texelBytes() {
    std::vector<uint8_t> v;
    for (int i = 0; i < kTexW * kTexH * 4; ++i) v.push_back(uint8_t(17 + i * 7));
    return v;
}

const float kUvs[] = {0, 1, 1, 1, 1, 0, 0, 0};

// Positions, TEXCOORD_0 and indices of a unit quad, then `image` (4-byte aligned), then
// `tangents` (four VEC4, for buffer view 3 without an image).
std::vector<unsigned char> quadBin(const std::vector<unsigned char>& image = {},
                                   const std::vector<float>& tangents = {}) {
    const float pos[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint16_t idx[] = {0, 1, 2, 0, 2, 3};
    // One allocation of the whole size (growing the vector by insert() trips GCC 12's
    // -Warray-bounds false positive in its inlined memmove).
    const size_t head = sizeof pos + sizeof kUvs + sizeof idx;
    const size_t tangentsAt = (head + image.size() + 3) / 4 * 4;
    std::vector<unsigned char> bin(tangentsAt + tangents.size() * sizeof(float), 0);
    std::memcpy(bin.data(), pos, sizeof pos);
    std::memcpy(bin.data() + sizeof pos, kUvs, sizeof kUvs);
    std::memcpy(bin.data() + sizeof pos + sizeof kUvs, idx, sizeof idx);
    if (!image.empty()) std::memcpy(bin.data() + head, image.data(), image.size());
    if (!tangents.empty())
        std::memcpy(bin.data() + tangentsAt, tangents.data(), tangents.size() * sizeof(float));
    return bin;
}

struct Quad {
    std::string images = R"([{"uri": "tex.png"}])";
    // Texture 0: image 0 with default sampling; texture 1: image 0 with sampler 0.
    std::string textures = R"([{"source": 0}, {"source": 0, "sampler": 0}])";
    std::string samplers = R"([{"wrapS": 33071, "wrapT": 33648}])";
    std::string pbr =
        R"("baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1})";
    std::string attributes = R"({"POSITION": 0, "TEXCOORD_0": 1})";
    std::string maps;             // more members of the material, each starting with a comma
    std::size_t imageBytes = 0;   // > 0: the image is buffer view 3, after the quad (GLB)
    std::vector<float> tangents;  // non-empty: accessor 3 (VEC4) in buffer view 3 (.gltf)
};

// buffer: "" for GLB (the BIN chunk), else the buffer's URI.
std::string quadJson(const Quad& q, const std::string& bufferUri, std::size_t binSize) {
    std::string buffer = R"({"byteLength": )" + std::to_string(binSize);
    if (!bufferUri.empty()) buffer += R"(, "uri": ")" + bufferUri + "\"";
    buffer += "}";
    std::string views = R"([{"buffer": 0, "byteOffset": 0, "byteLength": 48},)"
                        R"( {"buffer": 0, "byteOffset": 48, "byteLength": 32},)"
                        R"( {"buffer": 0, "byteOffset": 80, "byteLength": 12})";
    if (q.imageBytes > 0)
        views += R"(, {"buffer": 0, "byteOffset": 92, "byteLength": )" +
                 std::to_string(q.imageBytes) + "}";
    std::string tangents;
    if (!q.tangents.empty()) {
        views += R"(, {"buffer": 0, "byteOffset": 92, "byteLength": 64})";
        tangents = R"(, {"bufferView": 3, "componentType": 5126, "type": "VEC4", "count": 4})";
    }
    views += "]";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],)"
           R"( "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": )" +
           q.attributes +
           R"(, "indices": 2, "material": 0}]}],)"
           R"( "materials": [{"pbrMetallicRoughness": {)" +
           q.pbr + "}" + q.maps +
           R"(}],)"
           R"( "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 4},)"
           R"( {"bufferView": 1, "componentType": 5126, "type": "VEC2", "count": 4},)"
           R"( {"bufferView": 2, "componentType": 5123, "type": "SCALAR", "count": 6})" +
           tangents + R"(], "bufferViews": )" + views + R"(, "buffers": [)" + buffer + "]" +
           R"(, "images": )" + q.images + R"(, "textures": )" + q.textures + R"(, "samplers": )" +
           q.samplers + "}";
}

void writeFile(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A .gltf with the quad's buffer as quad.bin beside it.
std::string writeGltf(const TempDir& dir, const std::string& name, const Quad& q) {
    const std::vector<unsigned char> bin = quadBin({}, q.tangents);
    writeFile(dir.file("quad.bin"), bin);
    writeFile(dir.file(name), quadJson(q, "quad.bin", bin.size()));
    return dir.file(name);
}

void appendU32(std::vector<unsigned char>& s, uint32_t v) {
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    s.insert(s.end(), p, p + 4);
}

// A .glb whose BIN chunk holds the quad and `image` (buffer view 3).
std::string writeGlb(const TempDir& dir, const std::string& name, Quad q,
                     const std::vector<unsigned char>& image) {
    q.imageBytes = image.size();
    const std::vector<unsigned char> bin = quadBin(image);
    std::string json = quadJson(q, "", bin.size());
    while (json.size() % 4) json += ' ';
    std::vector<unsigned char> out = {'g', 'l', 'T', 'F'};
    appendU32(out, 2);
    appendU32(out, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    appendU32(out, uint32_t(json.size()));
    appendU32(out, 0x4E4F534A);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    appendU32(out, uint32_t(bin.size()));
    appendU32(out, 0x004E4942);  // "BIN\0"
    out.insert(out.end(), bin.begin(), bin.end());
    writeFile(dir.file(name), out);
    return dir.file(name);
}

std::vector<unsigned char> pngBytes(const TempDir& dir) {
    test::writeImage(dir.file("encode.png"), kTexW, kTexH, 4, texelBytes());
    return test::fileBytes(dir.file("encode.png"));
}

// The quad's material: base colour decoded from sRGB, metallic-roughness linear with the
// sampler's wrap modes, both from the same image.
void checkTexturedQuad(const Scene& s) {
    REQUIRE(s.materials.size() == 1);
    const Material& m = s.materials[0];
    REQUIRE(m.baseColorTexture >= 0);
    REQUIRE(m.metallicRoughnessTexture >= 0);
    CHECK(m.baseColorTexture != m.metallicRoughnessTexture);
    REQUIRE(s.textures.size() == 2);
    const Texture& base = s.textures[m.baseColorTexture];
    const Texture& mr = s.textures[m.metallicRoughnessTexture];
    REQUIRE(base.width() == kTexW);
    REQUIRE(base.height() == kTexH);
    REQUIRE(mr.width() == kTexW);
    const std::vector<uint8_t> v = texelBytes();
    for (int i = 0; i < kTexW * kTexH; ++i) {
        CAPTURE(i);
        for (int c = 0; c < 3; ++c) {
            CHECK(base.levels[0].texels[i][c] == srgbToLinear(float(v[i * 4 + c]) / 255.0f));
            CHECK(mr.levels[0].texels[i][c] == float(v[i * 4 + c]) / 255.0f);
        }
        CHECK(base.levels[0].texels[i].a == float(v[i * 4 + 3]) / 255.0f);
    }
    CHECK(base.wrapU == TextureWrap::Repeat);
    CHECK(base.wrapV == TextureWrap::Repeat);
    CHECK(mr.wrapU == TextureWrap::ClampToEdge);
    CHECK(mr.wrapV == TextureWrap::MirroredRepeat);
    REQUIRE(s.meshes.size() == 1);
    REQUIRE(s.meshes[0].uvs.size() == 4);
    for (int i = 0; i < 4; ++i)
        CHECK(s.meshes[0].uvs[i] == glm::vec2(kUvs[2 * i], kUvs[2 * i + 1]));
}

}  // namespace

TEST_CASE("gltf textures: an external PNG round-trips texels, encodings and wrap modes") {
    TempDir dir("gltf-tex");
    writeFile(dir.file("tex.png"), pngBytes(dir));
    checkTexturedQuad(loadGltf(writeGltf(dir, "quad.gltf", Quad{})));

    SUBCASE("a percent-encoded URI names the file") {
        writeFile(dir.file("my tex.png"), pngBytes(dir));
        Quad q;
        q.images = R"([{"uri": "my%20tex.png"}])";
        checkTexturedQuad(loadGltf(writeGltf(dir, "spaced.gltf", q)));
    }
    SUBCASE("one texture used twice with one encoding is decoded once") {
        Quad q;
        q.pbr = R"("baseColorTexture": {"index": 0})";
        q.textures = R"([{"source": 0}])";
        const Scene s = loadGltf(writeGltf(dir, "once.gltf", q));
        CHECK(s.textures.size() == 1);
        CHECK(s.materials[0].metallicRoughnessTexture == -1);
    }
}

TEST_CASE("gltf textures: a data URI and a .glb buffer view give the same texels") {
    TempDir dir("gltf-tex");
    const std::vector<unsigned char> png = pngBytes(dir);
    SUBCASE("data URI") {
        Quad q;
        q.images = R"([{"uri": "data:image/png;base64,)" + base64(png) + "\"}]";
        checkTexturedQuad(loadGltf(writeGltf(dir, "datauri.gltf", q)));
    }
    SUBCASE("buffer view in a .glb") {
        Quad q;
        q.images = R"([{"bufferView": 3, "mimeType": "image/png"}])";
        checkTexturedQuad(loadGltf(writeGlb(dir, "quad.glb", q, png)));
    }
}

TEST_CASE("gltf textures: textures that cannot be used give one clear error") {
    TempDir dir("gltf-tex-bad");
    const std::vector<unsigned char> png = pngBytes(dir);
    writeFile(dir.file("tex.png"), png);
    Quad q;
    SUBCASE("a third texture coordinate set") {
        q.pbr = R"("baseColorTexture": {"index": 0, "texCoord": 2})";
        checkRefused(writeGltf(dir, "texcoord.gltf", q), "TEXCOORD_2");
    }
    SUBCASE("an image file that is not an image") {
        writeFile(dir.file("tex.png"), std::string("this is not a PNG"));
        checkRefused(writeGltf(dir, "garbage.gltf", q), "image 0");
    }
    SUBCASE("truncated image bytes in a buffer view") {
        q.images = R"([{"bufferView": 3, "mimeType": "image/png"}])";
        const std::vector<unsigned char> half(png.begin(), png.begin() + png.size() / 2);
        checkRefused(writeGlb(dir, "truncated.glb", q, half), "image 0");
    }
    SUBCASE("an image type glTF does not allow") {
        q.images = R"([{"bufferView": 3, "mimeType": "image/gif"}])";
        checkRefused(writeGlb(dir, "gif.glb", q, png), "image/gif");
    }
    SUBCASE("a sampler that does not exist") {
        q.textures = R"([{"source": 0}, {"source": 0, "sampler": 4}])";
        checkRefused(writeGltf(dir, "sampler.gltf", q), "sampler 4");
    }
    SUBCASE("a texture index out of range") {
        q.pbr = R"("metallicRoughnessTexture": {"index": 9})";
        checkRefused(writeGltf(dir, "index.gltf", q), "texture 9 does not exist");
    }
    SUBCASE("a filter or wrap mode that is not glTF's") {
        q.samplers = R"([{"magFilter": 9987}])";  // a mipmap filter, for minFilter only
        checkRefused(writeGltf(dir, "mag.gltf", q),
                     "sampler 0: magFilter 9987 is not a glTF filter");
        q.samplers = R"([{"minFilter": 9730}])";
        checkRefused(writeGltf(dir, "min.gltf", q),
                     "sampler 0: minFilter 9730 is not a glTF filter");
        q.samplers = R"([{"wrapS": 10497, "wrapT": 1234}])";
        checkRefused(writeGltf(dir, "wrap.gltf", q), "sampler wrap mode 1234");
    }
}

// Every Khronos sample sets its samplers' filters; every glTF filter loads without a word
// (the texture is sampled the one way scenes/texture.h describes), the wrap modes still read.
TEST_CASE("gltf textures: sampler filters of every kind load without a warning") {
    TempDir dir("gltf-tex-filter");
    writeFile(dir.file("tex.png"), pngBytes(dir));
    const std::vector<std::pair<int, int>> filters = {{9728, 9728}, {9729, 9729}, {9728, 9984},
                                                      {9729, 9985}, {9728, 9986}, {9729, 9987}};
    for (const std::pair<int, int>& filter : filters) {
        // (Not a structured binding: clang 14's lambdas, which CAPTURE makes, cannot name one.)
        const int mag = filter.first, min = filter.second;
        CAPTURE(mag);
        CAPTURE(min);
        Quad q;
        q.samplers = R"([{"magFilter": )" + std::to_string(mag) + R"(, "minFilter": )" +
                     std::to_string(min) + R"(, "wrapS": 33071, "wrapT": 33648}])";
        ssrt::GltfLoadReport report;
        const Scene s = loadGltf(writeGltf(dir, "filters.gltf", q), {.strict = true}, &report);
        CHECK(report.warnings.empty());
        checkTexturedQuad(s);
    }
}

TEST_CASE("gltf textures: KHR_texture_transform is read per texture reference") {
    TempDir dir("gltf-tex-uv");
    writeFile(dir.file("tex.png"), pngBytes(dir));
    Quad q;
    // The extension's own example: the lower-left quadrant, rotated 90 degrees.
    q.pbr = R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":)"
            R"( {"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}}},)"
            R"( "metallicRoughnessTexture": {"index": 1})";
    const Scene s = loadGltf(writeGltf(dir, "transform.gltf", q));
    const Material& m = s.materials[0];
    CHECK(m.baseColorUv.row0.x == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(m.baseColorUv.row0.y == doctest::Approx(0.5).epsilon(1e-6));
    CHECK(m.baseColorUv.row1.x == doctest::Approx(-0.5).epsilon(1e-6));
    CHECK(m.baseColorUv.row1.y == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(m.baseColorUv.offset == glm::vec2(0.0f, 1.0f));
    // UV (0, 0) lands on (0, 1) and (1, 1) on (0.5, 0.5): u in [0, 0.5], v in [0.5, 1].
    const glm::vec2 a = m.baseColorUv.apply({0.0f, 0.0f}), b = m.baseColorUv.apply({1.0f, 1.0f});
    CHECK(a.x == doctest::Approx(0.0));
    CHECK(a.y == doctest::Approx(1.0));
    CHECK(b.x == doctest::Approx(0.5));
    CHECK(b.y == doctest::Approx(0.5));
    CHECK(m.metallicRoughnessUv.identity());

    SUBCASE("the defaults are exactly the identity") {
        q.pbr = R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":)"
                R"( {}}})";
        CHECK(loadGltf(writeGltf(dir, "empty.gltf", q)).materials[0].baseColorUv.identity());
    }
    SUBCASE("its texCoord overrides the reference's") {
        q.pbr = R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":)"
                R"( {"texCoord": 2}}})";
        checkRefused(writeGltf(dir, "texcoord.gltf", q), "TEXCOORD_2");
        q.pbr = R"("baseColorTexture": {"index": 0, "texCoord": 2, "extensions":)"
                R"( {"KHR_texture_transform": {"texCoord": 1}}})";
        const Scene s1 = loadGltf(writeGltf(dir, "override.gltf", q));
        CHECK(s1.materials[0].baseColorTexture == 0);
        CHECK(s1.materials[0].baseColorUv.set == 1);
    }
    SUBCASE("a malformed transform is an error naming the member") {
        q.pbr = R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":)"
                R"( {"scale": [2]}}})";
        checkRefused(writeGltf(dir, "scale.gltf", q), "KHR_texture_transform scale");
        q.pbr = R"("baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":)"
                R"( {"rotation": "half"}}})";
        checkRefused(writeGltf(dir, "rotation.gltf", q), "KHR_texture_transform rotation");
    }
}

TEST_CASE("gltf textures: TEXCOORD_1 is read, and a texture may sample it") {
    TempDir dir("gltf-tex-uv1");
    writeFile(dir.file("tex.png"), pngBytes(dir));
    Quad q;
    q.attributes = R"({"POSITION": 0, "TEXCOORD_1": 1})";
    q.pbr = R"("baseColorTexture": {"index": 0, "texCoord": 1},)"
            R"( "metallicRoughnessTexture": {"index": 1})";
    const Scene s = loadGltf(writeGltf(dir, "uv1.gltf", q));
    REQUIRE(s.meshes.size() == 1);
    CHECK(s.meshes[0].uvs.empty());
    REQUIRE(s.meshes[0].uvs1.size() == 4);
    for (int i = 0; i < 4; ++i)
        CHECK(s.meshes[0].uvs1[i] == glm::vec2(kUvs[2 * i], kUvs[2 * i + 1]));
    CHECK(s.materials[0].baseColorUv.set == 1);
    CHECK(s.materials[0].metallicRoughnessUv.set == 0);
    CHECK(s.materials[0].usesUvSet1());
}

TEST_CASE("gltf textures: normal, occlusion and emissive textures are read with their fields") {
    TempDir dir("gltf-tex-maps");
    writeFile(dir.file("tex.png"), pngBytes(dir));
    Quad q;
    q.pbr = R"("baseColorTexture": {"index": 0})";
    q.maps = R"(, "normalTexture": {"index": 1, "scale": 0.5},)"
             R"( "occlusionTexture": {"index": 1, "texCoord": 1, "strength": 0.25},)"
             R"( "emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform":)"
             R"( {"offset": [0.5, 0]}}}, "emissiveFactor": [1, 1, 1])";
    q.attributes = R"({"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 1})";
    ssrt::GltfLoadReport report;
    const Scene s = loadGltf(writeGltf(dir, "maps.gltf", q), {}, &report);
    CHECK(report.warnings.empty());  // nothing about these textures any more
    const Material& m = s.materials[0];
    REQUIRE(m.normalTexture >= 0);
    REQUIRE(m.occlusionTexture >= 0);
    REQUIRE(m.emissiveTexture >= 0);
    CHECK(m.normalScale == 0.5f);
    CHECK(m.occlusionStrength == 0.25f);
    CHECK(m.occlusionUv.set == 1);
    CHECK(m.normalUv.identity());
    CHECK(m.emissiveUv.offset == glm::vec2(0.5f, 0.0f));
    // Normal and occlusion maps are linear, the emissive one sRGB like base colour (one
    // texture per encoding).
    CHECK(m.emissiveTexture == m.baseColorTexture);
    CHECK(m.normalTexture == m.occlusionTexture);
    const std::vector<uint8_t> v = texelBytes();
    CHECK(s.textures[m.normalTexture].levels[0].texels[0].r == float(v[0]) / 255.0f);
    CHECK(s.textures[m.emissiveTexture].levels[0].texels[0].r ==
          srgbToLinear(float(v[0]) / 255.0f));
    CHECK(s.meshes[0].tangents.empty());  // no TANGENT: generated where needed

    SUBCASE("the defaults: scale 1, strength 1") {
        q.maps = R"(, "normalTexture": {"index": 1}, "occlusionTexture": {"index": 1})";
        const Material d = loadGltf(writeGltf(dir, "defaults.gltf", q)).materials[0];
        CHECK(d.normalScale == 1.0f);
        CHECK(d.occlusionStrength == 1.0f);
        CHECK(d.emissiveTexture == -1);
    }
    SUBCASE("a missing texture is an error naming it") {
        q.maps = R"(, "normalTexture": {"index": 7})";
        checkRefused(writeGltf(dir, "missing.gltf", q), "texture 7 does not exist");
    }
}

TEST_CASE("gltf textures: TANGENT is read, xyz made unit and w a sign") {
    TempDir dir("gltf-tex-tangent");
    writeFile(dir.file("tex.png"), pngBytes(dir));
    Quad q;
    q.tangents = {2, 0, 0, 1, 0, 3, 0, -1, 1, 0, 0, 0.9f, 0, 0, 1, -0.5f};
    q.attributes = R"({"POSITION": 0, "TEXCOORD_0": 1, "TANGENT": 3})";
    const Scene s = loadGltf(writeGltf(dir, "tangent.gltf", q));
    REQUIRE(s.meshes[0].tangents.size() == 4);
    CHECK(s.meshes[0].tangents[0] == glm::vec4(1, 0, 0, 1));
    CHECK(s.meshes[0].tangents[1] == glm::vec4(0, 1, 0, -1));
    CHECK(s.meshes[0].tangents[2] == glm::vec4(1, 0, 0, 1));
    CHECK(s.meshes[0].tangents[3] == glm::vec4(0, 0, 1, -1));
}

// End to end (issue 16): a MASK material whose PNG is transparent in its left half (u < 0.5;
// the quad's u runs along +x) loads and renders with that half cut out, where the same file
// without alphaMode draws the whole quad.
TEST_CASE("gltf textures: a MASK material's transparent texels are cut out of the render") {
    const TempDir dir;
    std::vector<uint8_t> texels;
    for (int y = 0; y < kTexH; ++y)
        for (int x = 0; x < kTexW; ++x)
            texels.insert(texels.end(), {200, 120, 60, uint8_t(x < 2 ? 0 : 255)});
    test::writeImage(dir.file("tex.png"), kTexW, kTexH, 4, texels);
    Quad q;
    q.pbr = R"("baseColorTexture": {"index": 0})";
    const Scene opaque = loadGltf(writeGltf(dir, "opaque.gltf", q));
    q.maps = R"(, "alphaMode": "MASK")";
    const Scene masked = loadGltf(writeGltf(dir, "masked.gltf", q));
    REQUIRE(masked.materials[0].alphaMode == Material::AlphaMode::Mask);
    RenderSettings rs;
    rs.width = 96;
    rs.height = 64;
    rs.shadowMapSize = 256;
    rs.trace.ssr = rs.trace.ssgi = false;
    const Renderer r(rs);
    const Frame a = r.renderWithoutHistory(opaque), b = r.renderWithoutHistory(masked);
    int whole = 0, cut = 0, leftOfCentre = 0;
    for (int y = 0; y < rs.height; ++y)
        for (int x = 0; x < rs.width; ++x) {
            whole += a.gbuffer.materialId.at(x, y) == 0.0f;
            const bool drawn = b.gbuffer.materialId.at(x, y) == 0.0f;
            cut += drawn;
            // The fitted camera looks at the quad's centre (x = 0.5) head on in x: the kept
            // half is right of the image's centre, but for the u = 0 edge (wrap: alpha 0.5).
            leftOfCentre += drawn && x < rs.width / 2 - 1;
        }
    MESSAGE("quad pixels: opaque " << whole << ", masked " << cut);
    REQUIRE(whole > 500);
    CHECK(cut >= 0.4 * whole);
    CHECK(cut <= 0.6 * whole);
    CHECK(leftOfCentre <= rs.height);  // at most the one-texel-wide u = 0 column
}
