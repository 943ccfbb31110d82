#include "scenes/gltf_textures.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <stdexcept>

namespace ssrt::gltf {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& problem) { throw std::runtime_error(problem); }

}  // namespace

std::string percentDecoded(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
            std::isxdigit((unsigned char)uri[i + 2])) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

namespace {

// A file name OIIO can pick the decoder by.
std::string formatHint(const std::string& mimeType) {
    if (mimeType == "image/png") return "image.png";
    if (mimeType == "image/jpeg") return "image.jpg";
    fail("image type '" + mimeType + "' is not supported (glTF allows image/png and image/jpeg)");
}

TextureWrap wrapMode(int gl) {
    switch (gl) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
        case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
        default: fail("sampler wrap mode " + std::to_string(gl) + " is not a glTF wrap mode");
    }
}

}  // namespace

bool keepDataUriImage(tinygltf::Image* image, int imageIndex, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void* dataUriImages) {
    // Buffer-view images are read from the buffer later, with bounds checks; external files
    // are read by name. Only data URIs have no other source.
    if (image->bufferView >= 0 || !image->uri.empty() || size <= 0) return true;
    auto& store = *static_cast<DataUriImages*>(dataUriImages);
    store[imageIndex].assign(bytes, bytes + size);
    return true;
}

TextureTable::TextureTable(const tinygltf::Model& model, std::string gltfPath,
                           const DataUriImages& dataUris, std::vector<Texture>& out)
    : model_(model), path_(std::move(gltfPath)), dataUris_(dataUris), out_(out) {}

int32_t TextureTable::get(int textureIndex, int texCoord, TextureEncoding encoding) {
    if (texCoord != 0)
        fail("texture " + std::to_string(textureIndex) + " uses TEXCOORD_" +
             std::to_string(texCoord) + " (only TEXCOORD_0 is supported)");
    const auto key = std::make_pair(textureIndex, encoding);
    if (auto it = loaded_.find(key); it != loaded_.end()) return it->second;
    out_.push_back(load(textureIndex, encoding));
    const auto index = int32_t(out_.size() - 1);
    loaded_[key] = index;
    return index;
}

Texture TextureTable::load(int textureIndex, TextureEncoding encoding) const {
    const std::string what = "texture " + std::to_string(textureIndex);
    if (textureIndex < 0 || std::size_t(textureIndex) >= model_.textures.size())
        fail(what + " does not exist");
    const tinygltf::Texture& tex = model_.textures[textureIndex];
    if (tex.source < 0 || std::size_t(tex.source) >= model_.images.size())
        fail(what + " has no image (source " + std::to_string(tex.source) + ")");
    const tinygltf::Image& img = model_.images[tex.source];
    const std::string name = "image " + std::to_string(tex.source);
    Texture texture;
    if (img.bufferView >= 0) {
        if (std::size_t(img.bufferView) >= model_.bufferViews.size())
            fail(name + ": bufferView " + std::to_string(img.bufferView) + " out of range");
        const tinygltf::BufferView& bv = model_.bufferViews[img.bufferView];
        if (bv.buffer < 0 || std::size_t(bv.buffer) >= model_.buffers.size())
            fail(name + ": buffer " + std::to_string(bv.buffer) + " out of range");
        const std::vector<unsigned char>& buf = model_.buffers[bv.buffer].data;
        if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
            fail(name + ": bufferView " + std::to_string(img.bufferView) + " overruns its buffer");
        texture = decodeTexture(name, buf.data() + bv.byteOffset, bv.byteLength,
                                formatHint(img.mimeType), encoding);
    } else if (auto it = dataUris_.find(tex.source); it != dataUris_.end()) {
        texture = decodeTexture(name, it->second.data(), it->second.size(),
                                formatHint(img.mimeType), encoding);
    } else if (!img.uri.empty()) {
        const fs::path file = fs::path(path_).parent_path() / percentDecoded(img.uri);
        std::error_code ec;
        if (!fs::is_regular_file(file, ec)) fail(name + " file not found: " + file.string());
        try {
            texture = readTexture(file.string(), encoding);
        } catch (const std::runtime_error& e) {
            fail(name + ": " + e.what());  // the error names the file; say which image it is
        }
    } else {
        fail(name + " has no data");
    }
    texture.name = img.name.empty() ? name : img.name;
    if (tex.sampler >= 0) {
        if (std::size_t(tex.sampler) >= model_.samplers.size())
            fail(what + ": sampler " + std::to_string(tex.sampler) + " does not exist");
        const tinygltf::Sampler& s = model_.samplers[tex.sampler];
        texture.wrapU = wrapMode(s.wrapS);
        texture.wrapV = wrapMode(s.wrapT);
    }
    return texture;
}

}  // namespace ssrt::gltf
