#include "shading/environment.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace ssrt {

EquirectImage::EquirectImage(int w, int h, std::vector<float> pixels)
    : width(w), height(h), rgb(std::move(pixels)) {
    if (w <= 0 || h <= 0 || rgb.size() != std::size_t(3) * w * h)
        throw std::invalid_argument("equirect image: " + std::to_string(w) + "x" +
                                    std::to_string(h) + " needs " + std::to_string(3L * w * h) +
                                    " floats (RGB), got " + std::to_string(rgb.size()));
    updatePoles();
}

Rgb EquirectImage::texel(int x, int y) const {
    const float* p = rgb.data() + (std::size_t(y) * width + x) * 3;
    return {p[0], p[1], p[2]};
}

// The pole values: the plain mean of the first and last rows (every texel of a pole row has
// the same solid angle), summed in double in a fixed order.
void EquirectImage::updatePoles() {
    for (int c = 0; c < 3; ++c) {
        double top = 0.0, bottom = 0.0;
        for (int x = 0; x < width; ++x) {
            top += rgb[std::size_t(x) * 3 + c];
            bottom += rgb[(std::size_t(height - 1) * width + x) * 3 + c];
        }
        poleTop[c] = float(top / width);
        poleBottom[c] = float(bottom / width);
    }
}

namespace {

// The half-open block of input indices [lo, hi) that output index i of n covers (of m).
std::pair<int, int> blockOf(int i, int n, int m) {
    return {int((long long)i * m / n), int((long long)(i + 1) * m / n)};
}

}  // namespace

// Box filter: output texel (x, y) is the plain mean of its block of input texels. With even
// sizes a block is 2 x 2; an odd size gives some blocks 3 texels along that axis, a size of 1
// stays 1. The mean is not weighted by solid angle (adjacent rows differ in solid angle by
// their ratio of sin(theta), close to 1 away from the poles): a mip is a filter for lookups,
// not an integral. Summed in float in a fixed order, so the chain is the same on every run.
EquirectImage downsampleBox(const EquirectImage& src) { return downsampleBox(src.view()); }

EquirectImage downsampleBox(const EquirectView& src) {
    const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    std::vector<float> out(std::size_t(3) * w * h);
    for (int y = 0; y < h; ++y) {
        const auto [y0, y1] = blockOf(y, h, src.height);
        for (int x = 0; x < w; ++x) {
            const auto [x0, x1] = blockOf(x, w, src.width);
            const float inv = 1.0f / float((y1 - y0) * (x1 - x0));
            for (int c = 0; c < 3; ++c) {
                float sum = 0.0f;
                for (int sy = y0; sy < y1; ++sy)
                    for (int sx = x0; sx < x1; ++sx)
                        sum += src.rgb[(std::size_t(sy) * src.width + sx) * 3 + c];
                out[(std::size_t(y) * w + x) * 3 + c] = sum * inv;
            }
        }
    }
    return EquirectImage(w, h, std::move(out));
}

Rgb sampleEquirect(const EquirectImage& img, lanes::V3<float> d) {
    float u, v;
    env::directionToUv(d, u, v);
    const lanes::V3<float> c = env::sampleBilinear(img.view(), u, v);
    return {c.x, c.y, c.z};
}

Environment Environment::constant(Rgb color) {
    Environment e;
    e.color_ = color;
    return e;
}

Environment Environment::equirect(int width, int height, std::vector<float> rgb) {
    Environment e;
    e.mips_.emplace_back(width, height, std::move(rgb));
    while (e.mips_.back().width > 1 || e.mips_.back().height > 1)
        e.mips_.push_back(downsampleBox(e.mips_.back()));
    // The colour of a constant stand-in: the top mip (the plain texel mean).
    e.color_ = e.mips_.back().texel(0, 0);
    return e;
}

Rgb Environment::radiance(lanes::V3<float> d) const {
    if (isConstant()) return color_;
    return sampleEquirect(mips_[0], d);
}

// Trilinear: bilinear in the two levels around lod, then linear between them.
Rgb Environment::radianceLod(lanes::V3<float> d, float lod) const {
    if (isConstant()) return color_;
    const float maxLod = float(mipCount() - 1);
    const float l = std::clamp(lod, 0.0f, maxLod);  // (a NaN lod would stay NaN: callers clamp)
    const int l0 = std::min(int(l), mipCount() - 1);
    const int l1 = std::min(l0 + 1, mipCount() - 1);
    const float t = l - float(l0);
    float u, v;
    env::directionToUv(d, u, v);
    const lanes::V3<float> a = env::sampleBilinear(mips_[l0].view(), u, v);
    if (t == 0.0f || l1 == l0) return {a.x, a.y, a.z};
    const lanes::V3<float> b = env::sampleBilinear(mips_[l1].view(), u, v);
    return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t};
}

}  // namespace ssrt
