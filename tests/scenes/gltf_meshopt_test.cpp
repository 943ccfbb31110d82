// EXT_meshopt_compression: a sphere's buffer views compressed here with Debian's
// libmeshoptimizer (every mode, the EXPONENTIAL filter on positions) load as the same mesh as
// the plain file; the fallback-buffer rule; malformed views refused naming the view; the
// OCTAHEDRAL and QUATERNION filters through the view decoder.
#include <doctest/doctest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scenes/gltf_compression.h"
#include "scenes/gltf_loader.h"
#include "scenes/gltf_test_files.h"
#include "scenes/mesh_builders.h"
#include "temp_dir.h"

using ssrt::loadGltf;
using ssrt::SceneLoadError;
using ssrt::test::TempDir;

using ssrt::test::checkRefused;
using ssrt::test::loadError;

namespace {

template <class T>
std::vector<unsigned char> bytesOf(const std::vector<T>& v) {
    std::vector<unsigned char> out(v.size() * sizeof(T));
    std::memcpy(out.data(), v.data(), out.size());
    return out;
}

// One buffer view: its plain bytes, and the same compressed.
struct Stream {
    std::vector<unsigned char> plain, packed;
    std::size_t stride = 0, count = 0;
    std::string mode, filter = "NONE";
};

Stream vertexStream(std::vector<unsigned char> plain, std::size_t stride,
                    std::vector<unsigned char> filtered = {}, std::string filter = "NONE") {
    Stream s;
    s.stride = stride;
    s.count = plain.size() / stride;
    s.mode = "ATTRIBUTES";
    s.filter = filter;
    const std::vector<unsigned char>& source = filter == "NONE" ? plain : filtered;
    s.packed.resize(meshopt_encodeVertexBufferBound(s.count, stride));
    s.packed.resize(meshopt_encodeVertexBuffer(s.packed.data(), s.packed.size(), source.data(),
                                               s.count, stride));
    s.plain = std::move(plain);
    return s;
}

Stream indexStream(const std::vector<uint32_t>& indices, std::size_t size, std::string mode) {
    Stream s;
    s.stride = size;
    s.count = indices.size();
    s.mode = mode;
    if (size == 2) s.plain = bytesOf(std::vector<uint16_t>(indices.begin(), indices.end()));
    else s.plain = bytesOf(indices);
    const std::size_t bound = mode == "TRIANGLES"
                                  ? meshopt_encodeIndexBufferBound(s.count, indices.size())
                                  : meshopt_encodeIndexSequenceBound(s.count, indices.size());
    s.packed.resize(bound);
    s.packed.resize(
        mode == "TRIANGLES"
            ? meshopt_encodeIndexBuffer(s.packed.data(), bound, indices.data(), s.count)
            : meshopt_encodeIndexSequence(s.packed.data(), bound, indices.data(), s.count));
    return s;
}

// The sphere with positions on a 1/1024 grid, so that the EXPONENTIAL filter with 16-bit
// mantissas holds them exactly.
ssrt::Mesh sphere() {
    ssrt::Mesh m = ssrt::makeUvSphere(1.0f, 12, 6);
    for (glm::vec3& p : m.positions) p = glm::round(p * 1024.0f) / 1024.0f;
    return m;
}

// Views 0-2: POSITION (EXPONENTIAL), NORMAL, TEXCOORD_0; 3: 16-bit TRIANGLES indices; 4: the
// same as 32-bit INDICES. Two primitives share the attributes, one per index view.
std::vector<Stream> sphereStreams() {
    const ssrt::Mesh m = sphere();
    const std::vector<float> flat(&m.positions[0].x, &m.positions[0].x + 3 * m.positions.size());
    std::vector<unsigned char> exp(flat.size() * 4);
    meshopt_encodeFilterExp(exp.data(), m.positions.size(), 12, 16, flat.data());
    return {vertexStream(bytesOf(m.positions), 12, exp, "EXPONENTIAL"),
            vertexStream(bytesOf(m.normals), 12), vertexStream(bytesOf(m.uvs), 8),
            indexStream(m.indices, 2, "TRIANGLES"), indexStream(m.indices, 4, "INDICES")};
}

std::size_t padded(std::size_t n) { return (n + 3) / 4 * 4; }

enum class Form { Plain, Compressed, Glb };

// `fallback`: buffer 1's members after its byteLength (compressed forms).
std::string sphereFile(const TempDir& dir, const std::string& name, Form form,
                       const std::string& fallback =
                           R"(, "extensions": {"EXT_meshopt_compression": {"fallback": true}})") {
    const std::vector<Stream> streams = sphereStreams();
    std::vector<unsigned char> plain, packed;
    std::string views;
    for (std::size_t i = 0; i < streams.size(); ++i) {
        const Stream& s = streams[i];
        const bool vertex = s.mode == "ATTRIBUTES";
        views += std::string(i ? ", " : "") + R"({"buffer": )" + (form == Form::Plain ? "0" : "1") +
                 R"(, "byteOffset": )" + std::to_string(plain.size()) + R"(, "byteLength": )" +
                 std::to_string(s.plain.size()) +
                 (vertex ? R"(, "byteStride": )" + std::to_string(s.stride) : "");
        if (form != Form::Plain)
            views += R"(, "extensions": {"EXT_meshopt_compression": {"buffer": 0, "byteOffset": )" +
                     std::to_string(packed.size()) + R"(, "byteLength": )" +
                     std::to_string(s.packed.size()) + R"(, "byteStride": )" +
                     std::to_string(s.stride) + R"(, "count": )" + std::to_string(s.count) +
                     R"(, "mode": ")" + s.mode + "\"" +
                     (s.filter != "NONE" ? R"(, "filter": ")" + s.filter + "\"" : "") + "}}";
        views += "}";
        plain.insert(plain.end(), s.plain.begin(), s.plain.end());
        packed.insert(packed.end(), s.packed.begin(), s.packed.end());
        plain.resize(padded(plain.size()));
        packed.resize(padded(packed.size()));
    }
    std::string buffers;
    if (form == Form::Plain)
        buffers = R"({"byteLength": )" + std::to_string(plain.size()) + R"(, "uri": ")" +
                  ssrt::test::dataUri(plain) + "\"}";
    else
        buffers = R"({"byteLength": )" + std::to_string(packed.size()) +
                  (form == Form::Glb ? "" : R"(, "uri": ")" + ssrt::test::dataUri(packed) + "\"") +
                  R"(}, {"byteLength": )" + std::to_string(plain.size()) + fallback + "}";
    const std::string vertices = std::to_string(streams[0].count);
    const std::string indices = std::to_string(streams[3].count);
    const std::string attributes = R"({"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2})";
    const std::string json =
        std::string(R"({"asset": {"version": "2.0"}, )") +
        (form == Form::Plain ? ""
                             : R"("extensionsUsed": ["EXT_meshopt_compression"], )"
                               R"("extensionsRequired": ["EXT_meshopt_compression"], )") +
        R"("scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], )"
        R"("meshes": [{"primitives": [{"attributes": )" +
        attributes + R"(, "indices": 3}, {"attributes": )" + attributes +
        R"(, "indices": 4}]}], "accessors": [)"
        R"({"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": )" +
        vertices + R"(}, {"bufferView": 1, "componentType": 5126, "type": "VEC3", "count": )" +
        vertices + R"(}, {"bufferView": 2, "componentType": 5126, "type": "VEC2", "count": )" +
        vertices + R"(}, {"bufferView": 3, "componentType": 5123, "type": "SCALAR", "count": )" +
        indices + R"(}, {"bufferView": 4, "componentType": 5125, "type": "SCALAR", "count": )" +
        indices + R"(}], "bufferViews": [)" + views + R"(], "buffers": [)" + buffers + "]}";
    const std::string path = dir.file(name);
    ssrt::test::writeFile(path, form == Form::Glb ? ssrt::test::glbOf(json, packed) : json);
    return path;
}

