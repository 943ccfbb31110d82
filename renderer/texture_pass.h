// The texture pass: after the resolve, multiplies the G-buffer's material factors by the
// textures of each pixel's material (base colour into albedo, metallic-roughness into
// metallic and roughness), bends its normal by the normal map, and writes the per-pixel
// emission and occlusion planes (frame.h, MaterialPlanes), each texture sampled trilinearly
// at the pixel's UV with its screen derivatives (scenes/texture.h has the conventions).
//
// Scalar code compiled once (not per ISA): the G-buffer it leaves is the same bits for
// every ISA and thread count, and pixels of untextured materials keep their G-buffer values.
#pragma once

#include "core/image.h"
#include "core/tiles.h"
#include "scenes/scene.h"

namespace ssrt {

struct TexturePlanes {
    // Per UV set: u, v, du/dx, dv/dx, du/dy, dv/dy (raster/resolve_kernel.h); set 1 only
    // when a material reads it.
    const PlaneF* uv[2][6] = {};
    const PlaneF* materialId = nullptr;
    PlaneF* albedo[3] = {};
    PlaneF* metallic = nullptr;
    PlaneF* roughness = nullptr;
    // With normal maps: the resolve's tangent frame (x, y, z, w) and the G-buffer normal it
    // bends (scenes/tangents.h, perturbNormal); all null otherwise.
    const PlaneF* tangent[4] = {};
    PlaneF* normal[3] = {};
    // Written for every pixel when set: emission (the material's factor times its emissive
    // texel, 0 on background) and occlusion (1 + strength (R - 1), 1 without a texture and
    // on background).
    PlaneF* emission[3] = {};
    PlaneF* occlusion = nullptr;
};

// One tile of the pass (the frame scheduler runs it with the resolve and the shading,
// renderer/frame_scheduler.h).
void applyTexturesTile(const Scene& scene, const TexturePlanes& planes, const TileGrid& grid,
                       int tile);

}  // namespace ssrt
