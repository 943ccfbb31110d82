// The environment: radiance arriving from infinitely far away, by direction. Either a
// constant colour (a uniform sky) or an equirectangular (latitude-longitude) float RGB image
// held in memory (loading files is the loaders' business, not the core library's).
//
// Lat-long mapping (+Y up, right-handed):
//   u = 0.5 + atan2(d.x, -d.z) / (2 pi)   in (0, 1]; u = 0.5 looks down -Z (the image centre),
//                                          u = 0.75 is +X, u = 0.25 is -X, and the seam
//                                          u = 0 = 1 lies at +Z;
//   v = atan2(|d.xz|, d.y) / pi            in [0, 1]; v = 0 is +Y (row 0), v = 1 is -Y.
// Texel (i, j) covers u in [i, i + 1) / w, v in [j, j + 1) / h; its centre is at +0.5.
// Seen from inside, looking down -Z with +Y up, the image appears unmirrored.
//
// Filtering is bilinear with u wrapping around the seam. Towards the poles (v < 0.5 / h or
// v > 1 - 0.5 / h) the row nearest the pole is blended with the pole value, the mean of that
// row, which every azimuth reaches at v = 0 (or 1): so lookups are continuous everywhere on
// the sphere, the poles included.
//
// The bilinear fetch is written once over the lane type (float or xsimd::batch<float, A>),
// so a kernel that looks up misses per lane gets the same bits as this scalar set-up code.
#pragma once

#include <array>
#include <vector>

#include "core/lane_math.h"
#include "core/lane_vec.h"

namespace ssrt {

struct Rgb {
    float r = 0.0f, g = 0.0f, b = 0.0f;
};

// A borrowed view of one equirect image, for the lane-generic fetch below.
struct EquirectView {
    const float* rgb = nullptr;  // interleaved RGB, row-major, 3 * width * height floats
    int width = 0, height = 0;
    const float* poleTop = nullptr;     // 3 floats: the mean of row 0
    const float* poleBottom = nullptr;  // 3 floats: the mean of row height - 1
};

// An owned equirect image: interleaved RGB, row-major, row 0 at +Y.
struct EquirectImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
    std::array<float, 3> poleTop{}, poleBottom{};

    EquirectImage() = default;
    // Computes the pole values; throws std::invalid_argument unless pixels has 3 w h floats.
    EquirectImage(int w, int h, std::vector<float> pixels);

    Rgb texel(int x, int y) const;
    EquirectView view() const {
        return {rgb.data(), width, height, poleTop.data(), poleBottom.data()};
    }
    void updatePoles();  // after writing rgb directly
};

namespace env {

namespace ln = ssrt::lanes;
using ln::V3;

inline constexpr float kInvTwoPi = 0.159154943091895335769f;

// Direction (any length, not zero) to (u, v) as in the header comment.
template <class L>
SSRT_INLINE void directionToUv(V3<L> d, L& u, L& v) {
    u = L(0.5f) + ln::atan2(d.x, L(0.0f) - d.z) * L(kInvTwoPi);
    v = ln::atan2(ln::sqrt(d.x * d.x + d.z * d.z), d.y) * L(ln::kInvPi);
}

// The inverse: the unit direction of (u, v).
template <class L>
SSRT_INLINE V3<L> uvToDirection(L u, L v) {
    L sp, cp, st, ct;
    ln::sincos((u - L(0.5f)) * L(2.0f * ln::kPi), sp, cp);
    ln::sincos(v * L(ln::kPi), st, ct);
    return {st * sp, ct, L(0.0f) - st * cp};
}

// Bilinear fetch at (u, v): u wraps, v blends into the pole values (header comment).
template <class L>
SSRT_INLINE V3<L> sampleBilinear(const EquirectView& img, L u, L v) {
    using I = ln::IntOf<L>;
    const float w = float(img.width), h = float(img.height);
    // Columns: x0 wrapped into [0, w), x1 its right neighbour across the seam
    const L x = u * L(w) - L(0.5f);
    const L xf = ln::floor(x);
    const L fx = x - xf;
    const L x0 = xf - L(w) * ln::floor(xf * L(1.0f / w));
    const L x1r = x0 + L(1.0f);
    const L x1 = ln::select(x1r >= L(w), L(0.0f), x1r);
    // Rows: y0 = -1 and y1 = h stand for the poles, which sit half a texel beyond the rows
    const L y = ln::clamp(v, L(0.0f), L(1.0f)) * L(h) - L(0.5f);
    const L y0 = ln::floor(y);
    const L fyRaw = y - y0;
    const auto top = y0 < L(0.0f);
    const auto bottom = y0 + L(1.0f) > L(h - 1.0f);
    const L fy = ln::saturate(
        ln::select(top, fyRaw + fyRaw - L(1.0f), ln::select(bottom, fyRaw + fyRaw, fyRaw)));
    const L r0 = ln::max(y0, L(0.0f)), r1 = ln::min(y0 + L(1.0f), L(h - 1.0f));
    // Gather the four texels, channel by channel
    // (texel indices are exact in float below 2^24 texels; the x3 is done in integers)
    const I k00 = ln::toIntTrunc(r0 * L(w) + x0), k01 = ln::toIntTrunc(r0 * L(w) + x1);
    const I k10 = ln::toIntTrunc(r1 * L(w) + x0), k11 = ln::toIntTrunc(r1 * L(w) + x1);
    const I i00 = k00 + k00 + k00, i01 = k01 + k01 + k01;
    const I i10 = k10 + k10 + k10, i11 = k11 + k11 + k11;
    L out[3];
    for (int c = 0; c < 3; ++c) {
        const L a = ln::gather(img.rgb, i00 + I(c)), b = ln::gather(img.rgb, i01 + I(c));
        const L d = ln::gather(img.rgb, i10 + I(c)), e = ln::gather(img.rgb, i11 + I(c));
        const L upper = ln::select(top, L(img.poleTop[c]), a + (b - a) * fx);
        const L lower = ln::select(bottom, L(img.poleBottom[c]), d + (e - d) * fx);
        out[c] = upper + (lower - upper) * fy;
    }
    return {out[0], out[1], out[2]};
}

}  // namespace env

// A constant colour or an equirect image with its mip chain.
class Environment {
public:
    Environment() = default;  // black
    static Environment constant(Rgb color);
    // width x height interleaved RGB floats, row 0 at +Y (see the header comment).
    static Environment equirect(int width, int height, std::vector<float> rgb);

    bool isConstant() const { return mips_.empty(); }
    Rgb constantColor() const { return color_; }

    // Mip chain: level 0 is the image; each next level halves width and height (down to 1)
    // by a box filter. Empty for a constant environment.
    int mipCount() const { return int(mips_.size()); }
    const EquirectImage& mip(int level) const { return mips_[level]; }

    // Radiance arriving from direction d (pointing away from the receiver, any length):
    // bilinear at level 0, and trilinear across levels at a fractional lod (clamped).
    Rgb radiance(lanes::V3<float> d) const;
    Rgb radianceLod(lanes::V3<float> d, float lod) const;

private:
    Rgb color_{};
    std::vector<EquirectImage> mips_;
};

// One box-filtered level down: width and height halve (odd sizes and 1 handled: each output
// texel averages the input texels of its own block, the blocks partitioning the input).
EquirectImage downsampleBox(const EquirectImage& src);
EquirectImage downsampleBox(const EquirectView& src);  // the same, from borrowed pixels

// Bilinear radiance of one image at direction d.
Rgb sampleEquirect(const EquirectImage& img, lanes::V3<float> d);

}  // namespace ssrt
