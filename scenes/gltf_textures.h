// glTF textures for the loader (part of ssrt_gltf): images from external files, data URIs
// or buffer views, decoded through OpenImageIO (io/texture_io.h), each (texture, encoding)
// pair once, with the sampler's wrap modes (all three of glTF's). Filters are checked to be
// glTF's values and otherwise not used: every texture is sampled one way (scenes/texture.h).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/texture_io.h"
#include "scenes/texture.h"

namespace tinygltf {
class Model;
struct Image;
struct TextureInfo;
}  // namespace tinygltf

namespace ssrt {
struct UvTransform;
}

namespace ssrt::gltf {

// The decoded bytes of data-URI images, by image index. tinygltf hands every image's bytes
// to an image callback; keepDataUriImage (installed with this map as its user data) keeps
// those of data URIs, the only ones that cannot be found again afterwards.
using DataUriImages = std::map<int, std::vector<unsigned char>>;

bool keepDataUriImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn,
                      int reqWidth, int reqHeight, const unsigned char* bytes, int size,
                      void* dataUriImages);

// A URI with its %XX escapes decoded (glTF URIs are percent-encoded).
std::string percentDecoded(const std::string& uri);

// A texture reference's KHR_texture_transform (offset, rotation, scale; the identity when
// absent) as a UvTransform (scenes/scene.h), and the texture coordinate set it samples: the
// extension's texCoord overrides the reference's. Throws std::runtime_error (one line) for
// a malformed extension (a member of the wrong type or size, or not finite).
UvTransform textureTransform(const tinygltf::TextureInfo& info, int* texCoord);

class TextureTable {
public:
    TextureTable(const tinygltf::Model& model, std::string gltfPath, const DataUriImages& dataUris,
                 std::vector<Texture>& out);

    // The index in `out` of glTF texture `textureIndex` decoded with `encoding`. Throws
    // std::runtime_error (one line, without the file's path) for a texture or image that is
    // missing, out of range, uses a texture coordinate set other than 0 and 1, has a wrap
    // mode or filter that is not glTF's, or cannot be decoded.
    int32_t get(int textureIndex, int texCoord, TextureEncoding encoding);

private:
    Texture load(int textureIndex, TextureEncoding encoding) const;

    const tinygltf::Model& model_;
    std::string path_;
    const DataUriImages& dataUris_;
    std::vector<Texture>& out_;
    std::map<std::pair<int, TextureEncoding>, int32_t> loaded_;
};

}  // namespace ssrt::gltf
