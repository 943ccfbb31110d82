// KHR_draco_mesh_compression: compressed primitives decoded with Debian's libdraco.
// https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_draco_mesh_compression
#include <draco/attributes/attribute_octahedron_transform.h>
#include <draco/compression/attributes/normal_compression_utils.h>
#include <draco/compression/decode.h>
#include <tiny_gltf.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <stdexcept>

#include "scenes/gltf_compression.h"
#include "scenes/gltf_errors.h"

namespace ssrt::gltf {
namespace {

// A non-negative integer member of the extension object.
int indexMember(const tinygltf::Value& ext, const char* key, const std::string& name) {
    const tinygltf::Value* v = ext.Has(key) ? &ext.Get(key) : nullptr;
    if (!v || !v->IsInt() || v->GetNumberAsInt() < 0)
        fail(name + ": " + key + " must be a non-negative integer");
    return v->GetNumberAsInt();
}

// "The data must be passed to a mesh decoder and decompressed to a mesh."
std::unique_ptr<draco::Mesh> decodeMesh(const tinygltf::Model& model, const tinygltf::Value& ext,
                                        const std::string& name) {
    const int index = indexMember(ext, "bufferView", name);
    if (std::size_t(index) >= model.bufferViews.size())
        fail(name + ": bufferView " + str(index) + " out of range (" +
             str(model.bufferViews.size()) + " bufferViews)");
    const tinygltf::BufferView& view = model.bufferViews[index];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
        fail(name + ": bufferView " + str(index) + " has no buffer");
    const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        fail(name + ": bufferView " + str(index) + " overruns its buffer (" + str(data.size()) +
             " bytes)");
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    // Normals stay octahedral integers: octahedralNormals() turns them into vectors.
    decoder.SetSkipAttributeTransform(draco::GeometryAttribute::NORMAL);
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        fail(name + ": Draco cannot decode bufferView " + str(index) + ": " +
             decoded.status().error_msg_string());
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) fail(name + ": Draco decoded no mesh from bufferView " + str(index));
    return mesh;
}

// The accessor a primitive's decoded data goes to. Accessors are filled in place (errors
// then name the file's own accessor); one that an earlier Draco primitive already filled is
// copied, so that two primitives never overwrite each other's data.
int accessorToFill(tinygltf::Model& model, int index, std::set<int>& filled,
                   const std::string& name) {
    if (index < 0 || std::size_t(index) >= model.accessors.size())
        fail(name + ": accessor " + std::to_string(index) + " out of range (" +
             str(model.accessors.size()) + " accessors)");
    if (filled.insert(index).second) return index;
    model.accessors.push_back(model.accessors[index]);
    return int(model.accessors.size() - 1);
}

// One attribute's values for every point, converted by Draco to the accessor's component
// type T (normalised integers as the attribute declares them).
template <class T>
std::vector<unsigned char> pointValues(const draco::PointAttribute& att, std::size_t points,
                                       int components, const std::string& name) {
    std::vector<unsigned char> out(points * components * sizeof(T));
    std::vector<T> value(components);
    for (std::size_t p = 0; p < points; ++p) {
        const draco::PointIndex point(static_cast<uint32_t>(p));
        // Draco maps points to values; a map that leaves its range is a corrupt stream.
        const bool mapped = att.is_mapping_identity() || p < att.indices_map_size();
        if (!mapped || att.mapped_index(point).value() >= att.size() ||
            !att.ConvertValue<T>(att.mapped_index(point), int8_t(components), value.data()))
            fail(name + ": the value of point " + str(p) +
                 " does not fit the accessor's component type");
        std::memcpy(out.data() + p * components * sizeof(T), value.data(), components * sizeof(T));
    }
    return out;
}

// Octahedral normals to unit vectors here rather than in libdraco: Debian builds libdraco
// with gcc's default FMA contraction, which on aarch64 fuses the decoding's multiply-adds
// and moves normals a few 1e-9 from x86-64's. Draco's OctahedronToolBox is inline in its
// headers, so compiled here it follows the project's -ffp-contract=off on every architecture
// and gives the bits libdraco gives on x86-64 (tests/scenes/gltf_draco_test.cpp).
bool isOctahedral(const draco::PointAttribute& att) {
    const draco::AttributeTransformData* data = att.GetAttributeTransformData();
    return data && data->transform_type() == draco::ATTRIBUTE_OCTAHEDRON_TRANSFORM;
}

std::vector<unsigned char> octahedralNormals(const draco::PointAttribute& att, std::size_t points,
                                             const std::string& name) {
    draco::AttributeOctahedronTransform transform;
    draco::OctahedronToolBox box;
    if (!transform.InitFromAttribute(att) || att.num_components() != 2 ||
        !box.SetQuantizationBits(transform.quantization_bits()))
        fail(name + ": invalid octahedral normal encoding");
    const std::vector<unsigned char> st = pointValues<int32_t>(att, points, 2, name);
    std::vector<unsigned char> out(points * 3 * sizeof(float));
    for (std::size_t p = 0; p < points; ++p) {
        int32_t coords[2];
        float normal[3];
        std::memcpy(coords, st.data() + p * sizeof(coords), sizeof(coords));
        box.QuantizedOctahedralCoordsToUnitVector(coords[0], coords[1], normal);
        std::memcpy(out.data() + p * sizeof(normal), normal, sizeof(normal));
    }
    return out;
}

std::vector<unsigned char> attributeBytes(const draco::PointAttribute& att, std::size_t points,
                                          const tinygltf::Accessor& a, const std::string& name) {
    const int n = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return pointValues<float>(att, points, n, name);
        case TINYGLTF_COMPONENT_TYPE_BYTE: return pointValues<int8_t>(att, points, n, name);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return pointValues<uint8_t>(att, points, n, name);
        case TINYGLTF_COMPONENT_TYPE_SHORT: return pointValues<int16_t>(att, points, n, name);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return pointValues<uint16_t>(att, points, n, name);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return pointValues<uint32_t>(att, points, n, name);
        default: fail(name + ": invalid component type " + std::to_string(a.componentType));
    }
}

