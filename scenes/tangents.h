// Tangent frames for normal maps (glTF 2.0 section 3.9.3): per-vertex tangents generated
// where a mesh has no TANGENT attribute, and the perturbed normal of a normal-map texel.
// Scalar code shared by the texture pass and the Embree truth, so both bend a normal by the
// same operations.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "scenes/scene.h"

namespace ssrt {

// Per-vertex tangents (xyz unit and orthogonal to the vertex normal, w = +-1) from the UV set
// `uvSet` (0: Mesh::uvs, 1: Mesh::uvs1), after Lengyel 2001, "Computing Tangent Space Basis
// Vectors for an Arbitrary Mesh": each triangle's dP/du and dP/dv, from its edges and UV
// differences, summed per vertex unnormalised (as Lengyel does), then Gram-Schmidt against
// the normal; w says whether the bitangent w cross(n, t) points along -dP/dv. (glTF's v runs
// down the image while a normal map's +Y is up the image, so glTF's bitangent is -dP/dv: a
// plain quad with u right and v down gets w = +1, as its TANGENT (1, 0, 0, 1) would say.)
//
// Where this differs from MikkTSpace, which the glTF specification recommends: MikkTSpace
// weights each corner by its angle and normalises the triangles' vectors first, and splits a
// vertex whose triangles disagree in handedness (mirrored UVs) into two; here such a vertex
// keeps the sum's direction and handedness. On meshes without mirrored UV seams the
// directions agree up to the weighting; a file that needs MikkTSpace's exact tangents should
// carry TANGENT.
//
// A vertex without usable UVs (no UV set, or degenerate triangles only) gets a tangent
// perpendicular to its normal, w = +1.
std::vector<glm::vec4> generateTangents(const Mesh& mesh, int uvSet);

// The mesh's tangents: Mesh::tangents when present, else generateTangents(mesh, uvSet).
std::vector<glm::vec4> meshTangents(const Mesh& mesh, int uvSet);

// A tangent through an instance's transform: xyz as a direction on the surface (the linear
// part, not the normal matrix), unit (zero if it vanishes); w turns over with a mirroring
// transform, under which the normal matrix turns cross(n, t) the other way.
glm::vec4 worldTangent(const glm::mat4& transform, glm::vec4 tangent);

// The world-space normal a normal-map texel gives (glTF 2.0 section 3.9.3):
//   m = normalize((2 texel.rgb - 1) (scale, scale, 1)),
//   t = normalize(tangent - n (n . tangent)), b = sign(w) cross(n, t),
//   normal = normalize(m.x t + m.y b + m.z n).
// `n` is the unit shading normal, `tangent` the interpolated tangent (xyz, not necessarily
// unit) and its handedness w (the sign is read: an interpolated w may lie between -1 and
// 1). Returns n where the tangent is parallel to it (no frame) or the result is not finite.
glm::vec3 perturbNormal(glm::vec3 n, glm::vec4 tangent, glm::vec3 texel, float scale);

}  // namespace ssrt
