#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "core/signal_lanes.h"
#include "denoise/reblur_lanes.h"

// REBLUR's history fix, one copy per ISA (denoise/reblur_lanes.h has what the passes share).

namespace ssrt::SSRT_ISA_NS {

namespace {

using namespace reblur_lanes;

// ---------------------------------------------------------------------------------------
// History fix (REBLUR_HistoryFix): young pixels get a wide reconstruction; the fast history
// clamps the slow one (anti-lag).

// Young pixels' reconstruction: the pixel and a sparse 5x5 of taps `stride` apart (wider the
// younger), weighted by plane distance, normal (and roughness) and the taps' own history. A
// specular pixel reaches (2 strides) no farther than its reflection's lobe spans
// (specularLobePixels), and one whose lobe spans less than 2 pixels keeps its own signal: its
// neighbours show other parts of the reflection (a mirror's: issue 44), and a lobe that narrow
// gives the signal little noise to remove. (One copy per signal, a.specular: each leaves out
// the other's branches.)
template <bool spec>
void reconstructYoung(const ReblurPassArgs& a, const Centre& p, Mask young, int x, int y,
                      const Lane frames, const Lane c[4], Lane result[4]) {
    const ReblurFrame& v = a.frame;
    const Lane zero(0.0f), one(1.0f);
    const Lane smc = spec ? rb::specMagicCurve(p.r) : one;
    Lane stride = ln::floor(Lane(a.frame.historyFixStride) / (Lane(2.0f) + frames) *
                            rb::lerp(Lane(0.5f), one, smc));
    if (spec) {
        const Lane hitWorld = c[3] * rb::hitDistanceScale(v.hitScale, p.z, p.r);
        const Lane reach = specularLobePixels(v, p, hitWorld, curvature(v, p, x, y));
        young = young & (reach >= Lane(2.0f));
        if (!ln::any(young)) return;
        stride = ln::min(stride, ln::floor(reach * Lane(0.5f)));
    }
    stride = ln::max(one, stride);
    const Lane alpha = one / (one + frames);
    const Lane invPlane = one / (Lane(a.frame.planeDistance * v.frustum) * p.z);
    const Lane normalScale = normalWeightScale(p.r, alpha, a.frame.lobeFraction2, 1.0f);
    // (Per tap below: the roughness weight's divisor, computed once.)
    const Lane roughDivisor = Lane(0.05f) + Lane(0.15f) * p.r;
    const ViewRays rays(v);
    Lane sum[4], weightSum = one + frames;
    for (int ch = 0; ch < 4; ++ch) sum[ch] = c[ch] * weightSum;
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            if ((i == 0 && j == 0) || (std::abs(i) == 2 && std::abs(j) == 2)) continue;
            const Tap t = tapAt(v, p.px + Lane(float(i)) * stride, p.py + Lane(float(j)) * stride);
            const Lane zs = ln::gather(v.signalZ[spec ? 1 : 0], t.index, t.run);  // 0: no signal
            const Mask ok = young & t.inside & (zs > zero);
            if (!ln::any(ok)) continue;
            const V3 xs = rays.at(t.x, t.y, zs);
            const V3 ns{ln::gather(v.normal[0], t.index, t.run),
                        ln::gather(v.normal[1], t.index, t.run),
                        ln::gather(v.normal[2], t.index, t.run)};
            Lane w = geometryWeight(p, xs, invPlane) *
                     rb::weightExp(normalScale * rb::acosApprox(ln::dot(p.n, ns)));
            if (spec) {
                const Lane rs = ln::gather(v.roughness, t.index, t.run);
                w = w * rb::weightExp((rs - p.r) / roughDivisor);
            }
            if (a.frames) w = w * (one + ln::gather(a.frames, t.index, t.run));  // (else * 1)
            w = ln::select(ok, w, zero);
            Lane s[4];
            gatherAt(a.in, t.index, t.run, s);
            for (int ch = 0; ch < 4; ++ch) sum[ch] = sum[ch] + w * s[ch];
            weightSum = weightSum + w;
        }
    for (int ch = 0; ch < 4; ++ch) result[ch] = ln::select(young, sum[ch] / weightSum, c[ch]);
}

// The fast history a frame without history has: the input's luma (of its signal s), as the
// temporal pass would have stored it in its f16 plane.
Lane inputLuma(const Lane s[4]) { return ln::roundedToF16<Lane>(rb::luma(s[0], s[1], s[2])); }

// The anti-lag clamp: the fast history's 5x5 moments bound the slow history's luma (REBLUR's
// "fast history" clamp), more firmly the older the pixel.
void clampToFast(const ReblurPassArgs& a, Mask valid, int x, int y, std::size_t o,
                 const Lane frames, Lane result[4]) {
    const ReblurFrame& v = a.frame;
    const bool spec = a.specular;
    const Lane zero(0.0f), one(1.0f);
    // (signalZ is 0 off surfaces, so it alone says which taps count. Where the whole
    // window lies in the frame for every lane, its rows are plain loads.)
    const bool interior = x >= 2 && x + kW + 2 <= v.width && y >= 2 && y + 2 < v.height;
    const float* mask = v.signalZ[spec ? 1 : 0];
    // (The pixels' centres, as centreAt's.)
    const Lane px = Lane(float(x) + 0.5f) + ln::laneIndex<Lane>(), py(float(y) + 0.5f);
    Lane m1 = zero, m2 = zero, count = zero;
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            Lane ms, f;
            Mask inside;
            if (interior) {
                const std::size_t at =
                    std::size_t(std::ptrdiff_t(o) + j * std::ptrdiff_t(v.stride) + i);
                ms = loadAt(mask, at);
                if (a.fastIsInputLuma) {
                    Lane s[4];
                    loadAt(a.in, at, s);
                    f = inputLuma(s);
                } else {
                    f = loadAt(a.fast, at);
                }
                inside = valid;
            } else {
                const Tap t = tapAt(v, px + Lane(float(i)), py + Lane(float(j)));
                ms = ln::gather(mask, t.index, t.run);
                if (a.fastIsInputLuma) {
                    Lane s[4];
                    gatherAt(a.in, t.index, t.run, s);
                    f = inputLuma(s);
                } else {
                    f = gatherAt(a.fast, t.index, t.run);
                }
                inside = valid & t.inside;
            }
            const Mask ok = inside & (ms > zero);
            f = ln::select(ok, f, zero);
            m1 = m1 + f;
            m2 = m2 + f * f;
            count = count + ln::select(ok, one, zero);
        }
    const Lane n = ln::max(count, one);
    m1 = m1 / n;
    const Lane sigma = ln::sqrt(ln::max(m2 / n - m1 * m1, zero));
    const Lane y0 = rb::luma(result[0], result[1], result[2]);
    const Lane clamped = ln::clamp(y0, m1 - Lane(2.0f) * sigma, m1 + Lane(2.0f) * sigma);
    const Lane y1 = rb::lerp(clamped, y0, one / (one + Lane(2.0f) * frames));
    const Lane scale = (y1 + Lane(rb::kEps)) / (y0 + Lane(rb::kEps));
    for (int ch = 0; ch < 3; ++ch) result[ch] = ln::select(valid, result[ch] * scale, result[ch]);
}

