// Texture images, at the edge: PNG, JPEG, HDR and EXR through their own libraries, any other
// format through OpenImageIO (io/image_decode.h), from a file or from bytes in memory (glTF's
// embedded images).
#pragma once

#include <cstddef>
#include <string>

#include "core/image.h"

namespace ssrt {

enum class TextureEncoding {
    Linear,  // texels are used as stored (metallic-roughness, HDR images)
    Srgb     // colour channels are sRGB encoded (base colour): decoded to linear; alpha is not
};

// Reads the first subimage as RGBA float (4 channels; scenes/texture.h makeTexture builds a
// Texture of it). Alpha is read as stored
// (straight, never premultiplied into colour); grey images fill R, G and B; images without
// alpha get alpha 1; extra channels are ignored. 8- and 16-bit values are normalized here
// (float(v) / 255, float(v) / 65535), not by a library, so the texels are the same bits on every
// CPU. Throws std::runtime_error, one line naming `name` and the problem, for a file that
// cannot be opened or decoded, or for a texel that is not finite.
InterleavedImage readTextureImage(const std::string& path, TextureEncoding encoding);

// The same from an encoded image in memory; `formatHint` is a file name or extension that
// tells OpenImageIO the format when the bytes are for it ("image.png", ".jpg"); `name` is
// used in errors.
InterleavedImage decodeTextureImage(const std::string& name, const void* bytes, std::size_t size,
                                    const std::string& formatHint, TextureEncoding encoding);

}  // namespace ssrt
