// KHR_mesh_quantization: a sphere written here with quantized positions, normals and UVs (the
// dequantization in the node's transform, as gltfpack writes it) loads to the same triangles
// as the float file, each value within its quantization step; glTF's normalized-integer rules
// decoded exactly; quantized views compressed with EXT_meshopt_compression (normals through
// the OCTAHEDRAL filter) load to the bits of the same views plain; and component types that the
// attribute may not have are refused, saying which it may have. And a sphere that gltfpack
// itself packed (tests/scenes/data/gltfpack_sphere.glb, from gltfpack_sphere.gltf beside it:
// gen_gltfpack_sphere.py says how) loads to its source's triangles.
#include <doctest/doctest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scenes/gltf_loader.h"
#include "scenes/gltf_test_files.h"
#include "scenes/mesh_builders.h"
#include "temp_dir.h"

using ssrt::loadGltf;
using ssrt::test::checkRefused;
using ssrt::test::TempDir;

namespace {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123,
              kUnsignedInt = 5125, kFloat = 5126;

std::size_t componentSize(int type) {
    return type == kByte || type == kUnsignedByte     ? 1
           : type == kShort || type == kUnsignedShort ? 2
                                                      : 4;
}

// One vertex attribute's view: its elements padded to 4 bytes, as glTF requires.
struct View {
    std::vector<unsigned char> bytes;
    std::size_t stride = 0;
    int componentType = kFloat;
    bool normalized = false;
    std::string type;  // "VEC2", "VEC3"
    std::string filter = "NONE";
    std::vector<unsigned char> filtered;  // the bytes the filter's encoder wrote (filter only)
};

// Stores `values` (n per element) as `componentType`, each already an integer in range (or
// any float for kFloat).
View viewOf(const std::vector<double>& values, int n, int componentType, bool normalized) {
    View v;
    v.componentType = componentType;
    v.normalized = normalized;
    v.type = n == 2 ? "VEC2" : "VEC3";
    const std::size_t size = componentSize(componentType);
    v.stride = (n * size + 3) / 4 * 4;
    const std::size_t count = values.size() / std::size_t(n);
    v.bytes.assign(count * v.stride, 0);
    for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < n; ++c) {
            unsigned char* p = v.bytes.data() + i * v.stride + std::size_t(c) * size;
            const double x = values[i * std::size_t(n) + std::size_t(c)];
            switch (componentType) {
                case kByte: *reinterpret_cast<int8_t*>(p) = int8_t(x); break;
                // (Through int: a refused file writes negative normals as unsigned bytes, and a
                // double out of uint8_t's range would be undefined; int to unsigned wraps.)
                case kUnsignedByte: *p = uint8_t(int(x)); break;
                case kShort: {
                    const int16_t s = int16_t(x);
                    std::memcpy(p, &s, 2);
                    break;
                }
                case kUnsignedShort: {
                    const uint16_t s = uint16_t(int(x));
                    std::memcpy(p, &s, 2);
                    break;
                }
                default: {
                    const float f = float(x);
                    std::memcpy(p, &f, 4);
                }
            }
        }
    return v;
}

// The largest value of an integer type, the scale of its normalized form.
double maxOf(int type) {
    switch (type) {
        case kByte: return 127;
        case kUnsignedByte: return 255;
        case kShort: return 32767;
        case kUnsignedShort: return 65535;
        default: return 1;
    }
}

// Values in [lo, lo + extent] quantized to `type`: round((x - lo) / extent * max), so one
// integer step is extent / max once dequantized (for normalized types the decoder's division
// by max is the first part of that).
std::vector<double> quantize(const std::vector<double>& values, double lo, double extent,
                             int type) {
    std::vector<double> out;
    for (double x : values) out.push_back(std::round((x - lo) / extent * maxOf(type)));
    return out;
}

ssrt::Mesh sphere() { return ssrt::makeUvSphere(1.0f, 12, 6); }

template <int N>
std::vector<double> flat(const std::vector<glm::vec<N, float>>& v) {
    std::vector<double> out;
    for (const auto& e : v)
        for (int c = 0; c < N; ++c) out.push_back(e[c]);
    return out;
}

