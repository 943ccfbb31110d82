// The G-buffer as a kernel reads it (renderer/frame.h's GBuffer names and fills the planes):
// each plane's first row and the one stride they share. Plain pointers only: it crosses into
// code compiled per ISA. Planes a kernel does not read may be null.
#pragma once

#include <cstddef>

namespace ssrt {

struct GBufferRows {
    const float* viewZ = nullptr;  // positive view-space depth; 0 on background
    const float* normal[3] = {};   // world space, unit
    const float* albedo[3] = {};   // base colour (linear)
    const float* metallic = nullptr;
    const float* roughness = nullptr;  // perceptual
    const float* materialId = nullptr;
    const float* motion[2] = {};  // previous minus current position, pixels
    std::size_t stride = 0;
};

}  // namespace ssrt