// "The accessors ... corresponding to the attributes and indices of the primitives must
// match the decompressed data": count and number of components are checked here, values by
// the loader as for any accessor.
void fillAttribute(tinygltf::Model& model, int accessor, const draco::Mesh& mesh, int uniqueId,
                   const std::string& name) {
    const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(uint32_t(uniqueId));
    if (!att) fail(name + ": the Draco mesh has no attribute with unique id " + str(uniqueId));
    tinygltf::Accessor& a = model.accessors[accessor];
    const std::string what = name + ": accessor " + str(accessor);
    if (a.count != mesh.num_points())
        fail(what + " has count " + str(a.count) + " but the Draco mesh has " +
             str(mesh.num_points()) + " points");
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    // (an octahedral normal decodes to 3 floats from Draco's 2 integers)
    const bool octahedral = isOctahedral(*att);
    const int decoded = octahedral ? 3 : att->num_components();
    if (components != decoded)
        fail(what + " has " + std::to_string(components) + " components but Draco attribute " +
             str(uniqueId) + " has " + std::to_string(decoded));
    if (octahedral && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail(what + " must be float for Draco's octahedral normals");
    std::vector<unsigned char> bytes = octahedral
                                           ? octahedralNormals(*att, mesh.num_points(), what)
                                           : attributeBytes(*att, mesh.num_points(), a, what);
    const int view = appendBufferView(model, std::move(bytes));
    model.accessors[accessor].bufferView = view;
    model.accessors[accessor].byteOffset = 0;
}

// The faces' point indices, three per triangle, as 32-bit indices.
void fillIndices(tinygltf::Model& model, int accessor, const draco::Mesh& mesh,
                 const std::string& name) {
    tinygltf::Accessor& a = model.accessors[accessor];
    const std::size_t count = std::size_t(mesh.num_faces()) * 3;
    if (a.type != TINYGLTF_TYPE_SCALAR)
        fail(name + ": accessor " + str(accessor) + " (indices) is not SCALAR");
    if (a.count != count)
        fail(name + ": accessor " + str(accessor) + " (indices) has count " + str(a.count) +
             " but the Draco mesh has " + str(mesh.num_faces()) + " triangles (" + str(count) +
             " indices)");
    std::vector<unsigned char> bytes(count * 4);
    for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
        const draco::Mesh::Face& face = mesh.face(draco::FaceIndex(f));
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = face[c].value();
            std::memcpy(bytes.data() + (std::size_t(f) * 3 + c) * 4, &v, 4);
        }
    }
    const int view = appendBufferView(model, std::move(bytes));
    tinygltf::Accessor& filled = model.accessors[accessor];
    filled.bufferView = view;
    filled.byteOffset = 0;
    filled.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// A primitive without indices gets an accessor for the decoded faces.
