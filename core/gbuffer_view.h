// The G-buffer as passes and kernels read it: each plane's first row, the one stride the
// planes share and their size (renderer/frame.h's GBuffer names and owns the full frame's
// planes, trace/trace_layout.h's HalfFrame the half frame's). Plain data only: it crosses
// into code compiled per ISA.
//
// A view is made in one place, gbufferView, which checks every plane it is given (of the
// size asked, so one stride serves them all); a pass then states the planes it reads with
// requireGBuffer. Both throw std::invalid_argument naming the pass and the plane.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string_view>

#include "core/image.h"

namespace ssrt {

struct GBufferView {
    const float* viewZ = nullptr;  // positive view-space depth; 0 on background
    const float* normal[3] = {};   // world space, unit
    const float* albedo[3] = {};   // base colour (linear)
    const float* metallic = nullptr;
    const float* roughness = nullptr;  // perceptual
    const float* materialId = nullptr;
    const float* motion[2] = {};  // previous minus current position, pixels
    std::size_t stride = 0;
    int width = 0, height = 0;
};

// The planes of a view, one bit each (a set: GBufferPlanes), in GBufferView's order.
enum GBufferPlane : unsigned {
    kGViewZ = 1u << 0,
    kGNormalX = 1u << 1,
    kGNormalY = 1u << 2,
    kGNormalZ = 1u << 3,
    kGAlbedoR = 1u << 4,
    kGAlbedoG = 1u << 5,
    kGAlbedoB = 1u << 6,
    kGMetallic = 1u << 7,
    kGRoughness = 1u << 8,
    kGMaterialId = 1u << 9,
    kGMotionX = 1u << 10,
    kGMotionY = 1u << 11,
};
using GBufferPlanes = unsigned;
inline constexpr int kGBufferPlaneCount = 12;
inline constexpr GBufferPlanes kGNormal = kGNormalX | kGNormalY | kGNormalZ;
inline constexpr GBufferPlanes kGAlbedo = kGAlbedoR | kGAlbedoG | kGAlbedoB;
inline constexpr GBufferPlanes kGMotion = kGMotionX | kGMotionY;

// One plane given to gbufferView: which it is, and the plane (null: absent).
struct GBufferSlot {
    GBufferPlane which;
    const PlaneF* plane;
};

// The view of `planes`, each of width x height (an empty or null plane is left out), every
// plane in `need` present; else std::invalid_argument naming `pass` and the plane.
GBufferView gbufferView(std::string_view pass, int width, int height, const GBufferSlot* planes,
                        std::size_t count, GBufferPlanes need = 0);
inline GBufferView gbufferView(std::string_view pass, int width, int height,
                               std::initializer_list<GBufferSlot> planes, GBufferPlanes need = 0) {
    return gbufferView(pass, width, height, planes.begin(), planes.size(), need);
}

// A pass's check of the view it was handed: of width x height, with every plane in `need`;
// else std::invalid_argument naming `pass` and the plane.
void requireGBuffer(std::string_view pass, const GBufferView& g, GBufferPlanes need, int width,
                    int height);

// The plane's name in messages ("viewZ", "normal.X", ...): its channel's name in the frame's
// resource table (renderer/resources.cpp).
std::string_view gbufferPlaneName(GBufferPlane which);
// The plane of that name, or 0 for a name that is none of them: an owner that names its planes
// so (renderer/frame.h's GBuffer) makes its view from its own table.
unsigned gbufferPlaneNamed(std::string_view name);

}  // namespace ssrt
