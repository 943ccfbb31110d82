// The G-buffer resolve's per-frame tables: per-triangle ray-plane and barycentric set-up in
// view space, per-instance material and motion, per-vertex world normals (and UVs for
// textured scenes), as raster/resolve_kernel.h reads them.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "raster/resolve_kernel.h"
#include "scenes/scene.h"

namespace ssrt {

// Per-triangle ray-plane and barycentric set-up in view space, and world-space normals per
// vertex, for the resolve kernel.
struct ResolveTables {
    std::vector<ResolveTriangle> triangles;
    std::vector<ResolveInstance> instances;
    std::vector<float> nx, ny, nz;
    // View-space positions per vertex (the corners ResolveTriangle::v names): the proof of a
    // screen hit meets the triangle itself (trace/hit_proof.h)
    std::vector<glm::vec3> viewPositions;
    std::vector<float> u, v;    // texture coordinates per vertex, only for textured scenes
    std::vector<float> u1, v1;  // the second set, only when a material reads it
    // World tangents (x, y, z, w) per vertex, only when a material has a normal map (zero
    // for the instances of other materials)
    std::vector<float> tangent[4];
};

bool anyTextured(const Scene& scene);
bool anyUvSet1(const Scene& scene);  // a material's texture reads the second UV set
bool anyNormalMapped(const Scene& scene);
bool anyOcclusionTextured(const Scene& scene);
bool anyEmissiveTextured(const Scene& scene);

// `view` is the camera's, `prevViewProj` the previous camera's (motion vectors), both of
// points measured from `origin` (Scene::origin(); Camera::viewFrom).
ResolveTables buildResolveTables(const Scene& scene, glm::vec3 origin, const glm::mat4& view,
                                 const glm::mat4& prevViewProj, bool textured, int threads);

}  // namespace ssrt