std::string edited(const std::string& path, const std::string& from, const std::string& to) {
    std::string text = ssrt::test::readFile(path);
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    ssrt::test::writeFile(path, text);
    return path;
}

// The same triangles in the same order, each maybe starting at another of its vertices.
bool sameTriangles(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t t = 0; t < a.size(); t += 3) {
        bool same = false;
        for (int r = 0; r < 3; ++r)
            same = same || (a[t] == b[t + r] && a[t + 1] == b[t + (r + 1) % 3] &&
                            a[t + 2] == b[t + (r + 2) % 3]);
        if (!same) return false;
    }
    return true;
}

// Both primitives of `s` hold the sphere as the plain file does: the same vertices bit for
// bit, and the same indices (the TRIANGLES codec may rotate a triangle's vertices, keeping
// its winding; the INDICES codec keeps the sequence).
void checkSameSphere(const ssrt::Scene& s, const ssrt::Scene& plain) {
    REQUIRE(s.meshes.size() == 2);
    REQUIRE(plain.meshes.size() == 2);
    for (std::size_t k = 0; k < 2; ++k) {
        CHECK(s.meshes[k].positions == plain.meshes[k].positions);
        CHECK(s.meshes[k].normals == plain.meshes[k].normals);
        CHECK(s.meshes[k].uvs == plain.meshes[k].uvs);
    }
    CHECK(sameTriangles(s.meshes[0].indices, plain.meshes[0].indices));
    CHECK(s.meshes[1].indices == plain.meshes[1].indices);
    CHECK(plain.meshes[0].positions == sphere().positions);
    CHECK(plain.meshes[0].indices == sphere().indices);
}

}  // namespace

