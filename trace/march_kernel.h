// The marcher kernels, one copy per ISA (trace/march_linear_kernel.cpp,
// march_dda_kernel.cpp, march_hiz_kernel.cpp): each marches a packed list of rays (one tile's)
// kWidth at a time and writes one result per ray. Plain pointers and values only (no GLM, no
// xsimd).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"

namespace ssrt {

inline constexpr int kMaxHiZLevels = 16;
// Packed ray arrays are padded to a multiple of this (the widest lane group).
inline constexpr int kMarchPad = 16;

struct MarchKernelArgs {
    // Frame and camera: a view point (x, y, -z) projects to pixel
    // (cx + x sx / z, cy - y sy / z); sx = width / (2 tanHalfX), cx = width / 2.
    int width, height;
    float sx, sy, cx, cy;
    float nearZ;
    float viewToWorld[9];  // column-major rotation
    GBufferView g;         // viewZ, normal
    // The back-face depth layer, of g's stride (0 where unknown), or null: the thickness is
    // the fallback at every pixel.
    const float* backZ;
    // Hi-Z min pyramid (levels of minZ, background +inf).
    int hizLevels;
    const float* hizMin[kMaxHiZLevels];
    std::size_t hizStride[kMaxHiZLevels];
    int hizWidth[kMaxHiZLevels], hizHeight[kMaxHiZLevels];
    // Each level's width and height as floats, for the kernels' lane tables.
    float hizWidthF[kMaxHiZLevels], hizHeightF[kMaxHiZLevels];
    // The same levels packed as 1/minZ (background 0) in 4x4 tiles (raster/hiz.h,
    // hiZPackedIndex), with each level's first element, tiles per row of tiles (a power of
    // two) and the shift that is a row of tiles' elements (log2 pitch + 4) as floats (exact:
    // the whole is < 2^24 elements), for a hardware gather; null when the pyramid is too
    // large (then the planes are read).
    const float* hizInvPacked;
    float hizOffset[kMaxHiZLevels], hizPitch[kMaxHiZLevels], hizRowShift[kMaxHiZLevels];
    // Settings.
    int maxSteps;
    float maxDistance, ddaStride;
    float stepScale, stepBias;            // linear step = origin depth * scale + bias
    float thicknessScale, thicknessBias;  // thickness at depth z = z * scale + bias
    int refineSteps, mostDetailedLevel, startLevel;
    // Packed rays: count, then arrays of at least count rounded up to kMarchPad. (For
    // marchSortKeys: a row's rays, unpacked, with their pdf.)
    int count;
    const float *ox, *oy, *oz, *dx, *dy, *dz;
    const float* pdf;              // marchSortKeys only
    const float *pixelX, *pixelY;  // the ray's own pixel (integers as floats)
    const float* jitter;           // DDA first-step offset in strides, [0, 1)
    // Outputs per packed ray (same padding).
    float *hit, *hitX, *hitY, *hitZ, *steps, *cause;
    // Outputs: lane slots issued and lanes active, summed over the steps.
    uint64_t laneSlots, laneActive;
    int8_t* key;  // marchSortKeys' output per ray
};

// The packing key of each of `count` rays in a row (pdf, ox .. dz; into key) by the camera's
// sx, sy (trace/march.cpp: the ray's bucket by its screen-space direction, 2 sector +
// (dir.z > 0)), or -1 where the pixel has no ray (pdf <= 0, a non-finite or zero direction or
// origin, an origin not in front of the camera). The inputs are read in whole lane groups:
// each must be readable up to count rounded up to a multiple of kMarchPad floats.
inline constexpr int kSortSectors = 64;
SSRT_DECLARE_KERNEL(void, marchSortKeys, (const MarchKernelArgs& args))
SSRT_DECLARE_KERNEL(void, marchLinearKernel, (MarchKernelArgs & args))
SSRT_DECLARE_KERNEL(void, marchDdaKernel, (MarchKernelArgs & args))
SSRT_DECLARE_KERNEL(void, marchHiZKernel, (MarchKernelArgs & args))

}  // namespace ssrt
