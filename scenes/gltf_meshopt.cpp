// EXT_meshopt_compression: compressed buffer views decoded with Debian's libmeshoptimizer.
// https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_meshopt_compression
#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <cmath>
#include <stdexcept>

#include "scenes/gltf_compression.h"
#include "scenes/gltf_errors.h"

namespace ssrt::gltf {
namespace {

// The most bytes one compressed byte can decode to. Attributes (Appendix A, mode 0): each
// data block's header spends 2 bits on a group of 16 bytes, so an all-zero group costs a
// quarter of a byte for 16 (64 to 1); triangles (mode 1) need a code byte per triangle of at
// most 12 bytes, indices (mode 2) a byte per index of at most 4. A view that claims more than
// this is refused before its output is allocated.
constexpr std::size_t kMaxExpansion = 64;

void checkLayout(const MeshoptView& v) {
    const std::size_t stride = v.byteStride;
    const bool indices = v.mode == "TRIANGLES" || v.mode == "INDICES";
    if (v.mode != "ATTRIBUTES" && !indices)
        fail("mode \"" + v.mode + "\" is not ATTRIBUTES, TRIANGLES or INDICES");
    if (v.mode == "ATTRIBUTES" && (stride == 0 || stride % 4 != 0 || stride > 256))
        fail("byteStride " + str(stride) + " must be a multiple of 4 from 4 to 256 for ATTRIBUTES");
    if (v.mode == "TRIANGLES" && v.count % 3 != 0)
        fail("count " + str(v.count) + " is not a multiple of 3 for TRIANGLES");
    if (indices && stride != 2 && stride != 4)
        fail("byteStride " + str(stride) + " must be 2 or 4 for " + v.mode);
    if (indices && v.filter != "NONE") fail("filter " + v.filter + " is only for ATTRIBUTES");
    if (v.filter == "OCTAHEDRAL" && stride != 4 && stride != 8)
        fail("byteStride " + str(stride) + " must be 4 or 8 for the OCTAHEDRAL filter");
    if (v.filter == "QUATERNION" && stride != 8)
        fail("byteStride " + str(stride) + " must be 8 for the QUATERNION filter");
    if (v.filter != "NONE" && v.filter != "OCTAHEDRAL" && v.filter != "QUATERNION" &&
        v.filter != "EXPONENTIAL")
        fail("filter \"" + v.filter + "\" is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
}

// A non-negative integer member; `fallback` when absent (-1: required).
std::size_t sizeMember(const tinygltf::Value& ext, const char* key, double fallback) {
    if (!ext.Has(key)) {
        if (fallback < 0) fail(std::string(key) + " is missing");
        return std::size_t(fallback);
    }
    const tinygltf::Value& v = ext.Get(key);
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d <= 9007199254740992.0 && d == std::floor(d)))
        fail(std::string(key) + " must be a non-negative integer");
    return std::size_t(d);
}

std::string stringMember(const tinygltf::Value& ext, const char* key, const char* fallback) {
    if (!ext.Has(key)) {
        if (!fallback) fail(std::string(key) + " is missing");
        return fallback;
    }
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsString()) fail(std::string(key) + " must be a string");
    return v.Get<std::string>();
}

