// glTF cameras placed by their node's world matrix, and what the placement drops (part of
// ssrt_gltf).
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ssrt::gltf {

// What placing a camera reinterpreted, for the loader's warnings.
struct CameraPlacement {
    float scale = 1.0f;         // the world matrix's scale along the view axis, applied to near/far
    bool uneven = false;        // scales unevenly or shears: the view was orthonormalised
    bool mirrored = false;      // the world matrix mirrors: ignored (the image is not flipped)
    bool degenerate = false;    // no view direction or up can be taken from it
    std::size_t beyondFar = 0;  // triangles it cannot see for its far plane (trianglesBeyondFar)
};

// The camera of a perspective glTF camera (yfov in radians, znear > 0, zfar 0 for infinite)
// at a node whose world matrix is `world`. glTF 2.0 (3.10.1, "Cameras") derives the view
// from that matrix "with the scaling ignored", which leaves znear and zfar in world units; a
// viewer that uses the inverse of the whole world matrix as its view (three.js, for one)
// measures them in the node's own units instead. ssrt takes the position and an orthonormal
// orientation from the matrix (looking along its -Z, its +Y orthogonalised for up) and scales
// znear and zfar by the matrix's scale along the view axis, as those viewers do: a file
// wrapped in a node that scales it, camera included, then shows the same image at any scale.
// The loader warns of each of these departures from the letter of glTF (CameraPlacement).
Camera placeCamera(const glm::mat4& world, double yfov, double znear, double zfar,
                   CameraPlacement& placement);

// Triangles (over every instance) whose three corners lie beyond the scene camera's far
// plane: the rasterizer draws none of them, and every pass and the truth leave them off screen.
std::size_t trianglesBeyondFar(const Scene& scene);

// One line for each thing `placement` reinterpreted or drops (the file's znear and zfar, zfar
// 0 for infinite; the scene with the camera placed), without the camera's name.
std::vector<std::string> placementWarnings(const CameraPlacement& placement, double znear,
                                           double zfar, const Scene& scene);

}  // namespace ssrt::gltf
