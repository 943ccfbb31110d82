// libFuzzer target for textures (io/texture_io.h) as glTF files embed them: bytes in memory,
// sRGB (base colour) or linear. Every input either gives an RGBA texture of finite texels or
// is refused with std::runtime_error; anything else is a bug.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "io/texture_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    // The first byte picks the encoding; the image follows it.
    const auto encoding = data[0] & 1 ? ssrt::TextureEncoding::Srgb : ssrt::TextureEncoding::Linear;
    try {
        const ssrt::InterleavedImage image =
            ssrt::decodeTextureImage("texture", data + 1, size - 1, "texture.png", encoding);
        if (image.channels != 4) std::abort();
        for (const float v : image.pixels)
            if (!std::isfinite(v)) std::abort();  // the reader's contract
    } catch (const std::runtime_error&) {
        // refused cleanly: fine
    }
    return 0;
}
