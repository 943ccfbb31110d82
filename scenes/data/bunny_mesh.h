// The Stanford bunny as the npm package bunny@1.0.1 ships it (licence "Public Domain"):
// 1839 vertices, 3674 triangles, a closed surface, y up, in the package's units (about
// 9.66 tall, lowest point at y = -0.003149). The arrays live in bunny_mesh.cpp, which
// scripts/import-bunny.sh generates from the package; see its header for the provenance.
#pragma once

#include <cstdint>
#include <span>

namespace ssrt::data {

// x, y, z per vertex.
std::span<const float> bunnyPositions();

// Three vertex indices per triangle, counter-clockwise seen from outside (front faces).
std::span<const uint32_t> bunnyIndices();

}  // namespace ssrt::data
