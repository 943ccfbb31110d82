#include "scenes/gltf_textures.h"

#include <tiny_gltf.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "scenes/gltf_errors.h"
#include "scenes/scene.h"

namespace ssrt::gltf {

namespace {

namespace fs = std::filesystem;

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

// glTF 2.0's sampler filters (magFilter, minFilter): any of them is accepted and none changes how
// the texture is sampled (scenes/texture.h). -1: absent.
void checkFilters(const tinygltf::Sampler& s, int index) {
    const auto bad = [&](const char* key, int value) {
        fail("sampler " + std::to_string(index) + ": " + key + " " + std::to_string(value) +
             " is not a glTF filter");
    };
    if (s.magFilter != -1 && s.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
        s.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR)
        bad("magFilter", s.magFilter);
    if (s.minFilter != -1 && s.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST &&
        s.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR &&
        (s.minFilter < TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
         s.minFilter > TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR))
        bad("minFilter", s.minFilter);
}

// A finite number, or a finite pair, of the extension `ext` named `key`; `fallback` when
// the member is absent.
double finiteNumber(const tinygltf::Value& ext, const char* key, double fallback) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
        fail(std::string("KHR_texture_transform ") + key + " must be a finite number");
    return v.GetNumberAsDouble();
}

glm::dvec2 finitePair(const tinygltf::Value& ext, const char* key, glm::dvec2 fallback) {
    if (!ext.Has(key)) return fallback;
    const tinygltf::Value& v = ext.Get(key);
    const auto bad = [&] {
        fail(std::string("KHR_texture_transform ") + key + " must be two finite numbers");
    };
    if (!v.IsArray() || v.ArrayLen() != 2) bad();
    glm::dvec2 out;
    for (int i = 0; i < 2; ++i) {
        if (!v.Get(i).IsNumber() || !std::isfinite(v.Get(i).GetNumberAsDouble())) bad();
        out[i] = v.Get(i).GetNumberAsDouble();
    }
    return out;
}

}  // namespace

UvTransform textureTransform(const tinygltf::TextureInfo& info, int* texCoord) {
    *texCoord = info.texCoord;
    const auto it = info.extensions.find("KHR_texture_transform");
    if (it == info.extensions.end()) return {};
    const tinygltf::Value& ext = it->second;
    if (!ext.IsObject()) fail("KHR_texture_transform must be an object");
    if (ext.Has("texCoord")) {
        const tinygltf::Value& t = ext.Get("texCoord");
        if (!t.IsInt() || t.GetNumberAsInt() < 0)
            fail("KHR_texture_transform texCoord must be a non-negative integer");
        *texCoord = t.GetNumberAsInt();
    }
    const glm::dvec2 offset = finitePair(ext, "offset", {0.0, 0.0});
    const glm::dvec2 scale = finitePair(ext, "scale", {1.0, 1.0});
    const double rotation = finiteNumber(ext, "rotation", 0.0);
    // linear = R S, R = [cos sin; -sin cos] (rows), in double, rounded once to float. The
    // extension's defaults give exactly the identity (cos 0 = 1, sin 0 = 0).
    const double c = std::cos(rotation), s = std::sin(rotation);
    UvTransform out;
    out.row0 = glm::vec2(float(c * scale.x), float(s * scale.y));
    out.row1 = glm::vec2(float(-s * scale.x), float(c * scale.y));
    out.offset = glm::vec2(offset);
    return out;
}

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
    if (texCoord != 0 && texCoord != 1)
        fail("texture " + std::to_string(textureIndex) + " uses TEXCOORD_" +
             std::to_string(texCoord) + " (TEXCOORD_0 and TEXCOORD_1 are supported)");
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
        texture =
            makeTexture(name, decodeTextureImage(name, buf.data() + bv.byteOffset, bv.byteLength,
                                                 formatHint(img.mimeType), encoding));
    } else if (auto it = dataUris_.find(tex.source); it != dataUris_.end()) {
        texture = makeTexture(name, decodeTextureImage(name, it->second.data(), it->second.size(),
                                                       formatHint(img.mimeType), encoding));
    } else if (!img.uri.empty()) {
        const fs::path file = fs::path(path_).parent_path() / percentDecoded(img.uri);
        std::error_code ec;
        if (!fs::is_regular_file(file, ec)) fail(name + " file not found: " + file.string());
        try {
            texture = makeTexture(file.string(), readTextureImage(file.string(), encoding));
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
        checkFilters(s, tex.sampler);
        texture.wrapU = wrapMode(s.wrapS);
        texture.wrapV = wrapMode(s.wrapT);
    }
    return texture;
}

}  // namespace ssrt::gltf
