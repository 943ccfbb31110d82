// A colour pyramid for the approximate ("mip") SSR resolve (trace/ssr_resolve.h), after
// HDRP's colour pyramid: level 0 is a copy of the frame's colour, each next level the 2x2 box
// average of the one before (sizes (w + 1) / 2 down to 1 x 1; on odd sizes the last column or
// row is averaged with itself). Scalar set-up code, one row per task: every pixel is the same
// four additions and one multiply whatever the thread count.
#pragma once

#include <array>
#include <vector>

#include "core/image.h"

namespace ssrt {

struct ColorPyramid {
    static constexpr int kMaxLevels = 16;       // 1 x 1 from 32768 pixels wide
    std::vector<std::array<PlaneF, 3>> levels;  // RGB planes, level 0 at full size

    int levelCount() const { return int(levels.size()); }
    int maxMip() const { return levelCount() - 1; }
};

// Fills `pyramid` from three planes of one size (reusing its memory when the size is
// unchanged); `threads` as parallelFor (0 = all cores). Throws std::invalid_argument on empty
// or mismatched planes.
void buildColorPyramid(const PlaneF* const rgb[3], ColorPyramid& pyramid, int threads);

}  // namespace ssrt