// How a file stores the sphere.
struct Layout {
    int position = kFloat, normal = kFloat, uv = kFloat;
    bool positionNormalized = false, uvNormalized = false;
    bool octahedral = false;  // normals as the OCTAHEDRAL filter decodes them (8 bits)
    bool meshopt = false;     // the three attribute views compressed, normals through the filter
    std::string extensions = R"("extensionsUsed": ["KHR_mesh_quantization"], )"
                             R"("extensionsRequired": ["KHR_mesh_quantization"], )";
};

// POSITION spans [-1, 1]: unsigned types store (p + 1) / 2 * max with the node's translation
// -1 and scale 2 / max (2 for normalized ones); signed types p * max with scale 1 / max (1
// normalized). UVs in [0, 1] store u * max, normalized or not (the caller scales back).
// NORMALs: normalized signed, n * max.
std::string sphereFile(const TempDir& dir, const std::string& name, const Layout& l) {
    const ssrt::Mesh m = sphere();
    const bool unsignedPos = l.position == kUnsignedByte || l.position == kUnsignedShort;
    std::vector<View> views;
    double posScale = 1, posOffset = 0;
    if (l.position == kFloat) {
        views.push_back(viewOf(flat(m.positions), 3, kFloat, false));
    } else {
        const double lo = unsignedPos ? -1 : 0, extent = unsignedPos ? 2 : 1;
        views.push_back(viewOf(quantize(flat(m.positions), lo, extent, l.position), 3, l.position,
                               l.positionNormalized));
        posScale = extent / (l.positionNormalized ? 1 : maxOf(l.position));
        posOffset = lo;
    }
    if (l.normal == kFloat) views.push_back(viewOf(flat(m.normals), 3, kFloat, false));
    else views.push_back(viewOf(quantize(flat(m.normals), 0, 1, l.normal), 3, l.normal, true));
    if (l.uv == kFloat) views.push_back(viewOf(flat(m.uvs), 2, kFloat, false));
    else views.push_back(viewOf(quantize(flat(m.uvs), 0, 1, l.uv), 2, l.uv, l.uvNormalized));
    if (l.octahedral) {  // the OCTAHEDRAL filter's encoding; its decoded bytes are the plain
        View& n = views[1];
        REQUIRE(n.stride == 4);
        std::vector<float> xyzw;
        for (const glm::vec3& v : m.normals) xyzw.insert(xyzw.end(), {v.x, v.y, v.z, 0.0f});
        n.filtered.resize(n.bytes.size());
        meshopt_encodeFilterOct(n.filtered.data(), m.normals.size(), 4, 8, xyzw.data());
        n.bytes = n.filtered;
        meshopt_decodeFilterOct(n.bytes.data(), m.normals.size(), 4);
        n.filter = "OCTAHEDRAL";
    }

    std::vector<uint16_t> indices(m.indices.begin(), m.indices.end());
    std::vector<unsigned char> plain, packed;
    std::string viewsJson, accessors;
    const std::string count = std::to_string(m.positions.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View& v = views[i];
        viewsJson += R"({"buffer": )" + std::string(l.meshopt ? "1" : "0") + R"(, "byteOffset": )" +
                     std::to_string(plain.size()) + R"(, "byteLength": )" +
                     std::to_string(v.bytes.size()) + R"(, "byteStride": )" +
                     std::to_string(v.stride);
        if (l.meshopt) {
            const std::vector<unsigned char>& source = v.filter == "NONE" ? v.bytes : v.filtered;
            std::vector<unsigned char> p(
                meshopt_encodeVertexBufferBound(m.positions.size(), v.stride));
            p.resize(meshopt_encodeVertexBuffer(p.data(), p.size(), source.data(),
                                                m.positions.size(), v.stride));
            viewsJson += R"(, "extensions": {"EXT_meshopt_compression": {"buffer": 0, )"
                         R"("byteOffset": )" +
                         std::to_string(packed.size()) + R"(, "byteLength": )" +
                         std::to_string(p.size()) + R"(, "byteStride": )" +
                         std::to_string(v.stride) + R"(, "count": )" + count +
                         R"(, "mode": "ATTRIBUTES")" +
                         (v.filter == "NONE" ? "" : R"(, "filter": ")" + v.filter + "\"") + "}}";
            packed.insert(packed.end(), p.begin(), p.end());
            packed.resize((packed.size() + 3) / 4 * 4);
        }
        viewsJson += "}, ";
        plain.insert(plain.end(), v.bytes.begin(), v.bytes.end());
        accessors += R"({"bufferView": )" + std::to_string(i) + R"(, "componentType": )" +
                     std::to_string(v.componentType) +
                     (v.normalized ? R"(, "normalized": true)" : "") + R"(, "type": ")" + v.type +
                     R"(", "count": )" + count + "}, ";
    }
    // The indices, plain (in buffer 0 of the meshopt form, after the packed views).
    std::vector<unsigned char>& indexBuffer = l.meshopt ? packed : plain;
    const std::size_t indexOffset = indexBuffer.size();
    indexBuffer.resize(indexOffset + indices.size() * 2);
    std::memcpy(indexBuffer.data() + indexOffset, indices.data(), indices.size() * 2);
    indexBuffer.resize((indexBuffer.size() + 3) / 4 * 4);
    viewsJson += R"({"buffer": 0, "byteOffset": )" + std::to_string(indexOffset) +
                 R"(, "byteLength": )" + std::to_string(indices.size() * 2) + "}";
    accessors += R"({"bufferView": 3, "componentType": 5123, "type": "SCALAR", "count": )" +
                 std::to_string(indices.size()) + "}";
    std::string buffers = R"({"byteLength": )" + std::to_string(indexBuffer.size()) +
                          R"(, "uri": ")" + ssrt::test::dataUri(indexBuffer) + "\"}";
    if (l.meshopt)
        buffers += R"(, {"byteLength": )" + std::to_string(plain.size()) +
                   R"(, "extensions": {"EXT_meshopt_compression": {"fallback": true}}})";
    std::string extensions = l.extensions;
    if (l.meshopt)
        extensions = R"("extensionsUsed": ["KHR_mesh_quantization", "EXT_meshopt_compression"], )"
                     R"("extensionsRequired": ["KHR_mesh_quantization", )"
                     R"("EXT_meshopt_compression"], )";
    const auto number = [](double x) {
        char text[64];
        std::snprintf(text, sizeof text, "%.17g", x);
        return std::string(text);
    };
    const std::string node = R"({"mesh": 0, "translation": [)" + number(posOffset) + ", " +
                             number(posOffset) + ", " + number(posOffset) + R"(], "scale": [)" +
                             number(posScale) + ", " + number(posScale) + ", " + number(posScale) +
                             "]}";
    const std::string json =
        R"({"asset": {"version": "2.0"}, )" + extensions +
        R"("scene": 0, "scenes": [{"nodes": [0]}], "nodes": [)" + node +
        R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1,)"
        R"( "TEXCOORD_0": 2}, "indices": 3}]}], "accessors": [)" +
        accessors + R"(], "bufferViews": [)" + viewsJson + R"(], "buffers": [)" + buffers + "]}";
    const std::string path = dir.file(name);
    ssrt::test::writeFile(path, json);
    return path;
}

