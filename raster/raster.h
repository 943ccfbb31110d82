// The rasterizer: a visibility pass (depth + triangle ids) or a depth-only pass.
#pragma once

#include <cstdint>

#include "core/image.h"
#include "core/isa.h"
#include "raster/geometry.h"
#include "raster/raster_stats.h"

namespace ssrt {

inline constexpr uint32_t kNoPrimitive = 0xffffffffu;

// Depth holds the depth key (larger = nearer: 1/w for perspective, 1 - z01 for
// orthographic); ids the global triangle id per pixel, kNoPrimitive where nothing is.
struct VisibilityBuffer {
    PlaneF depth;
    PlaneU32 ids;  // empty for a depth-only pass
};

struct RasterOptions {
    Isa isa = Isa::Scalar;
    int threads = 0;
    bool writeIds = true;     // false: the depth-only fast path (shadow maps)
    float clearDepth = 0.0f;  // depth key of the far plane: nothing farther is drawn
};

// Timings of the stages, for --stats.
struct RasterTimes {
    double geometryMs = 0.0;  // transform, clip, set-up, binning
    double rasterMs = 0.0;    // tile kernels
};

// Rasterizes already transformed vertices (see transformVertices) into `out`, reusing its
// planes when their size is right. Every pixel is written.
void rasterize(const Scene& scene, const TransformedVertices& vertices, const RasterView& view,
               const RasterOptions& options, VisibilityBuffer& out, RasterStats& stats,
               RasterTimes* times = nullptr);

// The same into a new buffer.
VisibilityBuffer rasterize(const Scene& scene, const TransformedVertices& vertices,
                           const RasterView& view, const RasterOptions& options, RasterStats& stats,
                           RasterTimes* times = nullptr);

}  // namespace ssrt
