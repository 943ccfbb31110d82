#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>
#include <limits>

#include "core/lane_vec.h"
#include "core/screen_lanes.h"
#include "core/tiles.h"
#include "trace/reconstruct_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;
using Mask = ln::MaskOf<Lane>;
using ILane = ln::IntOf<Lane>;

namespace {

constexpr int kValues = 6;              // colour, opacity, hit, distance
constexpr float kMinWeight = 1.0e-20f;  // smaller sums of weights count as none (blend())

// The pixel being filled.
struct Target {
    V3 p, n, nView;
    Lane invTolerance;
};

// A lane group's candidate: where its values and its guide are read, its w_space, whether
// it is a traced sample.
struct Candidate {
    ILane src, guide;
    Lane px, py, space;
    Mask ok;
    // How its pixels are read: a gather at src and guide (anywhere); or, away from the frame's
    // edges, side by side at `off` (checkerboard: values and guide alike, one load); or from
    // runs at `off` (the half frame's values) and `guideOff` (the frame's guides), each lane's
    // element picked by `pick` and `guidePick` (the half lattice: pairs of lanes share a half
    // pixel, and its guide pixels are every other one of a row).
    enum class Read { Gather, Contiguous, Runs } read = Read::Gather;
    std::size_t off = 0, guideOff = 0;
    ILane pick, guidePick;
};

// A plane's value at a candidate's values (src).
SSRT_INLINE Lane readSrc(const float* plane, const Candidate& c) {
    switch (c.read) {
        case Candidate::Read::Contiguous: return ln::load<Lane>(plane + c.off);
        case Candidate::Read::Runs: return ln::pickFromOne(plane + c.off, c.pick);
        default: return ln::gather(plane, c.src);
    }
}

// A plane's value at a candidate's guide pixel.
SSRT_INLINE Lane readGuide(const float* plane, const Candidate& c) {
    switch (c.read) {
        case Candidate::Read::Contiguous: return ln::load<Lane>(plane + c.off);
        case Candidate::Read::Runs: return ln::pickFromTwo(plane + c.guideOff, c.guidePick);
        default: return ln::gather(plane, c.guide);
    }
}

struct Sums {
    Lane w, wo, wh, whd, c[3];
};

// The values of a candidate (absent planes: opacity 1, the others 0).
SSRT_INLINE void readValues(const ReconstructArgs& a, const Candidate& c, Lane (&v)[kValues]) {
    const Lane zero(0.0f);
    for (int k = 0; k < 3; ++k) v[k] = a.in[kRecR] ? readSrc(a.in[kRecR + k], c) : zero;
    v[3] = a.in[kRecOpacity] ? readSrc(a.in[kRecOpacity], c) : Lane(1.0f);
    v[4] = a.in[kRecHit] ? readSrc(a.in[kRecHit], c) : zero;
    v[5] = a.in[kRecDistance] ? readSrc(a.in[kRecDistance], c) : zero;
}

// w_plane w_normal (trace/reconstruct.h) and the relative plane distance.
SSRT_INLINE Lane geometryWeight(const ReconstructArgs& a, const Target& t, const Candidate& c,
                                Lane& dist) {
    const Lane zero(0.0f), one(1.0f);
    const Lane z = readGuide(a.g.viewZ, c);
    // The view ray through the sample's pixel centre times its depth (trace/trace_types.h)
    const V3 s{(c.px * Lane(a.scaleX) - Lane(a.tanHalfX)) * z,
               (Lane(a.tanHalfY) - c.py * Lane(a.scaleY)) * z, zero - z};
    const V3 n{readGuide(a.g.normal[0], c), readGuide(a.g.normal[1], c),
               readGuide(a.g.normal[2], c)};
    dist = ln::abs(ln::dot(t.nView, s - t.p)) * t.invTolerance;
    const Lane wPlane = ln::max(one - dist, zero);  // (NaN -> 0: max keeps the second)
    Lane cosN = ln::max(ln::dot(t.n, n), zero);
    cosN = cosN * cosN, cosN = cosN * cosN, cosN = cosN * cosN;  // ^8
    // (A sample on the background is no sample: its distance is infinite, never nearest.)
    dist = ln::select(z > zero, dist, Lane(std::numeric_limits<float>::infinity()));
    return ln::select(c.ok & (z > zero), wPlane * cosN, zero);
}

// The blend of the candidates, with the nearest traced one where no weight is left.
SSRT_INLINE void blend(const ReconstructArgs& a, const Target& t, const Candidate* cand, int count,
                       Lane (&out)[kValues]) {
    const Lane zero(0.0f), one(1.0f);
    Sums s{zero, zero, zero, zero, {zero, zero, zero}};
    Lane best[kValues] = {zero, zero, zero, zero, zero, zero};
    Lane bestSpace(-1.0f), bestDist(0.0f);
    for (int i = 0; i < count; ++i) {
        const Candidate& c = cand[i];
        if (!ln::any(c.ok)) continue;
        Lane dist;
        const Lane w = c.space * geometryWeight(a, t, c, dist);
        Lane v[kValues];
        readValues(a, c, v);
        // (Lanes without this candidate add nothing, whatever their reads held: 0 x NaN.)
        for (int k = 0; k < kValues; ++k) v[k] = ln::select(c.ok, v[k], zero);
        const Lane wo = w * v[3], wh = w * v[4];
        s.w = s.w + w;
        s.wo = s.wo + wo;
        for (int k = 0; k < 3; ++k) s.c[k] = s.c[k] + wo * v[k];
        s.wh = s.wh + wh;
        s.whd = s.whd + wh * v[5];
        // The nearest: larger w_space, then smaller distance (a NaN or infinite one, the
        // background's, never wins).
        const Mask nearer = c.ok & (dist < Lane(std::numeric_limits<float>::infinity())) &
                            ((c.space > bestSpace) | ((c.space == bestSpace) & (dist < bestDist)));
        for (int k = 0; k < kValues; ++k) best[k] = ln::select(nearer, v[k], best[k]);
        bestSpace = ln::select(nearer, c.space, bestSpace);
        bestDist = ln::select(nearer, dist, bestDist);
    }
    // Ratio estimates; the nearest sample alone where every weight vanished; zeros (opacity
    // 0) without a traced candidate. A weight under kMinWeight counts as vanished: w_normal is
    // a cosine to the 8th power, which reaches the denormals, and 1 / w then overflows
    // (2CylinderEngine, whose creases gave NaN and infinite SSGI pixels, issue 27).
    const Lane minWeight(kMinWeight);
    const Mask any = s.w > minWeight, none = (!any) & (bestSpace >= zero);
    const Mask anyO = any & (s.wo > minWeight), anyH = any & (s.wh > minWeight);
    const Lane invW = one / ln::select(any, s.w, one);
    const Lane invO = one / ln::select(anyO, s.wo, one);
    const Lane invH = one / ln::select(anyH, s.wh, one);
    for (int k = 0; k < 3; ++k) out[k] = ln::select(anyO, s.c[k] * invO, zero);
    out[3] = ln::select(any, s.wo * invW, zero);
    out[4] = ln::select(any, s.wh * invW, zero);
    out[5] = ln::select(anyH, s.whd * invH, zero);
    for (int k = 0; k < 3; ++k)
        out[k] = ln::select(none, ln::select(best[3] > zero, best[k], zero), out[k]);
    out[3] = ln::select(none, best[3], out[3]);
    out[4] = ln::select(none, best[4], out[4]);
    out[5] = ln::select(none, ln::select(best[4] > zero, best[5], zero), out[5]);
}

SSRT_INLINE Target target(const ReconstructArgs& a, std::size_t o, Lane px, Lane py, Lane z) {
    const float* r = a.viewToWorld;
    Target t;
    t.p = {(px * Lane(a.scaleX) - Lane(a.tanHalfX)) * z,
           (Lane(a.tanHalfY) - py * Lane(a.scaleY)) * z, Lane(0.0f) - z};
    t.n = {ln::load<Lane>(a.g.normal[0] + o), ln::load<Lane>(a.g.normal[1] + o),
           ln::load<Lane>(a.g.normal[2] + o)};
    // World normal to view space: the transpose of viewToWorld
    t.nView = {(Lane(r[0]) * t.n.x + Lane(r[1]) * t.n.y) + Lane(r[2]) * t.n.z,
               (Lane(r[3]) * t.n.x + Lane(r[4]) * t.n.y) + Lane(r[5]) * t.n.z,
               (Lane(r[6]) * t.n.x + Lane(r[7]) * t.n.y) + Lane(r[8]) * t.n.z};
    t.invTolerance = Lane(a.invTolerance) / ln::select(z > Lane(0.0f), z, Lane(1.0f));
    return t;
}

// Checkerboard: the marked lanes of one group from their eight neighbours, written lane by
// lane (the traced pixels beside them, which other tiles read, are never stored to). A plain
// checkerboard traces only edge neighbours (a cut pixel's diagonal ones share its phase); the
// thinned one's cut pixels of the traced phase have only diagonal ones (trace/trace_layout.h,
// sparseBlockPick). No pixel has both, so every neighbour weighs the same (w_space 1).
void checkerChunk(const ReconstructArgs& a, int x, int y, int x1, uint64_t& filled) {
    const std::size_t o = std::size_t(y) * a.stride + std::size_t(x);
    const Lane zero(0.0f);
    const Lane xi = Lane(float(x)) + ln::laneIndex<Lane>();
    const Mask cut = (ln::load<Lane>(a.pdf + o) == Lane(a.cutMark)) & (xi < Lane(float(x1)));
    if (!ln::any(cut)) return;
    const Lane px = xi + Lane(0.5f), py(float(y) + 0.5f);
    const Lane z = ln::load<Lane>(a.g.viewZ + o);
    const Target t = target(a, o, px, py, z);
    constexpr int kNeighbours = 8;
    Candidate cand[kNeighbours];
    const float dx[kNeighbours] = {-1, 1, 0, 0, -1, 1, -1, 1};
    const float dy[kNeighbours] = {0, 0, -1, 1, -1, -1, 1, 1};
    for (int i = 0; i < kNeighbours; ++i) {
        const Lane nx = xi + Lane(dx[i]), ny(float(y) + dy[i]);
        const int yy = y + int(dy[i]);
        Candidate& c = cand[i];
        c.px = nx + Lane(0.5f), c.py = ny + Lane(0.5f), c.space = Lane(1.0f);
        if (yy >= 0 && yy < a.height && x + int(dx[i]) >= 0 && x + int(dx[i]) + kW <= a.width) {
            // Every lane's neighbour is in the frame, side by side in memory. (Lanes whose
            // neighbour is not traced read a pixel that may be filled meanwhile, by this
            // thread or, in the other tile colour, never at once: their values are dropped.)
            c.read = Candidate::Read::Contiguous;
            c.off = std::size_t(yy) * a.stride + std::size_t(x + int(dx[i]));
            c.ok = (ln::load<Lane>(a.pdf + c.off) > zero) & cut;
            continue;
        }
        const Mask inFrame = (nx >= zero) & (nx < Lane(float(a.width))) & (ny >= zero) &
                             (ny < Lane(float(a.height)));
        const ILane at = screen::pixelIndex(nx, ny, a.width, a.height, a.stride);
        c.ok = inFrame & (ln::gather(a.pdf, at) > zero) & cut;
        // Lanes without a traced neighbour read their own pixel instead.
        c.src = c.guide =
            screen::pixelIndex(ln::select(c.ok, nx, xi), ln::select(c.ok, ny, Lane(float(y))),
                               a.width, a.height, a.stride);
    }
    Lane v[kValues];
    blend(a, t, cand, kNeighbours, v);
    alignas(64) float buf[kValues][kW];
    alignas(64) float mask[kW];
    for (int k = 0; k < kValues; ++k) ln::store(buf[k], v[k]);
    ln::store(mask, ln::select(cut, Lane(1.0f), zero));
    for (int l = 0; l < kW; ++l) {
        if (mask[l] == 0.0f) continue;
        const std::size_t at = o + std::size_t(l);
        for (int k = 0; k < kValues; ++k)
            if (a.out[k]) a.out[k][at] = buf[k][l];
        ++filled;
    }
}

// Half: every lane of one group: its chosen pixel's values as they are, the others blended
// from the four nearest half pixels, background zeros.
void halfChunk(const ReconstructArgs& a, int x, int y, uint64_t& filled) {
    const std::size_t o = std::size_t(y) * a.stride + std::size_t(x);
    const Lane zero(0.0f), one(1.0f), halfL(0.5f);
    const Lane xi = Lane(float(x)) + ln::laneIndex<Lane>();
    const Lane z = ln::load<Lane>(a.g.viewZ + o);
    const Mask surface = (z > zero) & (xi < Lane(float(a.width)));
    Lane v[kValues] = {zero, zero, zero, zero, zero, zero};
    Lane steps = zero;
    if (ln::any(surface)) {
        // The lattice of chosen pixels 2 h + offset around (x, y): bilinear weights 1 - t, t
        // with t in {0, 1/2}.
        const Lane ex = xi - Lane(float(a.offsetX));
        const Lane hx0 = ln::floor(ex * halfL);
        const Lane tx = (ex - Lane(2.0f) * hx0) * halfL;
        const int ey = y - a.offsetY;
        const int hy0 = ey >= 0 ? ey / 2 : -1;
        const float ty = float(ey - 2 * hy0) * 0.5f;
        // Lane l's half pixel is hb + pick[l] (+ i): pairs of lanes share one, and its guide
        // pixel is every other one of the frame's row, so away from the edges each candidate's
        // reads are runs of a row (Candidate::Read::Runs) in place of gathers.
        const int ex0 = x - a.offsetX, hb = ex0 >> 1, parity = ex0 & 1;
        const int lastPick = (parity + kW - 1) >> 1;
        alignas(64) int32_t pick[kW], guidePick[kW];
        for (int l = 0; l < kW; ++l) pick[l] = (parity + l) >> 1, guidePick[l] = 2 * pick[l];
        Candidate cand[4];
        Mask own = zero > zero;
        Lane ownX = zero, ownY = zero;
        int count = 0, ownFrom = -1;  // (the candidate holding the own lanes; -2: several)
        for (int j = 0; j < 2; ++j) {
            const int hy = hy0 + j;
            const float wy = j ? ty : 1.0f - ty;
            if (hy < 0 || hy >= a.srcHeight || !(wy > 0.0f)) continue;
            const int sy = std::min(2 * hy + a.offsetY, a.height - 1);
            for (int i = 0; i < 2; ++i) {
                const Lane hx = hx0 + Lane(float(i));
                const Lane space = (i ? tx : one - tx) * Lane(wy);
                const Mask in = (hx >= zero) & (hx < Lane(float(a.srcWidth))) & (space > zero);
                const Lane sx =
                    ln::min(Lane(2.0f) * hx + Lane(float(a.offsetX)), Lane(float(a.width - 1)));
                Candidate& c = cand[count++];
                c.src =
                    screen::pixelIndex(hx, Lane(float(hy)), a.srcWidth, a.srcHeight, a.srcStride);
                c.guide = screen::pixelIndex(sx, Lane(float(sy)), a.width, a.height, a.stride);
                // Runs where no lane's pixel is clamped into the frame (then every lane reads
                // what the gather would) and both runs lie inside their rows.
                const int hs = hb + i, gs = 2 * hs + a.offsetX;
                if (ln::kPicksInRegisters<Lane> && hs >= 0 && hs + lastPick < a.srcWidth &&
                    std::size_t(hs + kW) <= a.srcStride && gs + 2 * lastPick < a.width &&
                    std::size_t(gs + 2 * kW) <= a.stride) {
                    c.read = Candidate::Read::Runs;
                    c.off = std::size_t(hy) * a.srcStride + std::size_t(hs);
                    c.guideOff = std::size_t(sy) * a.stride + std::size_t(gs);
                    c.pick = ln::loadInt<Lane>(pick);
                    c.guidePick = ln::loadInt<Lane>(guidePick);
                }
                const Mask isOwn = in & (sx == xi) & (Lane(sy == y ? 1.0f : 0.0f) > zero);
                if (ln::any(isOwn)) ownFrom = ownFrom == -1 ? count - 1 : -2;
                own = own | isOwn;
                ownX = ln::select(isOwn, hx, ownX);
                ownY = ln::select(isOwn, Lane(float(hy)), ownY);
                c.px = sx + halfL, c.py = Lane(float(sy) + 0.5f), c.space = space;
                c.ok = in & !isOwn & (readSrc(a.pdf, c) > zero) & surface;
            }
        }
        const Target t = target(a, o, xi + halfL, Lane(float(y) + 0.5f), z);
        blend(a, t, cand, count, v);
        if (ln::any(own)) {
            // The own lanes' half pixels are their candidate's (src): read as it reads them.
            Candidate mineAt{};
            if (ownFrom >= 0) mineAt = cand[ownFrom];
            else mineAt.src = screen::pixelIndex(ownX, ownY, a.srcWidth, a.srcHeight, a.srcStride);
            Lane mine[kValues];
            readValues(a, mineAt, mine);
            for (int k = 0; k < kValues; ++k) v[k] = ln::select(own, mine[k], v[k]);
            if (a.in[kRecSteps]) steps = ln::select(own, readSrc(a.in[kRecSteps], mineAt), zero);
        }
        for (int k = 0; k < kValues; ++k) v[k] = ln::select(surface, v[k], zero);
        filled += uint64_t(__builtin_popcountll(ln::maskBits(surface & !own)));
    }
    const std::size_t oo = std::size_t(y - a.outY0) * a.outStride + std::size_t(x - a.outX0);
    for (int k = 0; k < kValues; ++k)
        if (a.out[k]) ln::store(a.out[k] + oo, v[k]);
    if (a.out[kRecSteps]) ln::store(a.out[kRecSteps] + oo, steps);
}

}  // namespace

void reconstructTile(const ReconstructArgs& args, int tile, uint64_t& filled) {
    const auto [x0, y0, x1, y1] = tileRect(tile, args.tilesX, args.width, args.height);
    // (Lane groups past the right edge read and, for the half upsample, write the rows'
    // padding; the checkerboard writes only marked lanes inside the tile.)
    uint64_t n = 0;  // (a local: a store per pixel through the reference otherwise)
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; x += kW) {
            if (args.half) halfChunk(args, x, y, n);
            else checkerChunk(args, x, y, x1, n);
        }
    filled = n;
}

}  // namespace ssrt::SSRT_ISA_NS