glm::vec3 world(const ssrt::Scene& s, std::size_t v) {
    return glm::vec3(s.instances[0].transform * glm::vec4(s.meshes[0].positions[v], 1.0f));
}

// `q` holds the float file's triangles: the same indices, each world position within half a
// step (and float rounding) of the float one, each normal within one step, each UV (times
// `uvScale`) within half a step.
void checkSameTriangles(const ssrt::Scene& q, const ssrt::Scene& f, double posStep,
                        double normalStep, double uvStep, float uvScale) {
    REQUIRE(q.meshes.size() == 1);
    REQUIRE(q.instances.size() == 1);
    CHECK(q.meshes[0].indices == f.meshes[0].indices);
    REQUIRE(q.meshes[0].positions.size() == f.meshes[0].positions.size());
    REQUIRE(q.meshes[0].uvs.size() == f.meshes[0].uvs.size());
    double pos = 0, nrm = 0, uv = 0;
    for (std::size_t v = 0; v < q.meshes[0].positions.size(); ++v) {
        for (int c = 0; c < 3; ++c) {
            pos = std::max(pos, double(std::abs(world(q, v)[c] - world(f, v)[c])));
            nrm = std::max(nrm,
                           double(std::abs(q.meshes[0].normals[v][c] - f.meshes[0].normals[v][c])));
        }
        for (int c = 0; c < 2; ++c)
            uv = std::max(
                uv, double(std::abs(q.meshes[0].uvs[v][c] * uvScale - f.meshes[0].uvs[v][c])));
    }
    INFO("largest differences: position " << pos << ", normal " << nrm << ", uv " << uv);
    CHECK(pos <= 0.5 * posStep + 1e-6);
    CHECK(nrm <= normalStep);
    CHECK(uv <= 0.5 * uvStep + 1e-6);
    CHECK(pos > 0.0);  // quantized: not the float file again
}

}  // namespace

