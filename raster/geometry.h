// Front end of a raster pass: vertex transform, triangle assembly, culling, clipping
// (near plane and guard band; triangles wholly past the far plane dropped), snapping to fixed
// point and triangle set-up.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "raster/alpha_test.h"
#include "raster/raster_stats.h"
#include "raster/setup.h"
#include "scenes/scene.h"

namespace ssrt {

// Which faces a pass draws, by their winding on screen (counter-clockwise in NDC is front).
enum class Faces : uint8_t {
    Front,  // front faces, and back faces of double-sided materials (the visibility pass)
    All,    // every face (the shadow map: every face casts a shadow)
    Back,   // back faces only, of every material, opaque ones alone: the back-face depth layer
            // (the far side of what the visibility pass sees; renderer/back_depth.h)
};

// How the pass sees the scene.
struct RasterView {
    glm::mat4 viewProj{1.0f};  // of points measured from `origin`
    glm::vec3 origin{0.0f};    // Scene::origin() for the frame's passes (transformFrom)
    int width = 0, height = 0;
    bool perspective = true;  // depth key 1/w (perspective) or 1 - z01 (orthographic)
    float nearW = 0.05f;      // near plane as clip-space w (perspective only)
    // The far plane's depth key (RasterOptions::clearDepth): a triangle whose corners all
    // lie at or past it is dropped before binning, as the depth test would drop its pixels.
    double farKey = -std::numeric_limits<double>::infinity();
    Faces faces = Faces::Front;
};

// A vertex snapped to the screen: 24.8 fixed point and the depth key. Only valid when
// `inside` (within the near plane and the guard band); other vertices go through clipping.
struct ScreenVertex {
    int32_t x, y;
    double q;
    bool inside;
};

// Clip-space vertices of every instance, in instance order, and their screen positions.
struct TransformedVertices {
    std::vector<glm::vec4> clip;
    std::vector<ScreenVertex> screen;
    std::vector<uint32_t> instanceOffset;  // first vertex of each instance in `clip`
    std::vector<uint32_t> triangleOffset;  // first global triangle id of each instance
    uint32_t triangleCount = 0;
};

TransformedVertices transformVertices(const Scene& scene, const RasterView& view, int threads);

// Set-up triangles in chunks of consecutive global triangle ids; within and across chunks
// the order is submission order.
struct SetupChunks {
    static constexpr uint32_t kChunkSize = 2048;
    std::vector<std::vector<TriangleSetup>> chunks;
    std::vector<RasterStats> stats;  // per chunk, combined in chunk order
    // The alpha-tested triangles' slots (raster/alpha_test.h): the triangles of each instance
    // whose material is tested per point, in instance order; empty when there are none.
    std::vector<AlphaTriangle> alpha;
};

SetupChunks setupTriangles(const Scene& scene, const TransformedVertices& vertices,
                           const RasterView& view, int threads);

// The UV planes of an alpha-tested triangle from its unclipped clip-space vertices and the
// UVs its base colour reads (raster/alpha_test.h).
AlphaTriangle alphaTriangle(const glm::vec4 clip[3], const glm::vec2 uv[3], const RasterView& view,
                            uint32_t primId, uint32_t material);

// Clips one clip-space triangle and appends its screen triangles to `out`; exposed for the
// tests. Returns false when nothing of it can be seen.
// `keep`: the faces it draws by winding alone (Front: front faces only; a double-sided
// material is the caller's Faces::All).
bool setupTriangle(const glm::vec4 clip[3], uint32_t primId, Faces keep, const RasterView& view,
                   std::vector<TriangleSetup>& out, RasterStats& stats);

}  // namespace ssrt
