#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>
#include <limits>

#include "core/lane_vec.h"
#include "core/rng_lanes.h"
#include "core/screen_lanes.h"
#include "core/tiles.h"
#include "shading/brdf.h"
#include "shading/sampling.h"
#include "trace/ray_gen_kernel.h"
#include "trace/trace_layout.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
namespace sm = ssrt::sampling;
using V3 = ln::V3<Lane>;
using Mask = ln::MaskOf<Lane>;

namespace {

// The planes a tile writes through its row buffers: origin XYZ, direction XYZ, PDF.
constexpr int kRayGenOutputs = 7;
enum Out { kOriginX = 0, kDirX = 3, kPdf = 6 };

SSRT_INLINE V3 neg(V3 v) { return {Lane(0.0f) - v.x, Lane(0.0f) - v.y, Lane(0.0f) - v.z}; }

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited", listing 3: t, b, n right
// handed for a unit n, branch-free (the sign is a select), no NaN for any finite n.
SSRT_INLINE void orthonormalBasis(V3 n, V3& t, V3& b) {
    const Lane s = ln::select(n.z >= Lane(0.0f), Lane(1.0f), Lane(-1.0f));
    const Lane a = Lane(-1.0f) / (s + n.z);
    const Lane c = n.x * n.y * a;
    t = {Lane(1.0f) + s * n.x * n.x * a, s * c, Lane(0.0f) - s * n.x};
    b = {c, s + n.y * n.y * a, Lane(0.0f) - n.y};
}

// Local frame (t, b, n) to view space.
SSRT_INLINE V3 toView(V3 t, V3 b, V3 n, V3 w) { return (t * w.x + b * w.y) + n * w.z; }

// The lane group's two uniform numbers, lane by lane from the counter hash (integer work:
// the same bits on every ISA).
SSRT_INLINE void uniforms(const RayGenArgs& a, int x, int y, Lane& u1, Lane& u2) {
    const uint32_t base = uint32_t(y) * uint32_t(a.width) + uint32_t(x);
    u1 = ln::randomFloats<Lane>(base, a.frame, a.sample, a.dim);
    u2 = ln::randomFloats<Lane>(base, a.frame, a.sample, a.dim + 1u);
}

SSRT_INLINE unsigned popcount(Mask m, uint64_t valid) {
    return unsigned(__builtin_popcountll(ln::maskBits(m) & valid));
}

// The lobe's direction (view space, unit) and PDF for the surface pixels of one lane
// group; `ok` is false where the sample is rejected (see trace/ray_gen.h for what each
// method prescribes).
template <RayGenLobe K>
SSRT_INLINE void drawLobe(const RayGenArgs& a, std::size_t go, V3 n, V3 v, Lane u1, Lane u2,
                          V3& dir, Lane& pdf, Mask& ok) {
    const Lane zero(0.0f);
    const Lane NoV = ln::dot(n, v);
    if constexpr (K == RayGenLobe::Mirror) {
        // Reflect the view about the shading normal: r = 2 (n.v) n - v, n.r = n.v
        dir = ln::normalize(n * (NoV + NoV) - v);
        pdf = Lane(1.0f);
        ok = (NoV > zero) & (ln::dot(n, dir) > zero);
        return;
    }
    V3 t, b;
    orthonormalBasis(n, t, b);
    V3 wo;
    if constexpr (K == RayGenLobe::Diffuse) {
        // Cosine hemisphere around the shading normal (the view plays no part)
        wo = sm::sampleCosineHemisphere(u1, u2);
        pdf = sm::cosineHemispherePdf(wo);
        ok = wo.z > zero;
    } else {
        // The view in the local frame; alpha kept >= 1e-3 (brdf::roughnessToAlpha)
        const V3 wi{ln::dot(v, t), ln::dot(v, b), NoV};
        const Lane alpha = brdf::roughnessToAlpha(ln::load<Lane>(a.g.roughness + go));
        V3 wm;
        if constexpr (K == RayGenLobe::GgxNdf) wm = sm::sampleGgxNdf(alpha, alpha, u1, u2);
        else if constexpr (K == RayGenLobe::VndfEllipsoid)
            wm = sm::sampleVndfEllipsoid(wi, alpha, alpha, u1, u2);
        else if constexpr (K == RayGenLobe::VndfSphericalCaps)
            wm = sm::sampleVndfSphericalCaps(wi, alpha, alpha, u1, u2);
        else wm = sm::sampleVndfBounded(wi, alpha, alpha, u1, u2);
        // Reflect about the microfacet normal; its PDF over the reflected direction
        wo = sm::reflect(wi, wm);
        if constexpr (K == RayGenLobe::GgxNdf) pdf = sm::ggxNdfReflectionPdf(wi, wo, alpha, alpha);
        else if constexpr (K == RayGenLobe::VndfBounded)
            pdf = sm::vndfBoundedReflectionPdf(wi, wo, alpha, alpha);
        else pdf = sm::vndfReflectionPdf(wi, wo, alpha, alpha);
        // Rejections: a view below the shading normal's horizon, a reflection below it,
        // and (NDF sampling only) a microfacet facing away from the viewer
        ok = (NoV > zero) & (wo.z > zero);
        if constexpr (K == RayGenLobe::GgxNdf) ok = ok & (ln::dot(wi, wm) > zero);
    }
    // To view space; the horizon test again on what is written, and a finite positive PDF
    dir = ln::normalize(toView(t, b, n, wo));
    ok = ok & (ln::dot(n, dir) > zero) & (pdf > zero) &
         (pdf <= Lane(std::numeric_limits<float>::max()));
}

// Whether the last frame's history at the lanes' previous positions (through the motion
// vectors, the pixel containing the point) has at least sparseMin frames; off the frame (or a
// NaN motion), none.
SSRT_INLINE Mask longHistory(const RayGenArgs& a, Lane xi, int y, std::size_t go) {
    const Lane zero(0.0f);
    const Lane px = xi + Lane(0.5f) + ln::load<Lane>(a.g.motion[0] + go);
    const Lane py = Lane(float(y) + 0.5f) + ln::load<Lane>(a.g.motion[1] + go);
    const Mask inside =
        (px >= zero) & (px < Lane(float(a.width))) & (py >= zero) & (py < Lane(float(a.height)));
    const auto at = screen::nearestIndex(ln::select(inside, px, zero), ln::select(inside, py, zero),
                                         a.width, a.height, a.historyStride);
    return inside & (ln::gather(a.historyFrames, at) >= Lane(a.sparseMin));
}

// One lane group of row y starting at pixel x, into out[plane] + o (a row buffer of the
// tile); `valid` has a bit per lane inside the frame.
template <RayGenLobe K>
SSRT_INLINE void rayChunk(const RayGenArgs& a, int x, int y, uint64_t valid, float* const* out,
                          int o, RayGenCounts& c) {
    const std::size_t go = std::size_t(y) * a.g.stride + std::size_t(x);
    const int oo = o;
    const Lane zero(0.0f);
    const Lane viewZ = ln::load<Lane>(a.g.viewZ + go);
    const Mask surface = viewZ > zero;  // (false for NaN)
    const unsigned surfaceCount = popcount(surface, valid);
    const unsigned validCount = unsigned(__builtin_popcountll(valid));
    c.pixels += surfaceCount;
    c.background += validCount - surfaceCount;
    if (!ln::any(surface)) {
        for (int p = 0; p < kRayGenOutputs; ++p) ln::store(out[p] + oo, zero);
        return;
    }
    // Origin: the view ray through the pixel's point (its centre, or a half frame's chosen
    // pixel's: RayGenArgs::originX) times viewZ (trace/trace_types.h)
    const Lane xi = Lane(float(x)) + ln::laneIndex<Lane>();
    const Lane ndcX = (xi + Lane(a.originX)) * Lane(2.0f / float(a.width)) - Lane(1.0f);
    const Lane ndcY = Lane(1.0f) - Lane((float(y) + a.originY) * (2.0f / float(a.height)));
    const V3 ray{ndcX * Lane(a.tanHalfX), ndcY * Lane(a.tanHalfY), Lane(-1.0f)};
    const V3 origin{ray.x * viewZ, ray.y * viewZ, Lane(0.0f) - viewZ};
    // The view direction (towards the camera) and the normal rotated into view space
    // (the transpose of viewToWorld: its columns dotted with the world normal)
    const V3 v = ln::normalize(neg(ray));
    const V3 nw{ln::load<Lane>(a.g.normal[0] + go), ln::load<Lane>(a.g.normal[1] + go),
                ln::load<Lane>(a.g.normal[2] + go)};
    const float* r = a.viewToWorld;
    const V3 n = ln::normalize(V3{(Lane(r[0]) * nw.x + Lane(r[1]) * nw.y) + Lane(r[2]) * nw.z,
                                  (Lane(r[3]) * nw.x + Lane(r[4]) * nw.y) + Lane(r[5]) * nw.z,
                                  (Lane(r[6]) * nw.x + Lane(r[7]) * nw.y) + Lane(r[8]) * nw.z});
    // Rays whose result the composite would not show are not drawn: specular ones where
    // the resolve's roughness fade hides SSR, diffuse ones where the diffuse colour that
    // multiplies SSGI (as shading/composite_kernel.cpp computes it) is 0.
    Mask wanted = surface;
    if constexpr (K != RayGenLobe::Diffuse) {
        if (a.maxRoughness < std::numeric_limits<float>::infinity())
            wanted = surface & (ln::load<Lane>(a.g.roughness + go) < Lane(a.maxRoughness));
    } else if (a.noDiffuseColour) {
        // (!(x == 0), not x != 0: a NaN colour is kept on every ISA, where vector != is
        // ordered and scalar != is not.)
        const Lane keep = Lane(1.0f) - ln::load<Lane>(a.g.metallic + go);
        wanted = surface & !((ln::load<Lane>(a.g.albedo[0] + go) * keep == zero) &
                             (ln::load<Lane>(a.g.albedo[1] + go) * keep == zero) &
                             (ln::load<Lane>(a.g.albedo[2] + go) * keep == zero));
    }
    c.hidden += surfaceCount - popcount(wanted, valid);
    // The checkerboard's other phase: no ray, marked for the reconstruction. Pixel x is
    // traced when (x & 1) == ((y ^ frame ^ phase) & 1) (x's parity as an exact float).
    Mask cut = zero > zero;
    if (a.checkerboard) {
        const Lane parity = xi - Lane(2.0f) * ln::floor(xi * Lane(0.5f));
        const uint32_t want = (uint32_t(y) ^ a.frame ^ a.checkerPhase) & 1u;
        cut = wanted & !(parity == Lane(float(want)));
        wanted = wanted & !cut;
        c.cut += popcount(cut, valid);
        if (a.historyFrames && ln::any(wanted)) {
            // Of the block's two traced pixels, the one in column sparseBlockPick's parity
            // keeps its ray; the other only where its history is short.
            const Mask picked = parity == Lane(float(sparseBlockPick(a.frame)));
            const Mask sparse = wanted & !picked & longHistory(a, xi, y, go);
            wanted = wanted & !sparse;
            cut = cut | sparse;
            c.sparse += popcount(sparse, valid);
            c.cut += popcount(sparse, valid);
        }
    }
    V3 dir{zero, zero, zero};
    Lane pdf = zero;
    Mask ok = wanted;
    if (ln::any(wanted)) {
        Lane u1(0.0f), u2(0.0f);
        if constexpr (K != RayGenLobe::Mirror) uniforms(a, x, y, u1, u2);
        drawLobe<K>(a, go, n, v, u1, u2, dir, pdf, ok);
        ok = ok & wanted;
    }
    const unsigned rays = popcount(ok, valid);
    c.rays += rays;
    c.belowSurface += popcount(wanted, valid) - rays;
    ln::store(out[kOriginX] + oo, ln::select(surface, origin.x, zero));
    ln::store(out[kOriginX + 1] + oo, ln::select(surface, origin.y, zero));
    ln::store(out[kOriginX + 2] + oo, ln::select(surface, origin.z, zero));
    ln::store(out[kDirX] + oo, ln::select(ok, dir.x, zero));
    ln::store(out[kDirX + 1] + oo, ln::select(ok, dir.y, zero));
    ln::store(out[kDirX + 2] + oo, ln::select(ok, dir.z, zero));
    ln::store(out[kPdf] + oo, ln::select(ok, pdf, ln::select(cut, Lane(a.cutPdf), zero)));
}

template <RayGenLobe K>
void rayTile(const RayGenArgs& a, int tile, RayGenCounts& c) {
    const auto [x0, y0, x1, y1] = tileRect(tile, a.tilesX, a.width, a.height);
    // Lane groups past the right edge read and write the rows' 64-byte padding and are
    // left out of the counts. Rows go through a buffer and are written in whole cache lines,
    // streamed past the cache into a frame's batch (written once per pass; see
    // raster/resolve_kernel.cpp), stored into a tile's (its march reads them next).
    float* const planes[kRayGenOutputs] = {a.origin[0], a.origin[1], a.origin[2], a.dir[0],
                                           a.dir[1],    a.dir[2],    a.pdf};
    alignas(64) float rowBuf[kRayGenOutputs][kTileSize];
    float* bufPtr[kRayGenOutputs];
    for (int p = 0; p < kRayGenOutputs; ++p) bufPtr[p] = rowBuf[p];
    const int span = (x1 - x0 + kW - 1) / kW * kW;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; x += kW) {
            const int n = std::min(kW, x1 - x);
            const uint64_t valid = n >= 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1u;
            rayChunk<K>(a, x, y, valid, bufPtr, x - x0, c);
        }
        for (int p = 0; p < kRayGenOutputs; ++p) {
            float* dst =
                planes[p] + std::size_t(y - a.outY0) * a.outStride + std::size_t(x0 - a.outX0);
            if (a.stream)
                for (int i = 0; i < span; i += kW)
                    ln::storeStream(dst + i, ln::load<Lane>(rowBuf[p] + i));
            else
                for (int i = 0; i < span; i += kW)
                    ln::store(dst + i, ln::load<Lane>(rowBuf[p] + i));
        }
    }
    if (a.stream) ln::streamFence();
}

}  // namespace

void generateRaysTile(const RayGenArgs& args, int tile, RayGenCounts& counts) {
    counts = {};
    switch (args.lobe) {
        case RayGenLobe::Mirror: return rayTile<RayGenLobe::Mirror>(args, tile, counts);
        case RayGenLobe::GgxNdf: return rayTile<RayGenLobe::GgxNdf>(args, tile, counts);
        case RayGenLobe::VndfEllipsoid:
            return rayTile<RayGenLobe::VndfEllipsoid>(args, tile, counts);
        case RayGenLobe::VndfSphericalCaps:
            return rayTile<RayGenLobe::VndfSphericalCaps>(args, tile, counts);
        case RayGenLobe::VndfBounded: return rayTile<RayGenLobe::VndfBounded>(args, tile, counts);
        case RayGenLobe::Diffuse: return rayTile<RayGenLobe::Diffuse>(args, tile, counts);
    }
}

}  // namespace ssrt::SSRT_ISA_NS
