#include "scenes/texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/lane_math.h"

namespace ssrt {

namespace {

// One halving along x: out column i averages in columns 2i and 2i + 1, and the last one
// also takes column w - 1 when w is odd (a 3-tap box), so no texel is dropped.
TextureLevel halveX(const TextureLevel& in) {
    TextureLevel out;
    out.width = std::max(1, in.width / 2);
    out.height = in.height;
    out.texels.resize(std::size_t(out.width) * out.height);
    const bool odd = in.width % 2 == 1;
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            glm::vec4 sum = in.at(2 * x, y) + in.at(2 * x + 1, y);
            float n = 2.0f;
            if (odd && x == out.width - 1) {
                sum += in.at(in.width - 1, y);
                n = 3.0f;
            }
            out.texels[std::size_t(y) * out.width + x] = sum / n;
        }
    return out;
}

// The same along y.
TextureLevel halveY(const TextureLevel& in) {
    TextureLevel out;
    out.width = in.width;
    out.height = std::max(1, in.height / 2);
    out.texels.resize(std::size_t(out.width) * out.height);
    const bool odd = in.height % 2 == 1;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            glm::vec4 sum = in.at(x, 2 * y) + in.at(x, 2 * y + 1);
            float n = 2.0f;
            if (odd && y == out.height - 1) {
                sum += in.at(x, in.height - 1);
                n = 3.0f;
            }
            out.texels[std::size_t(y) * out.width + x] = sum / n;
        }
    return out;
}

// A texel index in [0, n) for any integer i, by the wrap mode.
int wrapIndex(int i, int n, TextureWrap mode) {
    if (unsigned(i) < unsigned(n)) return i;  // inside: every mode agrees
    switch (mode) {
        case TextureWrap::ClampToEdge: return std::clamp(i, 0, n - 1);
        case TextureWrap::MirroredRepeat: {
            const int period = 2 * n;
            const int m = ((i % period) + period) % period;
            return m < n ? m : period - 1 - m;
        }
        case TextureWrap::Repeat:
        default: return ((i % n) + n) % n;
    }
}

// The two texels a bilinear lookup blends along one axis, i and i + 1, wrapped.
void wrapPair(int i, int n, TextureWrap mode, int& a, int& b) {
    a = wrapIndex(i, n, mode);
    // Repeat: the next texel follows a (one modulo, not two).
    b = mode == TextureWrap::Repeat ? (a + 1 == n ? 0 : a + 1) : wrapIndex(i + 1, n, mode);
}

// Texel-space coordinate of u on n texels, kept where float still has whole texels
// (|x| < 2^22) and where int conversion is defined; NaN goes to 0.
float texelCoordinate(float u, int n) {
    const float x = u * float(n) - 0.5f;
    if (!(x == x)) return -0.5f;
    return std::clamp(x, -4194304.0f, 4194304.0f);
}

float footprint(glm::vec2 d, float w, float h) {
    const float du = d.x * w, dv = d.y * h;
    return std::sqrt(du * du + dv * dv);
}

}  // namespace

Texture::Texture(std::string textureName, int width, int height, std::vector<glm::vec4> texels)
    : name(std::move(textureName)) {
    if (width < 1 || height < 1)
        throw std::invalid_argument("texture '" + name + "': size must be at least 1x1");
    if (texels.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("texture '" + name + "': texel count does not match its size");
    for (const glm::vec4& t : texels)
        if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z) ||
            !std::isfinite(t.w))
            throw std::invalid_argument("texture '" + name + "': a texel is not finite");
    levels.push_back({width, height, std::move(texels)});
    while (levels.back().width > 1 || levels.back().height > 1) {
        TextureLevel next = levels.back();
        if (next.width > 1) next = halveX(next);
        if (next.height > 1) next = halveY(next);
        levels.push_back(std::move(next));
    }
}

glm::vec4 Texture::sampleLevel(int level, glm::vec2 uv) const {
    const TextureLevel& l = levels[std::clamp(level, 0, int(levels.size()) - 1)];
    const float x = texelCoordinate(uv.x, l.width), y = texelCoordinate(uv.y, l.height);
    const float fx0 = std::floor(x), fy0 = std::floor(y);
    const float fx = x - fx0, fy = y - fy0;
    const int x0 = int(fx0), y0 = int(fy0);
    int xa, xb, ya, yb;
    wrapPair(x0, l.width, wrapU, xa, xb);
    wrapPair(y0, l.height, wrapV, ya, yb);
    const glm::vec4 top = l.at(xa, ya) * (1.0f - fx) + l.at(xb, ya) * fx;
    const glm::vec4 bottom = l.at(xa, yb) * (1.0f - fx) + l.at(xb, yb) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

float Texture::lod(glm::vec2 dUVdx, glm::vec2 dUVdy) const {
    const float w = float(width()), h = float(height());
    const float rho = std::max(footprint(dUVdx, w, h), footprint(dUVdy, w, h));
    if (!(rho > 0.0f)) return 0.0f;                     // zero or NaN: level 0
    if (!(rho < 3.0e38f)) return float(levels.size());  // infinite: the last level
    return lanes::log2(rho);
}

glm::vec4 Texture::sample(glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy) const {
    const float last = float(levels.size() - 1);
    const float l = std::clamp(lod(dUVdx, dUVdy), 0.0f, last);
    const float l0 = std::floor(l);
    const float f = l - l0;
    const glm::vec4 a = sampleLevel(int(l0), uv);
    if (f == 0.0f) return a;
    return a * (1.0f - f) + sampleLevel(int(l0) + 1, uv) * f;
}

Texture makeTexture(std::string name, const InterleavedImage& rgba) {
    if (rgba.channels != 4)
        throw std::invalid_argument("texture '" + name + "': an RGBA image has 4 channels, not " +
                                    std::to_string(rgba.channels));
    const std::size_t count = std::size_t(rgba.width) * std::size_t(rgba.height);
    if (rgba.width < 1 || rgba.height < 1 || rgba.pixels.size() != count * 4)
        throw std::invalid_argument("texture '" + name + "': the pixels are not " +
                                    std::to_string(rgba.width) + "x" + std::to_string(rgba.height) +
                                    " RGBA");
    std::vector<glm::vec4> texels(count);
    for (std::size_t i = 0; i < count; ++i)
        texels[i] = glm::vec4(rgba.pixels[i * 4], rgba.pixels[i * 4 + 1], rgba.pixels[i * 4 + 2],
                              rgba.pixels[i * 4 + 3]);
    return Texture(std::move(name), rgba.width, rgba.height, std::move(texels));
}

}  // namespace ssrt
