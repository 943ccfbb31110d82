// The texture pass: after the resolve, multiplies the G-buffer's material factors by the
// textures of each pixel's material (base colour into albedo, metallic-roughness into
// metallic and roughness), bends its normal by the normal map, and writes the per-pixel
// emission and occlusion planes (frame.h, GBuffer), each texture sampled trilinearly
// at the pixel's UV with its screen derivatives (scenes/texture.h has the conventions).
//
// Scalar code compiled once (not per ISA): the G-buffer it leaves is the same bits for
// every ISA and thread count, and pixels of untextured materials keep their G-buffer values.
#pragma once

#include "core/tiles.h"
#include "renderer/frame.h"
#include "scenes/scene.h"

namespace ssrt {

// One tile of the pass (the frame scheduler runs it with the resolve and the shading,
// renderer/frame_scheduler.h). It reads the resolve's UV planes (Frame::Scratch::uv; set 1
// only where a material reads it) and, with normal maps, its tangent frame; it writes the
// G-buffer's albedo, metallic, roughness and normal in place, and the material planes the
// frame holds (emission: the material's factor times its emissive texel, 0 on background;
// occlusion: 1 + strength (R - 1), 1 without a texture and on background).
void applyTexturesTile(const Scene& scene, Frame& frame, const TileGrid& grid, int tile);

}  // namespace ssrt