void historyFixChunk(const ReblurPassArgs& a, int x, int y) {
    const ReblurFrame& v = a.frame;
    const std::size_t o = std::size_t(y) * v.stride + x;
    const bool spec = a.specular;
    Lane c[4];
    loadAt(a.in, o, c);
    const Mask valid = validAt(v, o, spec);
    const Lane frames = a.frames ? loadAt(a.frames, o) : Lane(0.0f);
    Lane result[4] = {c[0], c[1], c[2], c[3]};
    const Mask young = valid & (frames < Lane(a.frame.historyFixFrames));
    // (The centre's guides only where a pixel is young: most chunks of a converged frame have
    // none, and the clamp needs only the pixels' positions.)
    if (ln::any(young))
        (spec ? reconstructYoung<true> : reconstructYoung<false>)(a, centreAt(v, x, y, o, spec),
                                                                  young, x, y, frames, c, result);
    if ((a.fast || a.fastIsInputLuma) && ln::any(valid))
        clampToFast(a, valid, x, y, o, frames, result);
    storeAt(a.out, o, result);
}

}  // namespace

void reblurHistoryFixTile(const ReblurPassArgs& a, int tile) {
    const ReblurFrame& v = a.frame;
    if (!(v.tiles[tile] & (a.specular ? kTileSpecular : kTileDiffuse))) {
        return copyTile(v, a.in, a.out, SignalOut4(), tile);
    }
    const auto [x0, y0, x1, y1] = tileRect(tile, v.tilesX, v.width, v.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) historyFixChunk(a, x, y);
}

}  // namespace ssrt::SSRT_ISA_NS
