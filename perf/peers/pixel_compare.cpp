#include "perf/peers/pixel_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace peer {

namespace {

// Whether pred(j) holds for some pixel j of the 3x3 block around (x, y) inside the image:
// "within one pixel" throughout.
template <class Pred>
bool anyAround(int w, int h, int x, int y, Pred&& pred) {
    for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, h - 1); ++ny)
        for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, w - 1); ++nx)
            if (pred(std::size_t(ny) * std::size_t(w) + std::size_t(nx))) return true;
    return false;
}

// Whether a triangle boundary lies within one pixel: a pixel near (x, y) shows another id.
bool idEdgeAround(int w, int h, int x, int y, const std::vector<uint32_t>& ids, uint32_t id) {
    return anyAround(w, h, x, y, [&](std::size_t j) { return ids[j] != id; });
}

ErrorStats errorStats(std::vector<double> errors) {
    ErrorStats s;
    s.count = errors.size();
    if (errors.empty()) return s;
    // Nearest rank: the smallest value with at least share q of the values at or below it.
    auto quantile = [&](double q) {
        std::size_t k = std::size_t(std::ceil(q * double(errors.size()))) - 1;
        std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(k), errors.end());
        return errors[k];
    };
    s.median = quantile(0.5);
    s.p99 = quantile(0.99);
    s.max = quantile(1.0);
    return s;
}

void checkSizes(int w0, int h0, int w1, int h1, const char* what) {
    if (w0 != w1 || h0 != h1)
        throw std::runtime_error(std::string(what) + ": the two renders differ in size");
}

// A pixel the `emptySide` left empty but the other side covered: at a silhouette when the
// empty side covers a pixel within one of it.
template <class Covered>
void addOneSided(int w, int h, int x, int y, Covered&& emptySideCovers, OneSided& out) {
    if (anyAround(w, h, x, y, emptySideCovers)) ++out.silhouette;
    else ++out.elsewhere;
}

double share(std::size_t n, std::size_t of) { return of ? 100.0 * double(n) / double(of) : 0.0; }

void printCount(const char* label, std::size_t n, std::size_t of, const std::string& detail = "") {
    std::printf("    %-20s %10zu %8.3f %%%s\n", label, n, share(n, of), detail.c_str());
}

std::string oneSidedDetail(const OneSided& o) {
    return ": silhouette " + std::to_string(o.silhouette) + ", elsewhere " +
           std::to_string(o.elsewhere);
}

void printWarningIfOver(double unexplained, const char* what) {
    if (unexplained > kUnexplainedLimit)
        std::printf(
            "    WARNING: %.3f %% of the covered %s differ away from any edge (limit %.1f %%)\n",
            100.0 * unexplained, what, 100.0 * kUnexplainedLimit);
}

// A render shifted by a pixel would pass as edge differences, one pixel wide each; its depths
// would not: the median error rises by orders of magnitude.
void printDepthWarningIfOver(const ErrorStats& depth) {
    if (depth.median > kDepthOutlier)
        std::printf("    WARNING: median depth error %.2g is over %g: the depths disagree\n",
                    depth.median, kDepthOutlier);
}

}  // namespace

TriangleNeighbours::TriangleNeighbours(const GlSceneDesc& desc)
    : desc_(desc), first_(firstTriangles(desc)) {}

std::size_t TriangleNeighbours::drawOf(uint32_t triangle) const {
    auto it = std::upper_bound(first_.begin(), first_.end(), triangle);
    return std::size_t(it - first_.begin()) - 1;
}

