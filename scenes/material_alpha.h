// Alpha cut-outs (glTF 2.0 alphaMode MASK, and BLEND drawn as MASK): whether a point of a
// surface is drawn. One rule for the rasterizer's visibility and shadow passes
// (raster/alpha_test.h) and the Embree truth's filter (truth/embree_scene.cpp), so the
// reference rays pass through the very holes the frame shows.
//
// alpha = Material::baseColorAlpha * the base colour texture's alpha, sampled at level 0,
// bilinearly, at the point's UV (the set Material::baseColorUv names, through its UV
// transform). The point is drawn when alpha >= alphaCutoff (glTF: "greater than or equal
// to ... fully opaque, otherwise ... fully transparent").
//
// Why level 0 and not a screen-space level of detail: the truth has no pixel footprint (it
// samples every texture at level 0), the shadow map's texels are not the camera's pixels,
// and a mip level averages alpha, so cut-outs seen from afar would thin out or fill in
// (Castano 2010, "Computing Alpha Mipmaps"): level 0 keeps each sample's coverage exact and
// the three passes in agreement, at the price of aliasing where the texture is minified.
#pragma once

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace ssrt {

// What a material's alpha does to its triangles as a whole.
enum class AlphaCoverage {
    Opaque,     // drawn everywhere: OPAQUE, or MASK/BLEND without a texture whose factor passes
    PerPoint,   // MASK/BLEND with a base colour texture: tested at every point
    Invisible,  // drawn nowhere: MASK/BLEND without a texture whose factor fails
};

AlphaCoverage alphaCoverage(const Material& m);

// The material's alpha at `uv`, the mesh's UV in the set the base colour reads (before the
// UV transform); the factor alone without a texture.
float materialAlpha(const Scene& scene, const Material& m, glm::vec2 uv);

// Whether a point at `uv` is drawn: always for OPAQUE, else alpha >= alphaCutoff.
bool alphaPasses(const Scene& scene, const Material& m, glm::vec2 uv);

}  // namespace ssrt