TEST_CASE("gltf quantization: quantized attributes load to the float file's triangles") {
    TempDir dir("gltf-quant");
    const ssrt::Scene f = loadGltf(sphereFile(dir, "float.gltf", Layout{.extensions = ""}));
    ssrt::GltfLoadReport report;

    // As gltfpack writes it: 16-bit positions with the node's scale and translation, 8-bit
    // normals, 16-bit UVs as integers (the material's KHR_texture_transform scales them back).
    Layout pack;
    pack.position = kUnsignedShort;
    pack.normal = kByte;
    pack.uv = kUnsignedShort;
    const ssrt::Scene a = loadGltf(sphereFile(dir, "pack.gltf", pack), {.strict = true}, &report);
    CHECK(report.warnings.empty());
    checkSameTriangles(a, f, 2.0 / 65535, 1.0 / 127, 1.0 / 65535, 1.0f / 65535);

    // Normalized signed: positions and normals as SHORT, UVs as BYTE.
    Layout snorm;
    snorm.position = kShort;
    snorm.positionNormalized = true;
    snorm.normal = kShort;
    snorm.uv = kByte;
    snorm.uvNormalized = true;
    const ssrt::Scene b = loadGltf(sphereFile(dir, "snorm.gltf", snorm));
    checkSameTriangles(b, f, 1.0 / 32767, 1.0 / 32767, 1.0 / 127, 1.0f);

    // 8 bits everywhere: BYTE positions as integers, UNSIGNED_BYTE UVs normalized.
    Layout bytes;
    bytes.position = kUnsignedByte;
    bytes.normal = kByte;
    bytes.uv = kUnsignedByte;
    bytes.uvNormalized = true;
    const ssrt::Scene c = loadGltf(sphereFile(dir, "bytes.gltf", bytes));
    checkSameTriangles(c, f, 2.0 / 255, 1.0 / 127, 1.0 / 255, 1.0f);
}

// One triangle whose POSITION is `values` stored as `type` (9 components, plainly packed).
std::vector<glm::vec3> positionsOf(const TempDir& dir, const std::vector<double>& values, int type,
                                   bool normalized) {
    const View v = viewOf(values, 3, type, normalized);
    const std::string json =
        R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_mesh_quantization"],)"
        R"( "extensionsRequired": ["KHR_mesh_quantization"], "scenes": [{"nodes": [0]}],)"
        R"( "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],)"
        R"( "accessors": [{"bufferView": 0, "componentType": )" +
        std::to_string(type) + R"(, "normalized": )" + (normalized ? "true" : "false") +
        R"(, "type": "VEC3", "count": 3}], "bufferViews": [{"buffer": 0, "byteLength": )" +
        std::to_string(v.bytes.size()) + R"(, "byteStride": )" + std::to_string(v.stride) +
        R"(}], "buffers": [{"byteLength": )" + std::to_string(v.bytes.size()) + R"(, "uri": ")" +
        ssrt::test::dataUri(v.bytes) + R"("}]})";
    const std::string path = dir.file("triangle.gltf");
    ssrt::test::writeFile(path, json);
    const ssrt::Scene s = loadGltf(path);
    REQUIRE(s.meshes.size() == 1);
    return s.meshes[0].positions;
}

