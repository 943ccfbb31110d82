// Pixel by pixel: two renders of the same scene and camera (llvmpipe's and ssrt's) compared
// on which triangle each pixel shows and at what depth, and each difference put down to where
// it lies (a triangle edge, a silhouette, or neither). Knows nothing of ssrt.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "perf/peers/gl_peer.h"

namespace peer {

// One side's G-buffer, rows top-down.
struct IdDepthImage {
    int width = 0, height = 0;
    std::vector<uint32_t> ids;  // global triangle id (firstTriangles), kNoTriangle where empty
    std::vector<float> depth;   // linear view depth (distance along the view axis) where covered
};

// One side's shadow map, rows top-down: window depth in [0, 1] (near to far face of the light's
// box, so a share of its depth range), 1 where empty.
struct DepthImage {
    int width = 0, height = 0;
    std::vector<float> depth;
};

struct ErrorStats {
    std::size_t count = 0;
    double median = 0.0, p99 = 0.0, max = 0.0;
};

// Pixels covered by one side only, by whether the other side's coverage reaches within one
// pixel (a silhouette drawn a pixel apart) or not (a hole, or a surface the other lacks).
struct OneSided {
    std::size_t silhouette = 0, elsewhere = 0;
    std::size_t total() const { return silhouette + elsewhere; }
};

// A depth error above this (about ten times the usual p99) counts as an outlier, and a median
// above it is a WARNING: relative to the linear depth in the G-buffer, to the depth range in
// the shadow map.
inline constexpr double kDepthOutlier = 1e-5;

struct GBufferComparison {
    std::size_t pixels = 0, bothEmpty = 0, sameTriangle = 0;
    // Both covered, different triangles. Within one pixel of a triangle boundary (an id change
    // in either image): `sharedEdge` where the two triangles are neighbours in the mesh (they
    // share a vertex), `otherEdge` where not (one triangle's outline over another surface);
    // `interior` away from any boundary, where only the depth order can differ.
    std::size_t sharedEdge = 0, otherEdge = 0, interior = 0;
    OneSided glOnly, ssrtOnly;
    ErrorStats depth;  // |gl - ssrt| / ssrt linear depth, over the same-triangle pixels
    // Same-triangle pixels whose error exceeds kDepthOutlier, and those of them within one
    // pixel of a triangle boundary (where the two interpolations part most).
    std::size_t depthOutliers = 0, depthOutliersAtEdge = 0;

    std::size_t differentTriangle() const { return sharedEdge + otherEdge + interior; }
    std::size_t covered() const { return pixels - bothEmpty; }  // by either side
    std::size_t glCovered() const { return covered() - ssrtOnly.total(); }
    std::size_t ssrtCovered() const { return covered() - glOnly.total(); }
    // Differences no edge explains, as a share of the covered pixels.
    double unexplainedShare() const;
};

// Shadow-map depths further apart than this share of the depth range lie on different
// surfaces (rounding alone stays orders of magnitude below it).
inline constexpr float kSurfaceGap = 1e-3f;

struct ShadowComparison {
    std::size_t texels = 0, bothEmpty = 0, bothCovered = 0;
    OneSided glOnly, ssrtOnly;
    // Both covered at depths further apart than kSurfaceGap (different surfaces, not rounding),
    // and of those the ones within one texel of a depth step in either map.
    std::size_t apart = 0, apartAtStep = 0;
    ErrorStats depth;  // |gl - ssrt|, in shares of the depth range, over the covered texels

    std::size_t glCovered() const { return bothCovered + glOnly.total(); }
    std::size_t ssrtCovered() const { return bothCovered + ssrtOnly.total(); }
    double unexplainedShare() const;
};

// Which triangles of the scene are neighbours: the same draw, and a vertex position in common.
// Holds `desc` by reference: it must outlive this.
class TriangleNeighbours {
public:
    explicit TriangleNeighbours(const GlSceneDesc& desc);
    bool adjacent(uint32_t a, uint32_t b) const;
    bool contains(uint32_t triangle) const { return triangle < first_.back(); }
    std::size_t drawOf(uint32_t triangle) const;  // the draw (instance) of an id it contains
    uint32_t localOf(uint32_t triangle) const { return triangle - first_[drawOf(triangle)]; }

private:
    const GlSceneDesc& desc_;
    std::vector<uint32_t> first_;  // firstTriangles(desc): per draw, then the total
};

GBufferComparison compareGBuffers(const IdDepthImage& gl, const IdDepthImage& ssrt,
                                  const TriangleNeighbours& neighbours);
ShadowComparison compareShadowMaps(const DepthImage& gl, const DepthImage& ssrt);

// The rasterizers' vertex grids, for the verdict: sub-pixel bits of each.
struct SubPixel {
    int ssrtBits = 0, glBits = 0;
};

// Differences beyond this share of the covered pixels that no edge explains are a WARNING.
inline constexpr double kUnexplainedLimit = 0.001;

void printGBufferComparison(const GBufferComparison& c, const SubPixel& grid);
void printShadowComparison(const ShadowComparison& c);

}  // namespace peer