TEST_CASE("gltf meshopt: compressed views load as the same mesh as the plain file") {
    TempDir dir("gltf-meshopt");
    const ssrt::Scene plain = loadGltf(sphereFile(dir, "plain.gltf", Form::Plain));
    for (const Form form : {Form::Compressed, Form::Glb}) {
        const std::string path =
            sphereFile(dir, form == Form::Glb ? "packed.glb" : "packed.gltf", form);
        CAPTURE(path);
        ssrt::GltfLoadReport report;
        checkSameSphere(loadGltf(path, {.strict = true}, &report), plain);
        CHECK(report.warnings.empty());
    }
}

TEST_CASE("gltf meshopt: fallback buffers are never loaded") {
    TempDir dir("gltf-meshopt");
    const ssrt::Scene plain = loadGltf(sphereFile(dir, "plain.gltf", Form::Plain));
    SUBCASE("a placeholder without a uri or a fallback tag") {
        checkSameSphere(loadGltf(sphereFile(dir, "a.gltf", Form::Compressed, "")), plain);
        checkSameSphere(loadGltf(sphereFile(dir, "a.glb", Form::Glb, "")), plain);
    }
    SUBCASE("a tagged fallback whose file is missing") {
        checkSameSphere(loadGltf(sphereFile(
                            dir, "b.gltf", Form::Compressed,
                            R"(, "uri": "missing.bin", "extensions": {"EXT_meshopt_compression": )"
                            R"({"fallback": true}})")),
                        plain);
    }
    SUBCASE("a tagged fallback of zeros: the compressed data is read, not the fallback") {
        std::size_t size = 0;
        for (const Stream& s : sphereStreams()) size += padded(s.plain.size());
        ssrt::test::writeFile(dir.file("zeros.bin"), std::string(size, '\0'));
        checkSameSphere(loadGltf(sphereFile(
                            dir, "c.gltf", Form::Compressed,
                            R"(, "uri": "zeros.bin", "extensions": {"EXT_meshopt_compression": )"
                            R"({"fallback": true}})")),
                        plain);
    }
    SUBCASE("a plain view of a fallback buffer is refused") {
        const std::string path = sphereFile(dir, "d.gltf", Form::Compressed);
        checkRefused(
            edited(path, R"(, "byteStride": 8, "extensions")", R"(, "byteStride": 8, "x")"),
            "bufferView 2 reads fallback buffer 1, which is never loaded, without "
            "EXT_meshopt_compression");
    }
    SUBCASE("compressed data in a fallback buffer is refused") {
        const std::string path = sphereFile(dir, "e.gltf", Form::Compressed);
        checkRefused(edited(path, R"({"EXT_meshopt_compression": {"buffer": 0)",
                            R"({"EXT_meshopt_compression": {"buffer": 1)"),
                     "bufferView 0: EXT_meshopt_compression: buffer 1 is a fallback buffer and "
                     "cannot hold compressed data");
    }
}

