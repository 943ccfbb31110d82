// The built-in scene "bunny": a scanned mesh, the Stanford bunny, on a glossy ground.
// Instances are found by their material's name (the tests rely on it): "bunny_ground",
// then "bunny".
#pragma once

#include "scenes/scene.h"

namespace ssrt {

inline constexpr const char* kBunnyDescription =
    "the Stanford bunny (a scan: 3.7k small, irregular triangles, closed, thin ears, "
    "self-occlusion) on a glossy ground; tests contact shadows and reflections";

// The Stanford bunny of scenes/data/bunny_mesh.h scaled to `height` (> 0), its lowest
// point on y = 0 and its bounds centred on the Y axis; area-weighted smooth normals, no UVs.
Mesh makeBunnyMesh(float height);

// A 1 m bunny standing on a glossy ground at y = 0, seen three-quarters from the front.
Scene makeBunnyScene();

}  // namespace ssrt
