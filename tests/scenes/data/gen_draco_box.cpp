// Writes tests/scenes/data/draco_box.gltf: a unit box (24 vertices with face normals and
// UVs, 12 triangles, counter-clockwise seen from outside) compressed with Debian's Draco
// encoder into a KHR_draco_mesh_compression primitive, its buffer embedded as a data URI.
// The accessors' counts come from decoding the encoded stream, as the extension's
// implementation note asks of generators (Draco may reorder and renumber vertices).
//
//   cmake --build build --target ssrt_gen_draco_box
//   build/tests/ssrt_gen_draco_box tests/scenes/data/draco_box.gltf
//
// The fixture is committed, so the loader's Draco path is tested without this program (and
// without assimp-testmodels); re-running it may give other bytes with another Draco version.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace {

using Vec3 = std::array<float, 3>;

struct Box {
    std::vector<Vec3> positions, normals;
    std::vector<std::array<float, 2>> uvs;
    std::vector<std::array<uint32_t, 3>> triangles;
};

// Face n with in-plane axes u, v such that u x v = n: corners (-,-), (+,-), (+,+), (-,+)
// run counter-clockwise seen from outside.
Box unitBox() {
    Box box;
    const Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    const auto neg = [](Vec3 a) { return Vec3{-a[0], -a[1], -a[2]}; };
    const std::array<std::array<Vec3, 3>, 6> faces = {
        {{x, y, z}, {neg(x), z, y}, {y, z, x}, {neg(y), x, z}, {z, x, y}, {neg(z), y, x}}};
    const float corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& [n, u, v] : faces) {
        const auto base = uint32_t(box.positions.size());
        for (const auto& c : corner) {
            Vec3 p;
            for (int i = 0; i < 3; ++i) p[i] = 0.5f * (n[i] + c[0] * u[i] + c[1] * v[i]);
            box.positions.push_back(p);
            box.normals.push_back(n);
            box.uvs.push_back({0.5f * (c[0] + 1), 0.5f * (c[1] + 1)});
        }
        box.triangles.push_back({base, base + 1, base + 2});
        box.triangles.push_back({base, base + 2, base + 3});
    }
    return box;
}

template <class Values>
int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, const Values& values) {
    constexpr int n = int(std::tuple_size_v<typename Values::value_type>);
    draco::GeometryAttribute att;
    att.Init(type, nullptr, n, draco::DT_FLOAT32, false, sizeof(float) * n, 0);
    const int id = mesh.AddAttribute(att, true, uint32_t(values.size()));
    for (std::size_t i = 0; i < values.size(); ++i)
        mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)),
                                              values[i].data());
    return id;
}

std::string base64(const char* data, std::size_t size) {
    static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    const auto* in = reinterpret_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; i += 3) {
        const uint32_t v =
            in[i] << 16 | (i + 1 < size ? in[i + 1] << 8 : 0) | (i + 2 < size ? in[i + 2] : 0);
        out += abc[v >> 18 & 63];
        out += abc[v >> 12 & 63];
        out += i + 1 < size ? abc[v >> 6 & 63] : '=';
        out += i + 2 < size ? abc[v & 63] : '=';
    }
    return out;
}

std::string num(double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%.9g", v);
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUT.gltf\n", argv[0]);
        return 2;
    }
    const Box box = unitBox();
    draco::Mesh mesh;
    mesh.set_num_points(uint32_t(box.positions.size()));
    const int pos = addAttribute(mesh, draco::GeometryAttribute::POSITION, box.positions);
    const int nrm = addAttribute(mesh, draco::GeometryAttribute::NORMAL, box.normals);
    const int uv = addAttribute(mesh, draco::GeometryAttribute::TEX_COORD, box.uvs);
    for (const auto& t : box.triangles)
        mesh.AddFace({draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});

    // Quantisation as glTF exporters commonly set it (positions 14 bits, normals 10, UVs 12).
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    draco::EncoderBuffer encoded;
    if (!encoder.EncodeMeshToBuffer(mesh, &encoded).ok()) {
        std::fprintf(stderr, "Draco cannot encode the box\n");
        return 1;
    }
    draco::DecoderBuffer in;
    in.Init(encoded.data(), encoded.size());
    auto decoded = draco::Decoder().DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) {
        std::fprintf(stderr, "Draco cannot decode the box: %s\n", decoded.status().error_msg());
        return 1;
    }
    const std::unique_ptr<draco::Mesh> back = std::move(decoded).value();
    const draco::PointAttribute* p = back->GetAttributeByUniqueId(mesh.attribute(pos)->unique_id());
    Vec3 lo{1e9f, 1e9f, 1e9f}, hi{-1e9f, -1e9f, -1e9f};
    for (uint32_t i = 0; i < back->num_points(); ++i) {
        Vec3 v;
        p->GetMappedValue(draco::PointIndex(i), v.data());
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], v[c]), hi[c] = std::max(hi[c], v[c]);
    }

    const std::string points = std::to_string(back->num_points());
    const std::string bytes = std::to_string(encoded.size());
    const auto id = [&](int att) { return std::to_string(mesh.attribute(att)->unique_id()); };
    std::ofstream out(argv[1], std::ios::binary);
    out << "{\n"
        << R"(  "asset": {"version": "2.0", "generator": "ssrt tests/scenes/data/gen_draco_box.cpp"},)"
        << "\n"
        << R"(  "extensionsUsed": ["KHR_draco_mesh_compression"],)"
        << "\n"
        << R"(  "extensionsRequired": ["KHR_draco_mesh_compression"],)"
        << "\n"
        << R"(  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],)"
        << "\n"
        << R"(  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1],)"
        << R"( "metallicFactor": 0, "roughnessFactor": 0.6}}],)"
        << "\n"
        << R"(  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, )"
        << R"("TEXCOORD_0": 2}, "indices": 3, "material": 0, "mode": 4,)"
        << "\n"
        << R"(    "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": )"
        << R"({"POSITION": )" << id(pos) << R"(, "NORMAL": )" << id(nrm) << R"(, "TEXCOORD_0": )"
        << id(uv) << "}}}}]}],\n"
        << R"(  "accessors": [)"
        << "\n"
        << R"(    {"componentType": 5126, "count": )" << points << R"(, "type": "VEC3", "min": [)"
        << num(lo[0]) << ", " << num(lo[1]) << ", " << num(lo[2]) << R"(], "max": [)" << num(hi[0])
        << ", " << num(hi[1]) << ", " << num(hi[2]) << "]},\n"
        << R"(    {"componentType": 5126, "count": )" << points << R"(, "type": "VEC3"},)"
        << "\n"
        << R"(    {"componentType": 5126, "count": )" << points << R"(, "type": "VEC2"},)"
        << "\n"
        << R"(    {"componentType": 5123, "count": )" << std::to_string(back->num_faces() * 3)
        << R"(, "type": "SCALAR"}],)"
        << "\n"
        << R"(  "bufferViews": [{"buffer": 0, "byteLength": )" << bytes << "}],\n"
        << R"(  "buffers": [{"byteLength": )" << bytes
        << R"(, "uri": "data:application/octet-stream;base64,)"
        << base64(encoded.data(), encoded.size()) << "\"}]\n"
        << "}\n";
    return out ? 0 : 1;
}
