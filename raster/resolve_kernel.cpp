#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include <algorithm>
#include <bit>

#include "core/lane_vec.h"
#include "core/tiles.h"
#include "raster/raster.h"
#include "raster/resolve_kernel.h"

namespace ssrt::SSRT_ISA_NS {

namespace ln = ssrt::lanes;
using V3 = ln::V3<Lane>;

namespace {

// The planes a tile writes, in the order resolveChunk computes them: the G-buffer's 12, then
// each UV set's, then the tangent frame's (outputPlanes).
constexpr int kResolveOutputs = std::popcount(kResolvedPlanes);
constexpr int kMaxOutputs =
    kResolveOutputs + kResolveUvSets * kResolveUvOutputs + kResolveTangentOutputs;
constexpr int kMaterialOut = 9;  // background -1 there, 0 elsewhere

// Field rows of the structure-of-arrays gather below.
// clang-format off
enum Field {
    kP0 = 0, kN = 3, kD = 6, kG1 = 7, kG2 = 10,
    kN0 = 13, kN1 = 16, kN2 = 19,
    kAlbedo = 22, kMetallic = 25, kRoughness = 26, kMaterial = 27,
    kUv0 = 28, kUv1 = 30, kUv2 = 32,
    kSet1 = 34,  // the second UV set's three vertices, as kUv0..kUv2
    kTangent = 40,  // three vertices' tangents, x y z w each
    kFieldCount = 52
};
// clang-format on

// The rows a frame gathers: the second UV set's only when it is used, the tangents only with
// a normal map (then the second set's rows too, zero when unused).
SSRT_INLINE int fieldCount(const ResolveArgs& a) {
    return a.tangent[0] ? kFieldCount : a.u1 ? kTangent : kSet1;
}

// The UV planes a frame writes, and all of its planes.
SSRT_INLINE int uvOutputCount(const ResolveArgs& a) {
    return (a.u ? kResolveUvOutputs : 0) + (a.u1 ? kResolveUvOutputs : 0);
}
SSRT_INLINE int outputCount(const ResolveArgs& a) {
    return kResolveOutputs + uvOutputCount(a) + (a.tangent[0] ? kResolveTangentOutputs : 0);
}

// The output planes in that order (outputCount of them).
void outputPlanes(const ResolveArgs& a, float* (&out)[kMaxOutputs]) {
    int n = 0;
    GBufferOf<float*>::forEach(
        a.out, [&](GBufferPlane, float* p) { out[n++] = p; }, kResolvedPlanes);
    for (int s = 0; s < (a.u1 ? 2 : a.u ? 1 : 0); ++s)
        for (float* p : a.uv[s]) out[n++] = p;
    if (a.tangent[0])
        for (float* p : a.tangentFrame) out[n++] = p;
}

// Structure-of-arrays view of the triangles under kW pixels (a scalar gather loop: the
// same on every ISA).
struct Gathered {
    alignas(64) float f[kFieldCount][kW];
};

SSRT_INLINE void gatherLane(const ResolveArgs& a, uint32_t id, int l, Gathered& g, float* m) {
    const ResolveTriangle& t = a.triangles[id];
    const ResolveInstance& in = a.instances[t.instance];
    for (int k = 0; k < 3; ++k) {
        g.f[kP0 + k][l] = t.p0[k];
        g.f[kN + k][l] = t.n[k];
        g.f[kG1 + k][l] = t.g1[k];
        g.f[kG2 + k][l] = t.g2[k];
        g.f[kAlbedo + k][l] = in.albedo[k];
    }
    g.f[kD][l] = t.d;
    for (int v = 0; v < 3; ++v) {
        g.f[kN0 + 3 * v + 0][l] = a.normalX[t.v[v]];
        g.f[kN0 + 3 * v + 1][l] = a.normalY[t.v[v]];
        g.f[kN0 + 3 * v + 2][l] = a.normalZ[t.v[v]];
    }
    g.f[kMetallic][l] = in.metallic;
    g.f[kRoughness][l] = in.roughness;
    g.f[kMaterial][l] = in.materialId;
    for (int v = 0; v < 3; ++v) {
        g.f[kUv0 + 2 * v][l] = a.u ? a.u[t.v[v]] : 0.0f;
        g.f[kUv0 + 2 * v + 1][l] = a.v ? a.v[t.v[v]] : 0.0f;
    }
    if (a.u1)
        for (int v = 0; v < 3; ++v) {
            g.f[kSet1 + 2 * v][l] = a.u1[t.v[v]];
            g.f[kSet1 + 2 * v + 1][l] = a.v1[t.v[v]];
        }
    if (a.tangent[0]) {
        if (!a.u1)
            for (int k = kSet1; k < kTangent; ++k) g.f[k][l] = 0.0f;
        for (int v = 0; v < 3; ++v)
            for (int c = 0; c < 4; ++c) g.f[kTangent + 4 * v + c][l] = a.tangent[c][t.v[v]];
    }
    for (int k = 0; k < 16; ++k) m[k * kW + l] = in.viewToPrevClip[k];
}

// The fields as lanes: broadcast when every lane sees the same triangle (large triangles,
// the common case), loaded from the per-lane gather otherwise.
struct Fields {
    Lane f[kFieldCount];
    Lane m[16];
};

SSRT_INLINE void broadcastFields(const ResolveArgs& a, uint32_t id, Fields& out) {
    Gathered g;
    alignas(64) float m[16 * kW];
    gatherLane(a, id, 0, g, m);
    const int nf = fieldCount(a);
    for (int k = 0; k < nf; ++k) out.f[k] = Lane(g.f[k][0]);
    for (int k = 0; k < 16; ++k) out.m[k] = Lane(m[k * kW]);
}

SSRT_INLINE V3 field3(const Fields& g, int f) { return {g.f[f], g.f[f + 1], g.f[f + 2]}; }

// The last uniform chunk's fields: neighbouring chunks usually see the same triangle.
struct FieldCache {
    uint32_t id = kNoPrimitive;
    Fields fields;
};

// Barycentrics (b1, b2) where the ray `dir` meets the triangle's plane (extended beyond its
// edges, as the derivatives need).
SSRT_INLINE void barycentrics(const ResolveArgs& a, const Fields& g, const V3& dir, Lane& b1,
                              Lane& b2) {
    const Lane nd = ln::dot(field3(g, kN), dir);
    const Lane ndSafe = ln::select(ln::abs(nd) > Lane(1e-12f), nd, Lane(-1e-12f));
    const Lane t = ln::clamp(g.f[kD] / ndSafe, Lane(a.nearZ), Lane(a.farZ));
    const V3 r = dir * t - field3(g, kP0);
    b1 = ln::dot(r, field3(g, kG1));
    b2 = ln::dot(r, field3(g, kG2));
}

// The UV set whose three vertices start at field row `set` (kUv0 or kSet1).
SSRT_INLINE void interpolateUv(const Fields& g, int set, Lane b1, Lane b2, Lane& u, Lane& v) {
    const Lane b0 = Lane(1.0f) - b1 - b2;
    u = (g.f[set] * b0 + g.f[set + 2] * b1) + g.f[set + 4] * b2;
    v = (g.f[set + 1] * b0 + g.f[set + 3] * b1) + g.f[set + 5] * b2;
}

// UV at the pixel centre and its differences to the rays through the next pixel right and
// the next pixel down, on the same plane: exact screen-space derivatives for a planar
// triangle, which the texture pass turns into a level of detail. Every set in use is
// interpolated with the same three pairs of barycentrics.
SSRT_INLINE void uvAndDerivatives(const ResolveArgs& a, const Fields& g, const V3& dir, Lane b1,
                                  Lane b2, Lane* out) {
    Lane bx1, bx2, by1, by2;
    const V3 dirX{dir.x + Lane(2.0f / float(a.width) * a.tanHalfX), dir.y, dir.z};
    barycentrics(a, g, dirX, bx1, bx2);
    const V3 dirY{dir.x, dir.y - Lane(2.0f / float(a.height) * a.tanHalfY), dir.z};
    barycentrics(a, g, dirY, by1, by2);
    const int sets = a.u1 ? 2 : 1;
    for (int s = 0; s < sets; ++s) {
        Lane u, v, ux, vx, uy, vy;
        const int row = s == 0 ? int(kUv0) : int(kSet1);
        interpolateUv(g, row, b1, b2, u, v);
        interpolateUv(g, row, bx1, bx2, ux, vx);
        interpolateUv(g, row, by1, by2, uy, vy);
        Lane* o = out + s * kResolveUvOutputs;
        o[kUvU] = u;
        o[kUvV] = v;
        o[kUvDuDx] = ux - u;
        o[kUvDvDx] = vx - v;
        o[kUvDuDy] = uy - u;
        o[kUvDvDy] = vy - v;
    }
}

// The tangent frame at barycentrics (b1, b2): x y z w, each interpolated like the normal
// (not normalised: the texture pass orthonormalises against the normal), negated with it on
// a back face (`flip`).
SSRT_INLINE void interpolateTangent(const Fields& g, Lane b1, Lane b2, ln::MaskOf<Lane> flip,
                                    Lane* out) {
    const Lane b0 = Lane(1.0f) - b1 - b2;
    for (int c = 0; c < 4; ++c) {
        const Lane t =
            (g.f[kTangent + c] * b0 + g.f[kTangent + 4 + c] * b1) + g.f[kTangent + 8 + c] * b2;
        out[c] = ln::select(flip, Lane(0.0f) - t, t);
    }
}

// Writes lane group x of row y into out[plane] + (x - x0): a row buffer of the tile.
void resolveChunk(const ResolveArgs& a, int x, int y, FieldCache& cache, float* const* out,
                  int x0) {
    // Which lanes hold a visible triangle.
    const uint32_t* idRow = a.ids + std::size_t(y) * a.idStride;
    // Lanes past the right edge read the padding, which the raster pass filled with
    // kNoPrimitive (raster/tile_raster_kernel.cpp): they come out as background.
    const uint32_t* id = idRow + x;
    using ILane = ln::IntOf<Lane>;
    const ILane ids = ln::loadInt<Lane>(reinterpret_cast<const int32_t*>(id));
    const auto visibleInt = ids != ILane(int32_t(kNoPrimitive));
    const bool any = ln::any(visibleInt);
    const bool uniform = ln::all(ids == ILane(int32_t(id[0])));
    const int o = x - x0;
    const Lane zero(0.0f);
    const int outputs = outputCount(a);
    if (!any) {
        for (int p = 0; p < outputs; ++p)
            ln::store(out[p] + o, p == kMaterialOut ? Lane(-1.0f) : zero);
        return;
    }
    Fields local;
    const Fields* fields = &local;
    if (uniform) {
        if (cache.id != id[0]) {
            broadcastFields(a, id[0], cache.fields);
            cache.id = id[0];
        }
        fields = &cache.fields;
    } else {
        Fields& g = local;
        Gathered ga;
        alignas(64) float m[16 * kW];
        const int nf = fieldCount(a);
        for (int l = 0; l < kW; ++l) {
            if (id[l] != kNoPrimitive) {
                gatherLane(a, id[l], l, ga, m);
            } else {
                for (int k = 0; k < nf; ++k) ga.f[k][l] = 0.0f;
                for (int k = 0; k < 16; ++k) m[k * kW + l] = k % 5 == 0 ? 1.0f : 0.0f;
            }
        }
        for (int k = 0; k < nf; ++k) g.f[k] = ln::load<Lane>(ga.f[k]);
        for (int k = 0; k < 16; ++k) g.m[k] = ln::load<Lane>(m + k * kW);
    }
    const Fields& g = *fields;
    const auto vis = ln::toFloatMask(visibleInt);
    // View ray through the pixel centre: (ndcX tanHalfX, ndcY tanHalfY, -1).
    const Lane px = Lane(float(x)) + ln::laneIndex<Lane>() + Lane(0.5f);
    const Lane ndcX = px * Lane(2.0f / float(a.width)) - Lane(1.0f);
    const Lane ndcY = Lane(1.0f) - Lane((float(y) + 0.5f) * (2.0f / float(a.height)));
    const V3 dir{ndcX * Lane(a.tanHalfX), ndcY * Lane(a.tanHalfY), Lane(-1.0f)};
    // Ray-plane: t = d / (n.dir); the hit is dir t and view Z is t (dir.z = -1).
    const V3 n = field3(g, kN);
    const Lane nd = ln::dot(n, dir);
    const Lane ndSafe = ln::select(ln::abs(nd) > Lane(1e-12f), nd, Lane(-1e-12f));
    const Lane t = ln::clamp(g.f[kD] / ndSafe, Lane(a.nearZ), Lane(a.farZ));
    const V3 h = dir * t;
    const V3 r = h - field3(g, kP0);
    const Lane b1 = ln::dot(r, field3(g, kG1)), b2 = ln::dot(r, field3(g, kG2));
    const Lane b0 = Lane(1.0f) - b1 - b2;
    V3 normal = ln::normalize((field3(g, kN0) * b0 + field3(g, kN1) * b1) + field3(g, kN2) * b2);
    // Seen from behind (double-sided material): the shading normal faces the camera.
    normal = ln::select(nd > zero, V3{zero - normal.x, zero - normal.y, zero - normal.z}, normal);
    // Motion: the hit point in the previous clip space, to previous pixel coordinates.
    Lane pc[4];
    for (int row = 0; row < 4; ++row)
        pc[row] = ((g.m[0 * 4 + row] * h.x + g.m[1 * 4 + row] * h.y) + g.m[2 * 4 + row] * h.z) +
                  g.m[3 * 4 + row];
    const auto inFront = pc[3] > Lane(1e-6f);
    const Lane invW = Lane(1.0f) / ln::select(inFront, pc[3], Lane(1.0f));
    const Lane prevX = (pc[0] * invW * Lane(0.5f) + Lane(0.5f)) * Lane(float(a.width));
    const Lane prevY = (Lane(0.5f) - pc[1] * invW * Lane(0.5f)) * Lane(float(a.height));
    const Lane curY = Lane(float(y) + 0.5f);
    const Lane motionX = ln::select(inFront, prevX - px, zero);
    const Lane motionY = ln::select(inFront, prevY - curY, zero);

    // clang-format off
    Lane outs[kMaxOutputs] = {t, normal.x, normal.y, normal.z,
                              g.f[kAlbedo], g.f[kAlbedo + 1], g.f[kAlbedo + 2],
                              g.f[kMetallic], g.f[kRoughness], g.f[kMaterial],
                              motionX, motionY};
    // clang-format on
    if (a.u) uvAndDerivatives(a, g, dir, b1, b2, outs + kResolveOutputs);
    if (a.tangent[0])
        interpolateTangent(g, b1, b2, nd > zero, outs + kResolveOutputs + uvOutputCount(a));
    for (int p = 0; p < outputs; ++p) {
        const Lane background = p == kMaterialOut ? Lane(-1.0f) : zero;
        ln::store(out[p] + o, ln::select(vis, outs[p], background));
    }
}

}  // namespace

void resolveTile(const ResolveArgs& args, int tile) {
    const auto [x0, y0, x1, y1] = tileRect(tile, args.tilesX, args.width, args.height);
    // Each tile row is resolved into a small buffer, then streamed to the planes in whole
    // cache lines: fourteen planes written in 32-byte pieces would cost a read for
    // ownership per line and thrash the write-combining buffers.
    alignas(64) float rowBuf[kMaxOutputs][kTileSize];
    float* bufPtr[kMaxOutputs];
    for (int p = 0; p < kMaxOutputs; ++p) bufPtr[p] = rowBuf[p];
    const int outputs = outputCount(args);
    float* planes[kMaxOutputs] = {};
    outputPlanes(args, planes);
    // Lane groups past the right edge land in the rows' 64-byte padding.
    const int span = (x1 - x0 + kW - 1) / kW * kW;
    FieldCache cache;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; x += kW) resolveChunk(args, x, y, cache, bufPtr, x0);
        for (int p = 0; p < outputs; ++p) {
            float* dst = planes[p] + std::size_t(y) * args.outStride + x0;
            for (int i = 0; i < span; i += kW)
                ln::storeStream(dst + i, ln::load<Lane>(rowBuf[p] + i));
        }
    }
    ln::streamFence();
}

}  // namespace ssrt::SSRT_ISA_NS