// The decoded bytes of view `index` (which carries the extension).
std::vector<unsigned char> decodeView(const tinygltf::Model& model, std::size_t index,
                                      const CompressionFixups& fixups) {
    const tinygltf::BufferView& view = model.bufferViews[index];
    const tinygltf::Value& ext = view.extensions.at(kMeshoptExtension);
    if (!ext.IsObject()) fail("must be an object");
    const std::size_t buffer = sizeMember(ext, "buffer", -1);
    if (buffer >= model.buffers.size())
        fail("buffer " + str(buffer) + " out of range (" + str(model.buffers.size()) + " buffers)");
    if (fixups.fallbackBuffers.count(int(buffer)))
        fail("buffer " + str(buffer) + " is a fallback buffer and cannot hold compressed data");
    const std::vector<unsigned char>& data = model.buffers[buffer].data;
    const std::size_t offset = sizeMember(ext, "byteOffset", 0);
    const std::size_t length = sizeMember(ext, "byteLength", -1);
    if (offset > data.size() || length > data.size() - offset)
        fail("bytes " + str(offset) + " to " + str(offset) + " + " + str(length) +
             " overrun buffer " + str(buffer) + " (" + str(data.size()) + " bytes)");
    MeshoptView v;
    v.byteStride = sizeMember(ext, "byteStride", -1);
    v.count = sizeMember(ext, "count", -1);
    v.mode = stringMember(ext, "mode", nullptr);
    v.filter = stringMember(ext, "filter", "NONE");
    if (view.byteStride != 0 && view.byteStride != v.byteStride)
        fail("byteStride " + str(v.byteStride) + " differs from the bufferView's " +
             str(view.byteStride));
    if (v.byteStride == 0 || view.byteLength % v.byteStride != 0 ||
        view.byteLength / v.byteStride != v.count)
        fail("the bufferView's byteLength " + str(view.byteLength) + " is not count " +
             str(v.count) + " times byteStride " + str(v.byteStride));
    return decodeMeshoptView(v, data.data() + offset, length);
}

}  // namespace

std::vector<unsigned char> decodeMeshoptView(const MeshoptView& v, const unsigned char* data,
                                             std::size_t size) {
    checkLayout(v);
    if (v.count > size * kMaxExpansion / v.byteStride)
        fail(str(v.count) + " elements of " + str(v.byteStride) + " bytes cannot come from " +
             str(size) + " compressed bytes");
    std::vector<unsigned char> out(v.count * v.byteStride);
    int rc = 0;
    if (v.mode == "ATTRIBUTES")
        rc = meshopt_decodeVertexBuffer(out.data(), v.count, v.byteStride, data, size);
    else if (v.mode == "TRIANGLES")
        rc = meshopt_decodeIndexBuffer(out.data(), v.count, v.byteStride, data, size);
    else rc = meshopt_decodeIndexSequence(out.data(), v.count, v.byteStride, data, size);
    if (rc != 0)
        fail("the " + v.mode + " data cannot be decoded (meshoptimizer " +
             std::to_string(MESHOPTIMIZER_VERSION / 1000) + "." +
             std::to_string(MESHOPTIMIZER_VERSION % 1000 / 10) + " error " + std::to_string(rc) +
             ": malformed, or a newer codec version)");
    // Appendix B: the filters run in place on the decoded elements.
    if (v.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), v.count, v.byteStride);
    if (v.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), v.count, v.byteStride);
    if (v.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), v.count, v.byteStride);
    return out;
}

// Each compressed view then reads a new buffer of its decoded bytes. A plain view of a
// fallback buffer is refused: that buffer was never loaded.
void decodeMeshoptViews(tinygltf::Model& model, const CompressionFixups& fixups) {
    for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
        const std::string name = "bufferView " + str(i);
        if (!model.bufferViews[i].extensions.count(kMeshoptExtension)) {
            const int buffer = model.bufferViews[i].buffer;
            if (fixups.fallbackBuffers.count(buffer))
                fail(name + " reads fallback buffer " + std::to_string(buffer) +
                     ", which is never loaded, without " + kMeshoptExtension);
            continue;
        }
        std::vector<unsigned char> bytes;
        try {
            bytes = decodeView(model, i, fixups);
        } catch (const std::runtime_error& e) {
            fail(name + ": " + kMeshoptExtension + ": " + e.what());
        }
        model.buffers.emplace_back();
        model.buffers.back().data = std::move(bytes);
        tinygltf::BufferView& view = model.bufferViews[i];
        view.buffer = int(model.buffers.size() - 1);
        view.byteOffset = 0;
        view.extensions.erase(kMeshoptExtension);
    }
}

}  // namespace ssrt::gltf
