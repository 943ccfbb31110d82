// Counters a user profiling the rasterizer wants, per pass.
#pragma once

#include <cstdint>

namespace ssrt {

struct RasterStats {
    uint64_t trianglesIn = 0;       // submitted
    uint64_t trianglesInvalid = 0;  // NaN/infinite vertices or zero area: skipped
    uint64_t trianglesCulled = 0;   // back faces (materials that are not double-sided)
    uint64_t trianglesOutside = 0;  // wholly off screen, behind the camera or past far
    uint64_t trianglesClipped = 0;  // crossed the near plane or guard band and were split
    uint64_t trianglesSetUp = 0;    // screen triangles after clipping, sent to binning
    uint64_t trianglesMasked = 0;   // set up with a per-pixel alpha test (MASK, BLEND)
    uint64_t trianglesCutOut = 0;   // never drawn: MASK/BLEND without a texture, whose
                                    // alpha is below the cutoff
    uint64_t binEntries = 0;        // (triangle, tile) pairs
    uint64_t blocksRejected = 0;    // 8x8 blocks found wholly outside
    uint64_t blocksAccepted = 0;    // 8x8 blocks found wholly inside (no edge tests)
    uint64_t blocksPartial = 0;     // 8x8 blocks tested per pixel
    uint64_t pixelsTested = 0;      // on-screen lanes evaluated (depends on SIMD width;
                                    // every other counter is the same on every ISA)
    uint64_t pixelsCovered = 0;     // inside the triangle
    uint64_t pixelsWritten = 0;     // passed the depth test (and the alpha test)
    uint64_t pixelsCutOut = 0;      // passed the depth test, failed the alpha test

    RasterStats& operator+=(const RasterStats& o);
};

inline RasterStats& RasterStats::operator+=(const RasterStats& o) {
    trianglesIn += o.trianglesIn;
    trianglesInvalid += o.trianglesInvalid;
    trianglesCulled += o.trianglesCulled;
    trianglesOutside += o.trianglesOutside;
    trianglesClipped += o.trianglesClipped;
    trianglesSetUp += o.trianglesSetUp;
    trianglesMasked += o.trianglesMasked;
    trianglesCutOut += o.trianglesCutOut;
    binEntries += o.binEntries;
    blocksRejected += o.blocksRejected;
    blocksAccepted += o.blocksAccepted;
    blocksPartial += o.blocksPartial;
    pixelsTested += o.pixelsTested;
    pixelsCovered += o.pixelsCovered;
    pixelsWritten += o.pixelsWritten;
    pixelsCutOut += o.pixelsCutOut;
    return *this;
}

}  // namespace ssrt
