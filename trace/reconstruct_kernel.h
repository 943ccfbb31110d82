// The reconstruction's kernel, one copy per ISA (trace/reconstruct_kernel.cpp); the
// method is in trace/reconstruct.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"

namespace ssrt {

// The signal planes, in this order; null where absent (colour: all three or none).
enum ReconstructPlane { kRecR, kRecG, kRecB, kRecOpacity, kRecHit, kRecDistance, kRecSteps, kRecN };

// Plain values and pointers only: this crosses into code compiled with other ISA flags.
struct ReconstructArgs {
    bool half;  // upsampleHalf (else fillCheckerboard)
    int width, height, tilesX;
    std::size_t stride;  // every full-resolution plane: guides, outputs, the checkerboard's pdf
    GBufferView g;       // the guides: viewZ, normal
    float scaleX, scaleY, tanHalfX,
        tanHalfY;          // pixel centre to view ray: (x + 0.5) scale - tanHalf
    float viewToWorld[9];  // column-major
    float invTolerance;    // 1 / kReconstructPlaneTolerance
    // Checkerboard: the full-resolution pdf (marks and traced samples); half: the half
    // frame's (traced samples), with its size and stride.
    const float* pdf;
    float cutMark;  // kPdfLayoutCut: the checkerboard's pixels to fill
    int srcWidth, srcHeight;
    std::size_t srcStride;
    const float* in[kRecN];  // half: the half frame's planes (srcStride); checkerboard: = out
    float* out[kRecN];
    // half: the outputs' stride and the frame pixel of their element (0, 0) (a tile's planes,
    // or the frame's: stride, 0, 0); the checkerboard fills the frame's in place.
    std::size_t outStride;
    int outX0, outY0;
    int offsetX, offsetY;  // half: the chosen pixel of each block
};

// Returns through `filled` the pixels the tile filled (checkerboard) or blended (half).
SSRT_DECLARE_KERNEL(void, reconstructTile,
                    (const ReconstructArgs& args, int tile, uint64_t& filled))

}  // namespace ssrt
