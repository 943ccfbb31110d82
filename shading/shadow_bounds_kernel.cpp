#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <cmath>
#include <cstddef>

#include "core/lanes.h"
#include "shading/shadow_bounds.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;

namespace {

// (not std::min: a template's copy could be shared with other ISAs' objects)
inline int lesser(int a, int b) { return b < a ? b : a; }
inline int greater(int a, int b) { return a < b ? b : a; }
inline float lesser(float a, float b) { return b < a ? b : a; }
inline float greater(float a, float b) { return a < b ? b : a; }

constexpr int kHalf = kShadowBlock / 2;

// The texels [first, last] whose taps may be read from block `b`: widened by r, clipped.
struct Span {
    int first, last;
};
Span widened(int b, int r, int size) {
    return {greater(b * kShadowBlock - r, 0), lesser((b + 1) * kShadowBlock - 1 + r, size - 1)};
}

// The depth's slope across block b's own texels along one line of the map (`at(i)`, the depth
// of texel i on it): any slope gives true bounds, this one makes a plane's tight.
template <class At>
float slope(int b, int size, At at) {
    const int first = lesser(b * kShadowBlock, size - 1);
    const int last = lesser(b * kShadowBlock + kShadowBlock - 1, size - 1);
    if (last == first) return 0.0f;
    const float s = (at(last) - at(first)) / float(last - first);
    return std::isfinite(s) ? s : 0.0f;
}

// The off-plane depths of columns [first, last] over a block row's widened rows, each relative to
// its own block's plane, before the margin; NaN where one is NaN or infinite.
struct Columns {
    float lo, hi;
};
Columns columns(const float* lo, const float* hi, const float* poison, int first, int last) {
    Columns c{INFINITY, -INFINITY};
    float p = 0.0f;
    for (int x = first; x <= last; ++x)
        c.lo = lesser(c.lo, lo[x]), c.hi = greater(c.hi, hi[x]), p += poison[x];
    if (!(p == 0.0f)) c = {NAN, NAN};
    return c;
}

}  // namespace

// Two rows' depths off their blocks' planes at kWidth<L> columns, into the columns' lowest,
// highest and poison (NaN from here on where either is NaN or infinite).
template <class L>
SSRT_INLINE void offPlaneStep(const float* row0, const float* row1, const float* alongU,
                              const float* slopeV, float dy0, float dy1, float* lo, float* hi,
                              float* poison) {
    const L u = ln::load<L>(alongU), v = ln::load<L>(slopeV);
    const L off0 = (ln::load<L>(row0) - u) - v * L(dy0);
    const L off1 = (ln::load<L>(row1) - u) - v * L(dy1);
    ln::store(lo, ln::min(ln::min(off0, off1), ln::load<L>(lo)));
    ln::store(hi, ln::max(ln::max(off0, off1), ln::load<L>(hi)));
    ln::store(poison, ln::load<L>(poison) + (off0 + off1) * L(0.0f));
}

