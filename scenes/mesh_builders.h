// Procedural meshes for the built-in scenes and tests. Every builder returns unit normals,
// counter-clockwise front faces seen from outside, and UVs in [0, 1]. Degenerate inputs
// (too few segments, sizes that are not positive) throw std::invalid_argument.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "scenes/scene.h"

namespace ssrt {

// An axis-aligned box centred on the origin: 24 vertices (flat normals), 12 triangles.
Mesh makeBox(glm::vec3 halfExtents);

// A square grid in the XZ plane facing +Y, centred on the origin, subdivisions >= 1 cells
// along each side (2 * subdivisions^2 triangles).
Mesh makeQuad(glm::vec2 halfSize, int subdivisions);

// A latitude-longitude sphere centred on the origin; segments >= 3 around Y, rings >= 2
// from pole to pole. Normals are the normalized positions; no degenerate pole triangles,
// so it has 2 * segments * (rings - 1) triangles.
Mesh makeUvSphere(float radius, int segments, int rings);

// A tube of radius `tube` around the (p, q) torus knot: the curve winds p times around the
// Y axis and q times through the torus hole. `radius` is the distance from the centre to
// the torus core circle; the curve stays within radius / 2 of that circle. segments >= 3
// along the curve, sides >= 3 around the tube: 2 * segments * sides triangles.
Mesh makeTorusKnot(int p, int q, float radius, float tube, int segments, int sides);

// Smooth vertex normals for an indexed mesh: each vertex gets the unit sum of its
// triangles' face normals weighted by area (for meshes that come without normals, such as
// scans and glTF files). A vertex that no triangle of non-zero area uses gets +Y.
std::vector<glm::vec3> smoothNormals(const Mesh& mesh);

}  // namespace ssrt