int newIndexAccessor(tinygltf::Model& model, const draco::Mesh& mesh) {
    tinygltf::Accessor a;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.count = std::size_t(mesh.num_faces()) * 3;
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
}

void decodePrimitive(tinygltf::Model& model, int meshIndex, int primitiveIndex, int indices,
                     std::set<int>& filled) {
    const std::string name =
        "mesh " + str(meshIndex) + " primitive " + str(primitiveIndex) + ": " + kDracoExtension;
    // Copied: the model's vectors grow below.
    const tinygltf::Value ext =
        model.meshes[meshIndex].primitives[primitiveIndex].extensions.at(kDracoExtension);
    if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
        fail(name + ": must be an object with bufferView and attributes");
    const std::unique_ptr<draco::Mesh> mesh = decodeMesh(model, ext, name);
    // "The attributes defined in the extension must be a subset of the attributes of the
    // primitive"; those that are not in the extension are read as usual.
    const tinygltf::Value& attributes = ext.Get("attributes");
    for (const std::string& semantic : attributes.Keys()) {
        std::map<std::string, int>& own =
            model.meshes[meshIndex].primitives[primitiveIndex].attributes;
        const auto it = own.find(semantic);
        if (it == own.end())
            fail(name + ": attribute " + semantic + " is not among the primitive's attributes");
        const int id = indexMember(attributes, semantic.c_str(), name + ": attribute");
        const int accessor = accessorToFill(model, it->second, filled, name + " " + semantic);
        model.meshes[meshIndex].primitives[primitiveIndex].attributes[semantic] = accessor;
        fillAttribute(model, accessor, *mesh, id, name + " " + semantic);
    }
    const int target = indices >= 0 ? accessorToFill(model, indices, filled, name + " indices")
                                    : newIndexAccessor(model, *mesh);
    model.meshes[meshIndex].primitives[primitiveIndex].indices = target;
    fillIndices(model, target, *mesh, name);
}

}  // namespace

// The extension allows TRIANGLES and TRIANGLE_STRIP; Draco decodes a list of triangles, and
// how a strip's indices map to it is not specified, so a strip is refused. A point or line
// primitive is left alone: the loader skips it with its warning.
void decodeDracoPrimitives(tinygltf::Model& model, const CompressionFixups& fixups) {
    std::set<int> filled;
    for (std::size_t i = 0; i < model.meshes.size(); ++i) {
        for (std::size_t k = 0; k < model.meshes[i].primitives.size(); ++k) {
            const tinygltf::Primitive& p = model.meshes[i].primitives[k];
            if (!p.extensions.count(kDracoExtension)) continue;
            const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                fail("mesh " + str(i) + " primitive " + str(k) + ": " + kDracoExtension +
                     ": TRIANGLE_STRIP is not supported (Draco decodes triangle lists)");
            if (mode != TINYGLTF_MODE_TRIANGLES) continue;
            const auto taken = fixups.dracoIndices.find({int(i), int(k)});
            const int indices = taken != fixups.dracoIndices.end() ? taken->second : p.indices;
            decodePrimitive(model, int(i), int(k), indices, filled);
        }
    }
}

}  // namespace ssrt::gltf