bool TriangleNeighbours::adjacent(uint32_t a, uint32_t b) const {
    if (!contains(a) || !contains(b)) return false;  // a wrong id: counted, never dereferenced
    std::size_t draw = drawOf(a);
    if (draw != drawOf(b)) return false;
    // Positions, not indices: a mesh splits vertices where its normals break (hard edges).
    const GlMesh& mesh = desc_.meshes.at(desc_.draws[draw].mesh);
    const uint32_t* ta = &mesh.indices[std::size_t(localOf(a)) * 3];
    const uint32_t* tb = &mesh.indices[std::size_t(localOf(b)) * 3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (mesh.positions[ta[i]] == mesh.positions[tb[j]]) return true;
    return false;
}

double GBufferComparison::unexplainedShare() const {
    return covered() ? double(interior + glOnly.elsewhere + ssrtOnly.elsewhere) / double(covered())
                     : 0.0;
}

double ShadowComparison::unexplainedShare() const {
    std::size_t covered = texels - bothEmpty;
    std::size_t n = (apart - apartAtStep) + glOnly.elsewhere + ssrtOnly.elsewhere;
    return covered ? double(n) / double(covered) : 0.0;
}

GBufferComparison compareGBuffers(const IdDepthImage& gl, const IdDepthImage& ssrt,
                                  const TriangleNeighbours& neighbours) {
    checkSizes(gl.width, gl.height, ssrt.width, ssrt.height, "G-buffer comparison");
    const int w = gl.width, h = gl.height;
    GBufferComparison c;
    c.pixels = std::size_t(w) * std::size_t(h);
    std::vector<double> errors;
    errors.reserve(c.pixels);
    auto glCovers = [&](std::size_t j) { return gl.ids[j] != kNoTriangle; };
    auto ssrtCovers = [&](std::size_t j) { return ssrt.ids[j] != kNoTriangle; };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            const uint32_t a = gl.ids[i], b = ssrt.ids[i];
            if (a == kNoTriangle && b == kNoTriangle) {
                ++c.bothEmpty;
            } else if (a == kNoTriangle) {
                addOneSided(w, h, x, y, glCovers, c.ssrtOnly);
            } else if (b == kNoTriangle) {
                addOneSided(w, h, x, y, ssrtCovers, c.glOnly);
            } else if (a == b) {
                ++c.sameTriangle;
                const double e =
                    std::abs(double(gl.depth[i]) - double(ssrt.depth[i])) / double(ssrt.depth[i]);
                errors.push_back(e);
                if (e > kDepthOutlier) {
                    ++c.depthOutliers;
                    c.depthOutliersAtEdge += idEdgeAround(w, h, x, y, gl.ids, a);
                }
            } else if (idEdgeAround(w, h, x, y, gl.ids, a) ||
                       idEdgeAround(w, h, x, y, ssrt.ids, b)) {
                ++(neighbours.adjacent(a, b) ? c.sharedEdge : c.otherEdge);
            } else {
                ++c.interior;
            }
        }
    }
    c.depth = errorStats(std::move(errors));
    return c;
}

ShadowComparison compareShadowMaps(const DepthImage& gl, const DepthImage& ssrt) {
    checkSizes(gl.width, gl.height, ssrt.width, ssrt.height, "shadow-map comparison");
    const int w = gl.width, h = gl.height;
    ShadowComparison c;
    c.texels = std::size_t(w) * std::size_t(h);
    std::vector<double> errors;
    errors.reserve(c.texels);
    auto glCovers = [&](std::size_t j) { return gl.depth[j] < 1.0f; };
    auto ssrtCovers = [&](std::size_t j) { return ssrt.depth[j] < 1.0f; };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
            const bool g = glCovers(i), s = ssrtCovers(i);
            if (!g && !s) {
                ++c.bothEmpty;
            } else if (!g) {
                addOneSided(w, h, x, y, glCovers, c.ssrtOnly);
            } else if (!s) {
                addOneSided(w, h, x, y, ssrtCovers, c.glOnly);
            } else {
                ++c.bothCovered;
                const double d = std::abs(double(gl.depth[i]) - double(ssrt.depth[i]));
                if (d <= kSurfaceGap) {
                    errors.push_back(d);
                    continue;
                }
                ++c.apart;
                // A step: a neighbour further than the gap from this texel, in either map.
                auto step = [&](const std::vector<float>& z) {
                    return anyAround(w, h, x, y, [&](std::size_t j) {
                        return std::abs(z[j] - z[i]) > kSurfaceGap;
                    });
                };
                c.apartAtStep += step(gl.depth) || step(ssrt.depth);
            }
        }
    }
    c.depth = errorStats(std::move(errors));
    return c;
}