TEST_CASE("gltf meshopt: malformed views are refused naming the view") {
    TempDir dir("gltf-meshopt");
    const std::string path = sphereFile(dir, "bad.gltf", Form::Compressed);
    const std::string view3 = "bufferView 3: EXT_meshopt_compression: ";
    SUBCASE("mode") {
        checkRefused(edited(path, R"("mode": "TRIANGLES")", R"("mode": "STRIPS")"),
                     view3 + "mode \"STRIPS\" is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    SUBCASE("a filter on indices") {
        checkRefused(edited(path, R"("mode": "TRIANGLES")",
                            R"("mode": "TRIANGLES", "filter": "OCTAHEDRAL")"),
                     view3 + "filter OCTAHEDRAL is only for ATTRIBUTES");
    }
    SUBCASE("an unknown filter") {
        checkRefused(edited(path, R"("filter": "EXPONENTIAL")", R"("filter": "LOG")"),
                     "bufferView 0: EXT_meshopt_compression: filter \"LOG\" is not NONE, "
                     "OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    }
    SUBCASE("a stride that differs from the bufferView's") {
        checkRefused(edited(path, R"("byteStride": 8, "count")", R"("byteStride": 4, "count")"),
                     "bufferView 2: EXT_meshopt_compression: byteStride 4 differs from the "
                     "bufferView's 8");
    }
    SUBCASE("count times byteStride is not the bufferView's byteLength") {
        checkRefused(
            edited(path, R"("byteStride": 2, "count": 360)", R"("byteStride": 2, "count": 359)"),
            view3 + "the bufferView's byteLength 720 is not count 359 times byteStride 2");
    }
    SUBCASE("a missing member") {
        checkRefused(edited(path, R"(, "mode": "TRIANGLES")", ""), view3 + "mode is missing");
    }
    SUBCASE("corrupt data") {
        checkRefused(edited(path, R"({"buffer": 0, "byteOffset": 0, "byteLength": )",
                            R"({"buffer": 0, "byteOffset": 4, "byteLength": )"),
                     "bufferView 0: EXT_meshopt_compression: the ATTRIBUTES data cannot be "
                     "decoded (meshoptimizer 0.18 error");
    }
    SUBCASE("bytes outside the buffer") {
        checkRefused(edited(path, R"({"buffer": 0, "byteOffset": 0, "byteLength": )",
                            R"({"buffer": 0, "byteOffset": 99999, "byteLength": )"),
                     "bufferView 0: EXT_meshopt_compression: bytes 99999 to 99999 + ");
    }
}

TEST_CASE("gltf meshopt: the view decoder checks the layout and bounds the output") {
    const std::vector<unsigned char> data(40, 0xa0);
    const auto error = [&](ssrt::gltf::MeshoptView v) {
        try {
            ssrt::gltf::decodeMeshoptView(v, data.data(), data.size());
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(error({3, 6, "ATTRIBUTES", "NONE"}) ==
          "byteStride 6 must be a multiple of 4 from 4 to 256 for ATTRIBUTES");
    CHECK(error({4, 2, "TRIANGLES", "NONE"}) == "count 4 is not a multiple of 3 for TRIANGLES");
    CHECK(error({3, 8, "INDICES", "NONE"}) == "byteStride 8 must be 2 or 4 for INDICES");
    CHECK(error({3, 12, "ATTRIBUTES", "OCTAHEDRAL"}) ==
          "byteStride 12 must be 4 or 8 for the OCTAHEDRAL filter");
    CHECK(error({3, 4, "ATTRIBUTES", "QUATERNION"}) ==
          "byteStride 4 must be 8 for the QUATERNION filter");
    // 64 bytes out per byte in at most: 40 bytes cannot hold 641 elements of 4 bytes.
    CHECK(error({641, 4, "ATTRIBUTES", "NONE"}) ==
          "641 elements of 4 bytes cannot come from 40 compressed bytes");
}

TEST_CASE("gltf meshopt: OCTAHEDRAL and QUATERNION filters decode unit vectors and rotations") {
    const ssrt::Mesh m = sphere();
    const std::size_t n = m.normals.size();
    std::vector<float> normals, quats;
    for (std::size_t i = 0; i < n; ++i) {
        normals.insert(normals.end(), {m.normals[i].x, m.normals[i].y, m.normals[i].z, 0.0f});
        // A rotation by angle i about the normal.
        const float h = 0.5f * float(i) / float(n) * 6.0f;
        const glm::vec3 axis = m.normals[i] * std::sin(h);
        quats.insert(quats.end(), {axis.x, axis.y, axis.z, std::cos(h)});
    }
    std::vector<unsigned char> oct(n * 8), quat(n * 8);
    meshopt_encodeFilterOct(oct.data(), n, 8, 12, normals.data());
    meshopt_encodeFilterQuat(quat.data(), n, 8, 12, quats.data());
    const std::vector<unsigned char> dummy(n * 8, 0);
    const Stream a = vertexStream(dummy, 8, oct, "OCTAHEDRAL");
    const Stream b = vertexStream(dummy, 8, quat, "QUATERNION");
    const std::vector<unsigned char> octOut = ssrt::gltf::decodeMeshoptView(
        {n, 8, "ATTRIBUTES", "OCTAHEDRAL"}, a.packed.data(), a.packed.size());
    const std::vector<unsigned char> quatOut = ssrt::gltf::decodeMeshoptView(
        {n, 8, "ATTRIBUTES", "QUATERNION"}, b.packed.data(), b.packed.size());
    // Both filters write normalised 16-bit components; 12-bit encodings are within 2e-3.
    float normalError = 0.0f, rotationError = 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
        int16_t o[4], q[4];
        std::memcpy(o, octOut.data() + 8 * i, 8);
        std::memcpy(q, quatOut.data() + 8 * i, 8);
        float dot = 0.0f;
        for (int c = 0; c < 3; ++c)
            normalError = std::max(normalError, std::abs(o[c] / 32767.0f - normals[4 * i + c]));
        for (int c = 0; c < 4; ++c) dot += q[c] / 32767.0f * quats[4 * i + c];
        rotationError = std::max(rotationError, 1.0f - std::abs(dot));  // q, -q: one rotation
    }
    CHECK(normalError < 2e-3f);
    CHECK(rotationError < 2e-3f);
}
