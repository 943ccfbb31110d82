// The G-buffer resolve kernel, one copy per ISA (raster/resolve_kernel.cpp): for each pixel,
// the visible triangle's attributes from the view ray through the pixel centre.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/dispatch.h"
#include "core/gbuffer_view.h"

namespace ssrt {

// Per triangle, in view space: a point p0, the unit plane normal n with d = n.p0, and the
// gradients g1, g2 with barycentrics b1 = (h - p0).g1, b2 = (h - p0).g2 at a point h.
struct ResolveTriangle {
    float p0[3], n[3], d, g1[3], g2[3];
    uint32_t instance;
    uint32_t v[3];           // global vertex indices (world normals)
    uint32_t localTriangle;  // index within its mesh
};

// Per instance: material and the matrix from current view space to previous clip space.
struct ResolveInstance {
    float albedo[3], metallic, roughness, materialId;
    float viewToPrevClip[16];  // column-major
};

// With texturing on (ResolveArgs::u set), per UV set: u, v and their screen derivatives
// (per pixel, x right and y down), for the texture pass; named by ResolveUv.
enum ResolveUv : int { kUvU, kUvV, kUvDuDx, kUvDvDx, kUvDuDy, kUvDvDy, kResolveUvOutputs };
inline constexpr int kResolveUvSets = 2;  // TEXCOORD_0, and TEXCOORD_1 when u1 is set
// With normal maps (ResolveArgs::tangent set): the interpolated world tangent xyz (not unit)
// and its handedness w (between -1 and 1 where a triangle's vertices disagree), all four
// negated where the normal is (a back face seen), so the whole tangent frame turns over.
inline constexpr int kResolveTangentOutputs = 4;

// The G-buffer planes the resolve writes (the texture pass writes the material terms).
inline constexpr GBufferPlanes kResolvedPlanes =
    kGViewZ | kGNormal | kGAlbedo | kGMetallic | kGRoughness | kGMaterialId | kGMotion;

struct ResolveArgs {
    const ResolveTriangle* triangles;  // indexed by global triangle id
    const ResolveInstance* instances;
    const float* normalX;  // world normals per global vertex
    const float* normalY;
    const float* normalZ;
    const uint32_t* ids;
    std::size_t idStride;
    int width, height, tilesX;
    float tanHalfX, tanHalfY;  // view ray at NDC (x, y): (x tanHalfX, y tanHalfY, -1)
    float nearZ, farZ;
    // Texture coordinates per global vertex (zero for meshes without UVs), or null: then
    // no UV outputs are written.
    const float* u = nullptr;
    const float* v = nullptr;
    // The second set (TEXCOORD_1) likewise, or null: then only the first set's outputs.
    // Needs u.
    const float* u1 = nullptr;
    const float* v1 = nullptr;
    // World tangents per global vertex (x, y, z, w: Mesh::tangents through the instance's
    // transform; zero for instances without a normal map), or all null: then no tangent
    // outputs (a scene without normal maps gathers and writes nothing more).
    const float* tangent[4] = {};
    // Outputs, every one with outStride: the G-buffer (renderer/frame.h's GBuffer says what
    // each holds; background: viewZ 0, materialId -1, the rest 0) ...
    GBufferOf<float*> out;  // the planes of kResolvedPlanes
    // ... each UV set's outputs (set 0 with u, set 1 with u1; null otherwise) ...
    float* uv[kResolveUvSets][kResolveUvOutputs];
    // ... and the tangent frame x, y, z, w (with tangent; null otherwise).
    float* tangentFrame[kResolveTangentOutputs];
    std::size_t outStride;
};

SSRT_DECLARE_KERNEL(void, resolveTile, (const ResolveArgs& args, int tile))

}  // namespace ssrt
