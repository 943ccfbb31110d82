#include "raster/geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/tiles.h"
#include "scenes/material_alpha.h"

namespace ssrt {

namespace {

bool finite4(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// The clip volume as its planes, dot(plane, clip) >= 0: the near plane w >= nearW (perspective
// only) and the guard band |x| <= gx w, |y| <= gy w.
struct ClipVolume {
    glm::vec4 p[5];
    int count = 0;
};

ClipVolume clipVolume(const RasterView& view) {
    const float gx = 1.0f + 2.0f * float(kGuardBandPx) / float(view.width);
    const float gy = 1.0f + 2.0f * float(kGuardBandPx) / float(view.height);
    ClipVolume planes;
    if (view.perspective) planes.p[planes.count++] = {0.0f, 0.0f, 0.0f, 1.0f};  // w >= near
    planes.p[planes.count++] = {-1.0f, 0.0f, 0.0f, gx};
    planes.p[planes.count++] = {1.0f, 0.0f, 0.0f, gx};
    planes.p[planes.count++] = {0.0f, -1.0f, 0.0f, gy};
    planes.p[planes.count++] = {0.0f, 1.0f, 0.0f, gy};
    return planes;
}

float planeDistance(const glm::vec4& plane, const glm::vec4& v, bool isNear, float nearW) {
    return isNear ? v.w - nearW : glm::dot(plane, v);
}

// Sutherland-Hodgman against every plane; returns the vertex count (0 when culled).
int clipPolygon(const RasterView& view, glm::vec4* poly, int n) {
    const ClipVolume planes = clipVolume(view);
    glm::vec4 tmp[16];
    for (int k = 0; k < planes.count && n > 0; ++k) {
        const bool isNear = view.perspective && k == 0;
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const glm::vec4& a = poly[i];
            const glm::vec4& b = poly[(i + 1) % n];
            const float da = planeDistance(planes.p[k], a, isNear, view.nearW);
            const float db = planeDistance(planes.p[k], b, isNear, view.nearW);
            if (da >= 0.0f) tmp[m++] = a;
            if ((da >= 0.0f) != (db >= 0.0f)) {
                const float t = da / (da - db);
                tmp[m++] = a + (b - a) * t;
            }
        }
        std::copy(tmp, tmp + m, poly);
        n = m;
    }
    return n;
}

bool needsClipping(const RasterView& view, const glm::vec4 clip[3], bool& allOutside) {
    const ClipVolume planes = clipVolume(view);
    bool any = false;
    allOutside = false;
    for (int k = 0; k < planes.count; ++k) {
        const bool isNear = view.perspective && k == 0;
        int outside = 0;
        for (int i = 0; i < 3; ++i)
            outside += planeDistance(planes.p[k], clip[i], isNear, view.nearW) < 0.0f;
        if (outside == 3) allOutside = true;
        any |= outside > 0;
    }
    return any;
}

ScreenVertex toScreen(const glm::vec4& c, const RasterView& view) {
    const double invW = 1.0 / double(c.w);
    const double sx = (double(c.x) * invW * 0.5 + 0.5) * view.width;
    const double sy = (0.5 - double(c.y) * invW * 0.5) * view.height;
    ScreenVertex v;
    v.inside = true;
    v.x = int32_t(std::floor(sx * kSubPixel + 0.5));
    v.y = int32_t(std::floor(sy * kSubPixel + 0.5));
    v.q = view.perspective ? invW : 0.5 - 0.5 * double(c.z) * invW;
    return v;
}

// First pixel index whose centre is at or after fixed-point coordinate v.
int32_t firstPixelAtOrAfter(int64_t v) {
    const int64_t n = v - kSubPixel / 2;
    return int32_t(n >= 0 ? (n + kSubPixel - 1) / kSubPixel : -((-n) / kSubPixel));
}
// Last pixel index whose centre is at or before v.
int32_t lastPixelAtOrBefore(int64_t v) {
    const int64_t n = v - kSubPixel / 2;
    return int32_t(n >= 0 ? n / kSubPixel : -((-n + kSubPixel - 1) / kSubPixel));
}

// Set-up of one screen triangle; returns false when it covers no pixel centre's bounds.
bool setupScreenTriangle(ScreenVertex v0, ScreenVertex v1, ScreenVertex v2, uint32_t primId,
                         Faces keep, const RasterView& view, TriangleSetup& t, RasterStats& stats) {
    if (std::max({v0.q, v1.q, v2.q}) <= view.farKey) {
        ++stats.trianglesOutside;  // past the far plane
        return false;
    }
    int64_t area = int64_t(v1.x - v0.x) * (v2.y - v0.y) - int64_t(v2.x - v0.x) * (v1.y - v0.y);
    if (area == 0) {
        ++stats.trianglesInvalid;  // zero area after snapping
        return false;
    }
    // Counter-clockwise in NDC (front) is negative area in y-down pixel coordinates.
    if ((keep == Faces::Front && area > 0) || (keep == Faces::Back && area < 0)) {
        ++stats.trianglesCulled;
        return false;
    }
    if (area < 0) {
        std::swap(v1, v2);
        area = -area;
    }
    const ScreenVertex v[3] = {v0, v1, v2};
    for (int k = 0; k < 3; ++k) {
        const ScreenVertex& p = v[k];
        const ScreenVertex& q = v[(k + 1) % 3];
        const int32_t a = p.y - q.y, b = q.x - p.x;
        const bool topLeft = a > 0 || (a == 0 && b > 0);
        t.a[k] = a;
        t.b[k] = b;
        t.c[k] = -(int64_t(a) * p.x + int64_t(b) * p.y) - (topLeft ? 0 : 1);
    }
    const int64_t xmin = std::min({v0.x, v1.x, v2.x}), xmax = std::max({v0.x, v1.x, v2.x});
    const int64_t ymin = std::min({v0.y, v1.y, v2.y}), ymax = std::max({v0.y, v1.y, v2.y});
    t.minX = std::max(firstPixelAtOrAfter(xmin), 0);
    t.minY = std::max(firstPixelAtOrAfter(ymin), 0);
    t.maxX = std::min(lastPixelAtOrBefore(xmax), view.width - 1);
    t.maxY = std::min(lastPixelAtOrBefore(ymax), view.height - 1);
    if (t.minX > t.maxX || t.minY > t.maxY) {
        ++stats.trianglesOutside;  // off screen, or between pixel centres
        return false;
    }
    // Depth plane through the three vertices, solved in double, used in float.
    const double s = 1.0 / kSubPixel;
    const double x0 = v0.x * s, y0 = v0.y * s;
    const double x1 = v[1].x * s - x0, y1 = v[1].y * s - y0;
    const double x2 = v[2].x * s - x0, y2 = v[2].y * s - y0;
    const double q1 = v[1].q - v0.q, q2 = v[2].q - v0.q;
    const double det = x1 * y2 - x2 * y1;
    const double dqdx = (q1 * y2 - q2 * y1) / det;
    const double dqdy = (x1 * q2 - x2 * q1) / det;
    t.zdx = float(dqdx);
    t.zdy = float(dqdy);
    t.zBase = float(v0.q + dqdx * (t.minX + 0.5 - x0) + dqdy * (t.minY + 0.5 - y0));
    t.primId = primId;
    ++stats.trianglesSetUp;
    return true;
}

}  // namespace

// True when the vertex needs no clipping (and is finite): its screen position can be
// computed once and shared by every triangle that uses it.
static bool insideClipVolume(const glm::vec4& c, const RasterView& view) {
    if (!finite4(c)) return false;
    const ClipVolume planes = clipVolume(view);
    for (int k = 0; k < planes.count; ++k)
        if (planeDistance(planes.p[k], c, view.perspective && k == 0, view.nearW) < 0.0f)
            return false;
    return true;
}

bool setupTriangle(const glm::vec4 clip[3], uint32_t primId, Faces keep, const RasterView& view,
                   std::vector<TriangleSetup>& out, RasterStats& stats) {
    if (!finite4(clip[0]) || !finite4(clip[1]) || !finite4(clip[2])) {
        ++stats.trianglesInvalid;
        return false;
    }
    bool allOutside = false;
    const bool clipped = needsClipping(view, clip, allOutside);
    if (allOutside) {
        ++stats.trianglesOutside;
        return false;
    }
    if (!clipped) {
        TriangleSetup t;
        if (!setupScreenTriangle(toScreen(clip[0], view), toScreen(clip[1], view),
                                 toScreen(clip[2], view), primId, keep, view, t, stats))
            return false;
        out.push_back(t);
        return true;
    }
    ++stats.trianglesClipped;
    glm::vec4 poly[16] = {clip[0], clip[1], clip[2]};
    const int n = clipPolygon(view, poly, 3);
    if (n < 3) {
        ++stats.trianglesOutside;
        return false;
    }
    // Fan; every piece keeps the winding (and so the facing) of the original.
    bool any = false;
    const ScreenVertex s0 = toScreen(poly[0], view);
    for (int i = 1; i + 1 < n; ++i) {
        TriangleSetup t;
        RasterStats pieceStats;
        if (setupScreenTriangle(s0, toScreen(poly[i], view), toScreen(poly[i + 1], view), primId,
                                keep, view, t, pieceStats)) {
            out.push_back(t);
            any = true;
        }
        stats.trianglesSetUp += pieceStats.trianglesSetUp;
        if (pieceStats.trianglesCulled) {
            // Culling is a property of the triangle: count it once.
            stats.trianglesCulled += i == 1;
        }
    }
    return any;
}

TransformedVertices transformVertices(const Scene& scene, const RasterView& view, int threads) {
    TransformedVertices tv;
    uint32_t vertexCount = 0, triCount = 0;
    for (const Instance& inst : scene.instances) {
        tv.instanceOffset.push_back(vertexCount);
        tv.triangleOffset.push_back(triCount);
        vertexCount += uint32_t(scene.meshes[inst.mesh].positions.size());
        triCount += uint32_t(scene.meshes[inst.mesh].triangleCount());
    }
    tv.triangleCount = triCount;
    tv.clip.resize(vertexCount);
    tv.screen.resize(vertexCount);
    // Each instance's object-to-clip matrix, its translation taken relative to the origin in
    // double first (transformFrom).
    std::vector<glm::mat4> objectToClip;
    for (const Instance& inst : scene.instances)
        objectToClip.push_back(view.viewProj * transformFrom(inst.transform, view.origin));
    // Chunks of vertices across all instances, so one big mesh still uses every thread.
    constexpr uint32_t kChunk = 4096;
    parallelFor(int((vertexCount + kChunk - 1) / kChunk), threads, [&](int c) {
        const uint32_t begin = uint32_t(c) * kChunk, end = std::min(vertexCount, begin + kChunk);
        std::size_t i =
            std::upper_bound(tv.instanceOffset.begin(), tv.instanceOffset.end(), begin) -
            tv.instanceOffset.begin() - 1;
        for (uint32_t v = begin; v < end; ++v) {
            while (i + 1 < tv.instanceOffset.size() && tv.instanceOffset[i + 1] <= v) ++i;
            const Instance& inst = scene.instances[i];
            const glm::mat4& m = objectToClip[i];
            const glm::vec3& p = scene.meshes[inst.mesh].positions[v - tv.instanceOffset[i]];
            tv.clip[v] = m * glm::vec4(p, 1.0f);
            tv.screen[v] = insideClipVolume(tv.clip[v], view) ? toScreen(tv.clip[v], view)
                                                              : ScreenVertex{0, 0, 0.0, false};
        }
    });
    return tv;
}

namespace {

constexpr uint32_t kNoAlphaSlot = 0xffffffffu;

// Per instance, what its material's alpha does (scenes/material_alpha.h) and, for one tested
// per point, its first slot in SetupChunks::alpha; empty when no material cuts out anything,
// so such a pass sets up every triangle as before.
struct AlphaPlan {
    std::vector<AlphaCoverage> coverage;
    std::vector<uint32_t> firstSlot;  // kNoAlphaSlot unless PerPoint
    uint32_t slots = 0;
};

AlphaPlan alphaPlan(const Scene& scene) {
    AlphaPlan plan;
    const bool any = std::any_of(scene.materials.begin(), scene.materials.end(),
                                 [](const Material& m) { return m.alphaTested(); });
    if (!any) return plan;
    uint64_t slots = 0;
    for (const Instance& inst : scene.instances) {
        const AlphaCoverage c = alphaCoverage(scene.materials[inst.material]);
        plan.coverage.push_back(c);
        plan.firstSlot.push_back(c == AlphaCoverage::PerPoint ? uint32_t(slots) : kNoAlphaSlot);
        if (c == AlphaCoverage::PerPoint) slots += scene.meshes[inst.mesh].triangleCount();
    }
    // Slots and global ids must leave kAlphaTestedBit free (raster/alpha_test.h).
    if (scene.triangleCount() >= kAlphaTestedBit)
        throw std::length_error(
            "rasterizer: alpha-tested scenes are limited to 2^31 - 1 triangles");
    plan.slots = uint32_t(slots);
    return plan;
}

// The UVs an alpha-tested triangle's base colour reads, (0, 0) for a mesh without them.
void baseColorUvs(const Mesh& mesh, const Material& m, uint32_t local, glm::vec2 uv[3]) {
    const std::vector<glm::vec2>& set = m.baseColorUv.set == 1 ? mesh.uvs1 : mesh.uvs;
    for (int k = 0; k < 3; ++k)
        uv[k] = set.empty() ? glm::vec2(0.0f) : set[mesh.indices[3 * local + k]];
}

// A triangle of an instance whose material cuts out (not Opaque): none of it when Invisible;
// else set up as any other under a marked id, and given its UV planes in its slot when some
// piece of it was set up.
void setupAlphaTested(const Scene& scene, const TransformedVertices& tv, const RasterView& view,
                      const AlphaPlan& alpha, std::size_t inst, uint32_t prim, const uint32_t v[3],
                      Faces cull, std::vector<TriangleSetup>& out,
                      std::vector<AlphaTriangle>& slots, RasterStats& stats) {
    if (alpha.coverage[inst] == AlphaCoverage::Invisible) {
        ++stats.trianglesCutOut;
        return;
    }
    const uint32_t local = prim - tv.triangleOffset[inst];
    const uint32_t slot = alpha.firstSlot[inst] + local;
    const glm::vec4 clip[3] = {tv.clip[v[0]], tv.clip[v[1]], tv.clip[v[2]]};
    if (!setupTriangle(clip, kAlphaTestedBit | slot, cull, view, out, stats)) return;
    const Instance& instance = scene.instances[inst];
    glm::vec2 uv[3];
    baseColorUvs(scene.meshes[instance.mesh], scene.materials[instance.material], local, uv);
    slots[slot] = alphaTriangle(clip, uv, view, prim, instance.material);
    ++stats.trianglesMasked;
}

// The faces a triangle of `material` keeps in a pass drawing `faces`.
Faces facesOf(Faces faces, const Material& material) {
    return faces == Faces::Front && material.doubleSided ? Faces::All : faces;
}

// The triangles [begin, end) in order. kAlpha: the pass has cut-out materials (AlphaPlan not
// empty); without, the loop is the one it was before there were any.
template <bool kAlpha>
void setupRange(const Scene& scene, const TransformedVertices& tv, const RasterView& view,
                const AlphaPlan& alpha, uint32_t begin, uint32_t end,
                std::vector<TriangleSetup>& out, std::vector<AlphaTriangle>& slots,
                RasterStats& stats) {
    // Instance holding `begin`: the last whose first triangle is <= begin.
    std::size_t inst = std::upper_bound(tv.triangleOffset.begin(), tv.triangleOffset.end(), begin) -
                       tv.triangleOffset.begin() - 1;
    for (uint32_t prim = begin; prim < end; ++prim) {
        while (inst + 1 < tv.triangleOffset.size() && tv.triangleOffset[inst + 1] <= prim) ++inst;
        const Instance& instance = scene.instances[inst];
        const Mesh& mesh = scene.meshes[instance.mesh];
        const Faces cull = facesOf(view.faces, scene.materials[instance.material]);
        const uint32_t local = prim - tv.triangleOffset[inst];
        const uint32_t i0 = tv.instanceOffset[inst] + mesh.indices[3 * local];
        const uint32_t i1 = tv.instanceOffset[inst] + mesh.indices[3 * local + 1];
        const uint32_t i2 = tv.instanceOffset[inst] + mesh.indices[3 * local + 2];
        ++stats.trianglesIn;
        if (kAlpha && alpha.coverage[inst] != AlphaCoverage::Opaque) {
            // (The back-face layer has no cut-outs: a cut-out surface's thickness is unknown.)
            if (view.faces == Faces::Back) continue;
            const uint32_t v[3] = {i0, i1, i2};
            setupAlphaTested(scene, tv, view, alpha, inst, prim, v, cull, out, slots, stats);
            continue;
        }
        const ScreenVertex &s0 = tv.screen[i0], &s1 = tv.screen[i1], &s2 = tv.screen[i2];
        if (s0.inside && s1.inside && s2.inside) {
            // Common case: no clipping, vertices snapped once and shared.
            TriangleSetup t;
            if (setupScreenTriangle(s0, s1, s2, prim, cull, view, t, stats)) out.push_back(t);
            continue;
        }
        const glm::vec4 clip[3] = {tv.clip[i0], tv.clip[i1], tv.clip[i2]};
        setupTriangle(clip, prim, cull, view, out, stats);
    }
}

}  // namespace

SetupChunks setupTriangles(const Scene& scene, const TransformedVertices& tv,
                           const RasterView& view, int threads) {
    SetupChunks result;
    const uint32_t n = tv.triangleCount;
    const uint32_t chunkCount = (n + SetupChunks::kChunkSize - 1) / SetupChunks::kChunkSize;
    result.chunks.resize(chunkCount);
    result.stats.resize(chunkCount);
    const AlphaPlan alpha = alphaPlan(scene);
    result.alpha.resize(alpha.slots);
    parallelFor(int(chunkCount), threads, [&](int c) {
        const uint32_t begin = uint32_t(c) * SetupChunks::kChunkSize;
        const uint32_t end = std::min(n, begin + SetupChunks::kChunkSize);
        auto& out = result.chunks[c];
        out.reserve(end - begin);
        if (alpha.coverage.empty())
            setupRange<false>(scene, tv, view, alpha, begin, end, out, result.alpha,
                              result.stats[c]);
        else
            setupRange<true>(scene, tv, view, alpha, begin, end, out, result.alpha,
                             result.stats[c]);
    });
    return result;
}

}  // namespace ssrt