TEST_CASE("gltf quantization: normalized integers decode by glTF's rules, to the bit") {
    TempDir dir("gltf-quant");
    using V = std::vector<glm::vec3>;
    // Signed: max(c / max, -1), so the most negative value and the one above it are both -1.
    CHECK(positionsOf(dir, {-128, 0, 0, 127, 0, 0, 0, 64, -127}, kByte, true) ==
          V{{-1, 0, 0}, {1, 0, 0}, {0, 64.0f / 127.0f, -1}});
    CHECK(positionsOf(dir, {-32768, 0, 0, 32767, 0, 0, 0, 1000, -32767}, kShort, true) ==
          V{{-1, 0, 0}, {1, 0, 0}, {0, 1000.0f / 32767.0f, -1}});
    // Unsigned: c / max.
    CHECK(positionsOf(dir, {255, 0, 0, 0, 255, 0, 0, 0, 128}, kUnsignedByte, true) ==
          V{{1, 0, 0}, {0, 1, 0}, {0, 0, 128.0f / 255.0f}});
    CHECK(positionsOf(dir, {65535, 0, 0, 0, 65535, 0, 0, 0, 300}, kUnsignedShort, true) ==
          V{{1, 0, 0}, {0, 1, 0}, {0, 0, 300.0f / 65535.0f}});
    // Not normalized: the integer itself, the node's transform scales it.
    CHECK(positionsOf(dir, {-128, 0, 0, 127, 0, 0, 0, 1, 0}, kByte, false) ==
          V{{-128, 0, 0}, {127, 0, 0}, {0, 1, 0}});
    CHECK(positionsOf(dir, {-32768, 0, 0, 65535 - 32768, 0, 0, 0, 7, 0}, kShort, false) ==
          V{{-32768, 0, 0}, {32767, 0, 0}, {0, 7, 0}});
    CHECK(positionsOf(dir, {65535, 0, 0, 0, 255, 0, 0, 0, 1}, kUnsignedShort, false) ==
          V{{65535, 0, 0}, {0, 255, 0}, {0, 0, 1}});
    CHECK(positionsOf(dir, {255, 0, 0, 0, 128, 0, 0, 0, 1}, kUnsignedByte, false) ==
          V{{255, 0, 0}, {0, 128, 0}, {0, 0, 1}});
}

TEST_CASE("gltf quantization: quantized views compressed with EXT_meshopt_compression") {
    TempDir dir("gltf-quant");
    // Octahedral normals (8 bits) and 16-bit positions and UVs, compressed; the plain file
    // holds the bytes the decoder gives, so the two load to the same bits.
    Layout l;
    l.position = kUnsignedShort;
    l.normal = kByte;
    l.uv = kUnsignedShort;
    l.uvNormalized = true;
    l.octahedral = true;
    const ssrt::Scene plain = loadGltf(sphereFile(dir, "plain.gltf", l));
    l.meshopt = true;
    ssrt::GltfLoadReport report;
    const ssrt::Scene packed =
        loadGltf(sphereFile(dir, "meshopt.gltf", l), {.strict = true}, &report);
    CHECK(report.warnings.empty());
    REQUIRE(packed.meshes.size() == 1);
    REQUIRE(plain.meshes.size() == 1);
    CHECK(packed.meshes[0].positions == plain.meshes[0].positions);
    CHECK(packed.meshes[0].normals == plain.meshes[0].normals);
    CHECK(packed.meshes[0].uvs == plain.meshes[0].uvs);
    CHECK(packed.meshes[0].indices == plain.meshes[0].indices);
    CHECK(packed.instances[0].transform == plain.instances[0].transform);
    // And both hold the float file's triangles; octahedral 8-bit normals are coarser than
    // rounding each component: within 4 steps.
    const ssrt::Scene f = loadGltf(sphereFile(dir, "float.gltf", Layout{.extensions = ""}));
    checkSameTriangles(packed, f, 2.0 / 65535, 4.0 / 127, 1.0 / 65535, 1.0f);
}

TEST_CASE("gltf quantization: component types the attribute may not have are refused") {
    TempDir dir("gltf-quant");
    Layout l;
    l.normal = kUnsignedByte;  // normals must be signed
    checkRefused(sphereFile(dir, "unsigned-normal.gltf", l),
                 "accessor 1 (NORMAL): component type normalized UNSIGNED_BYTE (5121) is not "
                 "allowed for NORMAL (KHR_mesh_quantization allows FLOAT, normalized BYTE or "
                 "normalized SHORT)");
    l = Layout{};
    l.position = kShort;  // quantized, but the file does not say so
    l.extensions = "";
    checkRefused(sphereFile(dir, "undeclared.gltf", l),
                 "accessor 0 (POSITION): component type SHORT (5122) needs KHR_mesh_quantization, "
                 "which the file does not declare (glTF 2.0 alone allows only FLOAT for POSITION)");
    l = Layout{};
    l.uv = kUnsignedByte;  // integer UVs without the extension: core glTF wants them normalized
    l.extensions = "";
    checkRefused(sphereFile(dir, "integer-uv.gltf", l),
                 "accessor 2 (TEXCOORD_0): component type UNSIGNED_BYTE (5121) needs "
                 "KHR_mesh_quantization");
    l = Layout{};
    l.position = kUnsignedInt;  // no 32-bit integers for attributes, quantized or not
    checkRefused(sphereFile(dir, "uint.gltf", l),
                 "component type UNSIGNED_INT (5125) is not allowed for POSITION");
}

