#include "scenes/gltf_compression.h"

#include <tiny_gltf.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

namespace ssrt::gltf {
namespace {

using Json = nlohmann::json;

bool hasExtension(const Json& object, const char* name) {
    if (!object.is_object()) return false;
    const auto ext = object.find("extensions");
    return ext != object.end() && ext->is_object() && ext->contains(name);
}

// An index member as tinygltf would read it, or -1.
int indexMember(const Json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number_integer()) return -1;
    const auto v = it->get<int64_t>();
    return v >= 0 && v <= INT32_MAX ? int(v) : -1;
}

// tinygltf refuses a primitive whose indices accessor has no bufferView; a Draco primitive's
// accessors have none (the data is in the compressed view). Its indices move to the fixups.
bool takeDracoIndices(Json& root, CompressionFixups* fixups) {
    static const Json kNone = Json::array();
    const auto found = root.find("accessors");
    const Json& accessors = found != root.end() ? *found : kNone;
    if (!root.contains("meshes") || !root["meshes"].is_array() || !accessors.is_array())
        return false;
    bool changed = false;
    for (std::size_t i = 0; i < root["meshes"].size(); ++i) {
        Json& mesh = root["meshes"][i];
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            continue;
        for (std::size_t k = 0; k < mesh["primitives"].size(); ++k) {
            Json& primitive = mesh["primitives"][k];
            if (!hasExtension(primitive, kDracoExtension)) continue;
            const int indices = indexMember(primitive, "indices");
            if (indices < 0 || std::size_t(indices) >= accessors.size()) continue;
            const Json& accessor = accessors[std::size_t(indices)];
            if (accessor.is_object() && accessor.contains("bufferView")) continue;
            fixups->dracoIndices[{int(i), int(k)}] = indices;
            primitive.erase("indices");
            changed = true;
        }
    }
    return changed;
}

// A buffer EXT_meshopt_compression says need not be loaded: tagged as a fallback, or a
// placeholder without a uri (outside a GLB's binary chunk, buffer 0) that only compressed
// views read (the extension's "Fallback buffers").
bool isFallbackBuffer(const Json& root, std::size_t index, bool binary) {
    const Json& buffer = root.at("buffers").at(index);
    if (!buffer.is_object()) return false;
    if (hasExtension(buffer, kMeshoptExtension)) {
        const Json& ext = buffer.at("extensions").at(kMeshoptExtension);
        const auto fallback = ext.find("fallback");  // end() when ext is not an object
        if (fallback != ext.end() && fallback->is_boolean() && fallback->get<bool>()) return true;
    }
    if (buffer.contains("uri") || (binary && index == 0)) return false;
    if (!root.contains("bufferViews") || !root["bufferViews"].is_array()) return false;
    bool read = false;
    for (const Json& view : root.at("bufferViews")) {
        if (indexMember(view, "buffer") != int(index)) continue;
        if (!hasExtension(view, kMeshoptExtension)) return false;
        read = true;
    }
    return read;
}

// The fallback buffers become one-byte data URIs: tinygltf needs a buffer it can load, and
// none of their bytes is ever read (decompress refuses a plain view of one).
bool standInFallbackBuffers(Json& root, bool binary, CompressionFixups* fixups) {
    if (!root.contains("buffers") || !root["buffers"].is_array()) return false;
    bool changed = false;
    for (std::size_t j = 0; j < root["buffers"].size(); ++j) {
        if (!isFallbackBuffer(root, j, binary)) continue;
        Json& buffer = root["buffers"][j];
        buffer["uri"] = "data:application/octet-stream;base64,AA==";
        buffer["byteLength"] = 1;
        fixups->fallbackBuffers.insert(int(j));
        changed = true;
    }
    return changed;
}

void appendU32(std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

uint32_t loadU32(const std::string& s, std::size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, s.data() + at, 4);
    return v;
}

// GLB (glTF 2.0 section 4.4): a 12-byte header, the JSON chunk, then the other chunks as they
// were. The JSON chunk is padded with spaces to 4 bytes.
std::string withJsonChunk(const std::string& glb, std::string json) {
    const std::size_t oldLength = loadU32(glb, 12);
    while (json.size() % 4) json += ' ';
    const std::string rest = glb.substr(20 + oldLength);
    std::string out = glb.substr(0, 8);
    appendU32(out, uint32_t(20 + json.size() + rest.size()));
    appendU32(out, uint32_t(json.size()));
    appendU32(out, 0x4E4F534A);  // "JSON"
    return out + json + rest;
}

}  // namespace

std::optional<std::string> withCompressionFixups(const std::string& file, bool binary,
                                                 CompressionFixups* fixups) {
    *fixups = {};
    std::string json = file;
    if (binary) {  // only a well-formed container; tinygltf reports any other
        if (file.size() < 20 || loadU32(file, 16) != 0x4E4F534A) return std::nullopt;
        const std::size_t length = loadU32(file, 12);
        if (length > file.size() - 20) return std::nullopt;
        json = file.substr(20, length);
    }
    if (json.find(kDracoExtension) == std::string::npos &&
        json.find(kMeshoptExtension) == std::string::npos)
        return std::nullopt;
    Json root = Json::parse(json, nullptr, /*allow_exceptions=*/false);
    if (root.is_discarded() || !root.is_object()) return std::nullopt;
    const bool draco = takeDracoIndices(root, fixups);
    const bool meshopt = standInFallbackBuffers(root, binary, fixups);
    if (!draco && !meshopt) return std::nullopt;
    // dump() writes every double so that it reads back to the same bits.
    return binary ? withJsonChunk(file, root.dump()) : root.dump();
}

void decompress(tinygltf::Model& model, const CompressionFixups& fixups) {
    decodeMeshoptViews(model, fixups);  // first: a Draco view may itself be meshopt-compressed
    decodeDracoPrimitives(model, fixups);
}

int appendBufferView(tinygltf::Model& model, std::vector<unsigned char> bytes) {
    tinygltf::BufferView view;
    view.buffer = int(model.buffers.size());
    view.byteOffset = 0;
    view.byteLength = bytes.size();
    model.buffers.emplace_back();
    model.buffers.back().data = std::move(bytes);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
}

}  // namespace ssrt::gltf
