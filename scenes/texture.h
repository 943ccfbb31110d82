// Textures of the scene model: linear RGBA float texels with a full mip chain, sampled
// trilinearly with a level of detail from screen-space UV derivatives.
//
// Conventions (glTF 2.0):
//   UV (0, 0) is the top-left corner of the image (row 0 first), (1, 1) the bottom-right;
//   texel (i, j) covers u in [i, i + 1) / w, v in [j, j + 1) / h, its centre at +0.5.
//   Base-colour images are sRGB encoded and decoded on loading (core/color.h); metallic-
//   roughness images are linear (roughness in G, metallic in B).
//
// Mip level k + 1 is the 2x2 box average of level k (sizes halve, rounding down, never
// below 1; an odd last row or column is folded into its neighbour's average with weight
// 1/3 so that every texel contributes). The level of detail is OpenGL's isotropic one:
//   rho = max(|dUV/dx|, |dUV/dy|) measured in level-0 texels, lod = log2(rho),
// clamped to [0, levels - 1]; magnification (lod <= 0) is bilinear on level 0.
// Everything here is scalar code that uses the project's own log2 and pow, so the same
// inputs give the same bits on every machine and for every ISA.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/image.h"

namespace ssrt {

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

struct TextureLevel {
    int width = 0, height = 0;
    std::vector<glm::vec4> texels;  // row-major, row 0 at v = 0

    const glm::vec4& at(int x, int y) const { return texels[std::size_t(y) * width + x]; }
};

struct Texture {
    std::string name;
    TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
    std::vector<TextureLevel> levels;  // levels[0] is the image itself

    Texture() = default;
    // Takes level 0 (linear RGBA, w * h texels) and builds the mip chain. Throws
    // std::invalid_argument for a zero size, a texel count that does not match, or a texel
    // that is not finite.
    Texture(std::string name, int width, int height, std::vector<glm::vec4> texels);

    int width() const { return levels.empty() ? 0 : levels[0].width; }
    int height() const { return levels.empty() ? 0 : levels[0].height; }

    // Bilinear lookup in one level, with this texture's wrap modes.
    glm::vec4 sampleLevel(int level, glm::vec2 uv) const;
    // Trilinear lookup: the UV and its derivatives along the screen's x and y.
    glm::vec4 sample(glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy) const;
    // The level of detail (before clamping) for those derivatives.
    float lod(glm::vec2 dUVdx, glm::vec2 dUVdy) const;
};

// A texture from a decoded RGBA image (io/texture_io.h): its pixels are level 0, the mips
// are built. Throws std::invalid_argument as the constructor does, and for an image that
// does not hold 4 channels.
Texture makeTexture(std::string name, const InterleavedImage& rgba);

}  // namespace ssrt
