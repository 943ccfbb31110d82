// The renderer tests' quad that fills the view exactly: a camera at the origin looking down
// -Z with a 90-degree field of view, and a quad at z = -2 whose UV (0, 0) is the image's
// top-left corner and (1, 1) its bottom-right (u along +x, v along -y), normal +z.
#pragma once

#include "scenes/scene.h"

namespace ssrt::test {

inline Mesh screenQuadMesh() {
    Mesh quad;
    quad.positions = {{-2, 2, -2}, {-2, -2, -2}, {2, -2, -2}, {2, 2, -2}};
    quad.normals.assign(4, {0, 0, 1});
    quad.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    return quad;
}

inline Camera screenQuadCamera() {
    Camera c;
    c.position = {0, 0, 0};
    c.target = {0, 0, -1};
    c.fovY = 90.0f;
    return c;
}

// The quad in `material`, seen by that camera (still).
inline Scene screenQuadScene(const Material& material) {
    Scene s;
    s.meshes.push_back(screenQuadMesh());
    s.materials.push_back(material);
    s.instances.push_back(Instance{});
    s.camera = s.previousCamera = screenQuadCamera();
    return s;
}

}  // namespace ssrt::test