// Block row `by`: first each block's own columns, down every widened row (a pass over whole
// rows, per column, that the compiler vectorizes); then each block widened by its neighbours'
// columns, bounded through the neighbour's own plane (below).
void boundShadowBlockRow(const float* map, std::size_t stride, int size, int radius, int by,
                         float* work, ShadowBlockBounds* out) {
    const int n = (size + kShadowBlock - 1) / kShadowBlock;
    const int cy = by * kShadowBlock + kHalf;
    float* du = work + 5 * std::size_t(size);
    float* dv = du + n;
    for (int bx = 0; bx < n; ++bx) {
        const int cx = lesser(bx * kShadowBlock + kHalf, size - 1);
        const float* mid = map + std::size_t(lesser(cy, size - 1)) * stride;
        du[bx] = slope(bx, size, [&](int x) { return mid[x]; });
        dv[bx] = slope(by, size, [&](int y) { return map[std::size_t(y) * stride + cx]; });
    }
    // Per column x: its block's plane along u at x, and its block's slope in v; then, down the
    // widened rows, the column's lowest and highest depth off its block's plane (`poison`: NaN
    // where one of them is NaN or infinite, for `columns`), two rows a step.
    float* alongU = work;
    float* slopeV = alongU + size;
    float* lo = slopeV + size;
    float* hi = lo + size;
    float* poison = hi + size;
    for (int x = 0; x < size; ++x) {
        lo[x] = INFINITY, hi[x] = -INFINITY, poison[x] = 0.0f;
    }
    for (int bx = 0; bx < n; ++bx)
        for (int i = 0; i < kShadowBlock && bx * kShadowBlock + i < size; ++i) {
            alongU[bx * kShadowBlock + i] = du[bx] * float(i - kHalf);
            slopeV[bx * kShadowBlock + i] = dv[bx];
        }
    const Span rows = widened(by, radius, size);
    for (int y = rows.first; y <= rows.last; y += 2) {
        // (an odd last row reads itself twice)
        const int y1 = lesser(y + 1, rows.last);
        const float* row0 = map + std::size_t(y) * stride;
        const float* row1 = map + std::size_t(y1) * stride;
        const float dy0 = float(y - cy), dy1 = float(y1 - cy);
        int x = 0;
        for (; x + kW <= size; x += kW)
            offPlaneStep<Lane>(row0 + x, row1 + x, alongU + x, slopeV + x, dy0, dy1, lo + x, hi + x,
                               poison + x);
        for (; x < size; ++x)
            offPlaneStep<float>(row0 + x, row1 + x, alongU + x, slopeV + x, dy0, dy1, lo + x,
                                hi + x, poison + x);
    }
    // A neighbour N's columns, depth = off_N + du_N X_N + dv_N Y with X_N = X + (cx - cx_N),
    // lie off this block's plane by off_N + du_N (cx - cx_N) + (du_N - du) X + (dv_N - dv) Y,
    // |X|, |Y| <= kHalf + r over the widened block: a plane's neighbours add nothing.
    const float reach = float(kHalf + radius);
    for (int bx = 0; bx < n; ++bx) {
        const Span own = widened(bx, 0, size), wide = widened(bx, radius, size);
        Columns c = columns(lo, hi, poison, own.first, own.last);
        float slopes = std::fabs(du[bx]) + std::fabs(dv[bx]);
        for (const Span halo : {Span{wide.first, own.first - 1}, Span{own.last + 1, wide.last}}) {
            if (halo.first > halo.last) continue;
            const int nx = halo.first / kShadowBlock;
            const Columns h = columns(lo, hi, poison, halo.first, halo.last);
            const float shift = du[nx] * float((bx - nx) * kShadowBlock);  // exact: times 8
            const float tilt =
                std::fabs(du[nx] - du[bx]) * reach + std::fabs(dv[nx] - dv[bx]) * reach;
            const float nl = (h.lo + shift) - tilt, nh = (h.hi + shift) + tilt;
            c.lo = (nl < c.lo || nl != nl) ? nl : c.lo;
            c.hi = (nh > c.hi || nh != nh) ? nh : c.hi;
            slopes += std::fabs(du[nx]) + std::fabs(dv[nx]);
        }
        // Rounding: each value above is within 16 u (u = 2^-24) of its exact value, relative
        // to the largest magnitude it is made of, under |lo| + |hi| + (3 kHalf + r) slopes
        // (a depth is within (kHalf + r) slopes of its off-plane value, a shift 2 kHalf
        // slopes); the margin, 64 u of that, keeps lo and hi true after their own rounding.
        const float margin =
            0x1p-18f * ((std::fabs(c.lo) + std::fabs(c.hi)) + float(3 * kHalf + radius) * slopes);
        out[bx] = {c.lo - margin, c.hi + margin, du[bx], dv[bx]};
    }
}

}  // namespace ssrt::SSRT_ISA_NS