void printGBufferComparison(const GBufferComparison& c, const SubPixel& grid) {
    std::printf("  G-buffer, per pixel (ids and linear depth), %zu pixels:\n", c.pixels);
    printCount("both empty", c.bothEmpty, c.pixels);
    printCount("same triangle", c.sameTriangle, c.pixels);
    printCount("different triangle", c.differentTriangle(), c.pixels,
               ": shared mesh edge " + std::to_string(c.sharedEdge) + ", other edge " +
                   std::to_string(c.otherEdge) + ", interior " + std::to_string(c.interior));
    printCount("llvmpipe only", c.glOnly.total(), c.pixels, oneSidedDetail(c.glOnly));
    printCount("ssrt only", c.ssrtOnly.total(), c.pixels, oneSidedDetail(c.ssrtOnly));
    std::printf(
        "    linear depth on the same triangle, relative error: median %.2g, p99 %.2g, "
        "max %.2g\n",
        c.depth.median, c.depth.p99, c.depth.max);
    std::printf("    relative error over %g: %zu pixels, of them within one pixel of an edge %zu\n",
                kDepthOutlier, c.depthOutliers, c.depthOutliersAtEdge);
    std::printf(
        "    sub-pixel grids: ssrt 1/%d pixel (%d bits), llvmpipe 1/%d (GL_SUBPIXEL_BITS %d)\n",
        1 << grid.ssrtBits, grid.ssrtBits, 1 << grid.glBits, grid.glBits);
    const std::size_t unexplained = c.interior + c.glOnly.elsewhere + c.ssrtOnly.elsewhere;
    const std::size_t differing = c.differentTriangle() + c.glOnly.total() + c.ssrtOnly.total();
    if (differing == 0)
        std::printf("    verdict: every pixel shows the same triangle on both sides\n");
    else if (unexplained == 0)
        std::printf(
            "    verdict: all %zu differing pixels lie within one pixel of a triangle edge or a "
            "silhouette: fill rule and sub-pixel snapping\n",
            differing);
    else
        std::printf(
            "    verdict: %zu differing pixels lie on triangle edges or silhouettes (fill rule, "
            "sub-pixel snapping), %zu (%.4f %% of the covered) away from any edge (depth order, "
            "or a surface one side lacks)\n",
            differing - unexplained, unexplained, 100.0 * c.unexplainedShare());
    printWarningIfOver(c.unexplainedShare(), "pixels");
    printDepthWarningIfOver(c.depth);
}

void printShadowComparison(const ShadowComparison& c) {
    std::printf("  shadow map, per texel (depth only), %zu texels:\n", c.texels);
    printCount("both empty", c.bothEmpty, c.texels);
    char apart[96];
    std::snprintf(apart, sizeof apart, ": depths over %g apart %zu, of them at a depth step %zu",
                  double(kSurfaceGap), c.apart, c.apartAtStep);
    printCount("both covered", c.bothCovered, c.texels, apart);
    printCount("llvmpipe only", c.glOnly.total(), c.texels, oneSidedDetail(c.glOnly));
    printCount("ssrt only", c.ssrtOnly.total(), c.texels, oneSidedDetail(c.ssrtOnly));
    std::printf(
        "    depth on the same surface, error in shares of the depth range: median %.2g, "
        "p99 %.2g, max %.2g\n",
        c.depth.median, c.depth.p99, c.depth.max);
    const std::size_t differing = c.apart + c.glOnly.total() + c.ssrtOnly.total();
    const std::size_t unexplained =
        (c.apart - c.apartAtStep) + c.glOnly.elsewhere + c.ssrtOnly.elsewhere;
    if (differing == 0)
        std::printf(
            "    verdict: every texel is covered by both sides or by neither, on the same "
            "surface\n");
    else if (unexplained == 0)
        std::printf(
            "    verdict: all %zu differing texels lie within one texel of a silhouette or "
            "depth step: edge rasterization (fill rule, sub-pixel snapping)\n",
            differing);
    else
        std::printf(
            "    verdict: %zu differing texels lie at silhouettes or depth steps, %zu (%.4f %% of "
            "the covered) elsewhere\n",
            differing - unexplained, unexplained, 100.0 * c.unexplainedShare());
    printWarningIfOver(c.unexplainedShare(), "texels");
    printDepthWarningIfOver(c.depth);
}

}  // namespace peer