namespace {

const std::string kPackedSphere = SSRT_SOURCE_DIR "/tests/scenes/data/gltfpack_sphere.glb";
const std::string kFloatSphere = SSRT_SOURCE_DIR "/tests/scenes/data/gltfpack_sphere.gltf";

struct Corner {
    glm::vec3 position, normal;
    glm::vec2 uv;  // through the base colour's UV transform
};

std::vector<Corner> corners(const ssrt::Scene& s) {
    REQUIRE(s.meshes.size() == 1);
    REQUIRE(s.instances.size() == 1);
    const ssrt::Mesh& m = s.meshes[0];
    const ssrt::Material& mat = s.materials[s.instances[0].material];
    std::vector<Corner> out;
    for (uint32_t i : m.indices)
        out.push_back({glm::vec3(s.instances[0].transform * glm::vec4(m.positions[i], 1.0f)),
                       m.normals[i], mat.baseColorUv.apply(m.uvs[i])});
    return out;
}

}  // namespace

// gltfpack's defaults: 14-bit positions (UNSIGNED_SHORT, the node's scale and translation),
// 8-bit normals (normalized BYTE), 12-bit UVs (normalized UNSIGNED_SHORT, KHR_texture_transform
// scaling them back), every view meshopt-compressed; its triangles reordered and rotated.
TEST_CASE("gltf quantization: gltfpack's output loads to its source's triangles") {
    ssrt::GltfLoadReport report;
    const ssrt::Scene packed = loadGltf(kPackedSphere, {.strict = true}, &report);
    CHECK(report.warnings.empty());
    const ssrt::Scene source = loadGltf(kFloatSphere);
    const std::vector<Corner> p = corners(packed), f = corners(source);
    REQUIRE(p.size() == f.size());
    // The dequantization steps, from what the file says: the node's scale for positions, the
    // UV transform's scale over 65535 for UVs; normals one 8-bit step.
    const float posStep = packed.instances[0].transform[0][0];
    const glm::vec2 uvStep =
        glm::vec2(packed.materials[0].baseColorUv.row0.x, packed.materials[0].baseColorUv.row1.y) /
        65535.0f;
    INFO("position step " << posStep << ", uv steps " << uvStep.x << " " << uvStep.y);
    CHECK(posStep > 0.0f);
    CHECK(posStep < 1e-3f);
    // Each packed triangle is a source triangle, its corners maybe rotated: matched by
    // position (the sphere's vertices lie far more than a step apart, but for its poles,
    // whose triangles the other two corners tell apart).
    std::vector<bool> used(f.size() / 3, false);
    float pos = 0, nrm = 0, uv = 0;
    std::size_t matched = 0;
    for (std::size_t t = 0; t < p.size(); t += 3) {
        for (std::size_t g = 0; g < f.size(); g += 3) {
            for (std::size_t r = 0; r < 3 && !used[g / 3]; ++r) {
                float d = 0;
                for (std::size_t k = 0; k < 3; ++k)
                    d = std::max(d, glm::length(p[t + k].position - f[g + (k + r) % 3].position));
                if (d > 0.01f) continue;
                used[g / 3] = true;
                ++matched;
                for (std::size_t k = 0; k < 3; ++k) {
                    const Corner &a = p[t + k], &b = f[g + (k + r) % 3];
                    for (int c = 0; c < 3; ++c) {
                        pos = std::max(pos, std::abs(a.position[c] - b.position[c]));
                        nrm = std::max(nrm, std::abs(a.normal[c] - b.normal[c]));
                    }
                    uv = std::max({uv, std::abs(a.uv.x - b.uv.x) / uvStep.x,
                                   std::abs(a.uv.y - b.uv.y) / uvStep.y});
                }
            }
        }
    }
    INFO("largest differences: position " << pos << ", normal " << nrm << ", uv " << uv
                                          << " steps");
    CHECK(matched == p.size() / 3);
    CHECK(pos <= 0.5f * posStep + 1e-5f);
    CHECK(nrm <= 1.0f / 127.0f);
    CHECK(uv <= 0.5f + 1e-2f);
}
