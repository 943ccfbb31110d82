// The G-buffer as a kernel reads it (renderer/frame.h's GBuffer names and fills the planes):
// each plane's first row and the one stride they share. Plain pointers only: it crosses into
// code compiled per ISA. Planes a kernel does not read may be null.
#pragma once

#include <cstddef>

namespace ssrt {

template <class F>
struct GBufferRowsOf {
    F* viewZ = nullptr;  // positive view-space depth; 0 on background
    F* normal[3] = {};   // world space, unit
    F* albedo[3] = {};   // base colour (linear)
    F* metallic = nullptr;
    F* roughness = nullptr;  // perceptual
    F* materialId = nullptr;
    F* motion[2] = {};  // previous minus current position, pixels
    std::size_t stride = 0;
};
using GBufferRows = GBufferRowsOf<const float>;

}  // namespace ssrt
