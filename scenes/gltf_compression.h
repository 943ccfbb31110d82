// Compressed glTF geometry for the loader (part of ssrt_gltf): KHR_draco_mesh_compression
// through Debian's libdraco and EXT_meshopt_compression through Debian's libmeshoptimizer,
// both decoded into plain buffers, buffer views and accessors before the loader reads an
// accessor, so the rest of the loader sees an uncompressed model and checks it as any other.
//
// Debian's tinygltf 2.7 is built without Draco, and refuses two things these files hold: a
// primitive's indices accessor without a bufferView (every Draco primitive's), and a buffer
// without a uri outside a GLB's binary chunk (meshopt's placeholder fallback buffers). So the
// file's JSON is adjusted before tinygltf parses it (withCompressionFixups), and what was
// taken out is handed to decompress() afterwards. A file that uses neither extension is not
// touched: tinygltf reads it from disk as before.
//
// Specifications:
//   https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_draco_mesh_compression
//   https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_meshopt_compression
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace tinygltf {
class Model;
}

namespace ssrt::gltf {

inline const char* const kDracoExtension = "KHR_draco_mesh_compression";
inline const char* const kMeshoptExtension = "EXT_meshopt_compression";

// What withCompressionFixups took out of the JSON, for decompress().
struct CompressionFixups {
    // (mesh, primitive) -> the indices accessor of a Draco primitive whose indices accessor
    // has no bufferView (removed from the primitive so that tinygltf accepts it).
    std::map<std::pair<int, int>, int> dracoIndices;
    // Fallback buffers of EXT_meshopt_compression (tagged "fallback", or without a uri and
    // read only by compressed views): never loaded; tinygltf sees a one-byte stand-in.
    std::set<int> fallbackBuffers;
};

// `file` is the whole file (.gltf JSON or .glb, `binary`). Returns it adjusted for tinygltf,
// or nothing when no adjustment is needed (the file uses neither extension, or its JSON is
// malformed: tinygltf then reports that itself).
std::optional<std::string> withCompressionFixups(const std::string& file, bool binary,
                                                 CompressionFixups* fixups);

// Decodes every EXT_meshopt_compression buffer view (into a new buffer the view then reads),
// then every KHR_draco_mesh_compression primitive (its accessors then read new buffer views).
// Throws std::runtime_error, one line naming the buffer view or the mesh and primitive.
void decompress(tinygltf::Model& model, const CompressionFixups& fixups);

// One EXT_meshopt_compression view: `count` elements of `byteStride` bytes, decoded by `mode`
// ("ATTRIBUTES", "TRIANGLES", "INDICES") and `filter` ("NONE", "OCTAHEDRAL", "QUATERNION",
// "EXPONENTIAL"), with the extension's validity rules checked. Throws std::runtime_error.
struct MeshoptView {
    std::size_t count = 0;
    std::size_t byteStride = 0;
    std::string mode;
    std::string filter = "NONE";
};
std::vector<unsigned char> decodeMeshoptView(const MeshoptView& view, const unsigned char* data,
                                             std::size_t size);

// For gltf_draco.cpp and gltf_meshopt.cpp: the stages of decompress().
void decodeMeshoptViews(tinygltf::Model& model, const CompressionFixups& fixups);
void decodeDracoPrimitives(tinygltf::Model& model, const CompressionFixups& fixups);
// Appends `bytes` as a new buffer and a tightly packed buffer view over all of it; returns
// the view's index.
int appendBufferView(tinygltf::Model& model, std::vector<unsigned char> bytes);

}  // namespace ssrt::gltf
