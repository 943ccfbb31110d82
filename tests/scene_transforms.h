// A built-in scene in another unit or far from 0 (issue 16's scale-invariance tests): every
// instance (and its previous pose) and both cameras through a similarity, the cameras' near
// and far planes scaled with it.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "scenes/builtin_scenes.h"

namespace ssrt::test {

inline void transformScene(Scene& scene, const glm::mat4& m, float scale) {
    for (Instance& inst : scene.instances) {
        inst.transform = m * inst.transform;
        inst.previousTransform = m * inst.previousTransform;
    }
    for (Camera* cam : {&scene.camera, &scene.previousCamera}) {
        cam->position = glm::vec3(m * glm::vec4(cam->position, 1.0f));
        cam->target = glm::vec3(m * glm::vec4(cam->target, 1.0f));
        cam->nearZ *= scale;
        cam->farZ *= scale;
    }
}

inline Scene scaledScene(const std::string& name, float s) {
    Scene scene = makeBuiltinScene(name);
    transformScene(scene, glm::scale(glm::mat4(1.0f), glm::vec3(s)), s);
    return scene;
}

// The offset of the moved-scene tests: 1e4 units along each axis (exact in float).
inline const glm::vec3 kFarOffset(1e4f, -1e4f, 1e4f);

inline Scene movedScene(const std::string& name, glm::vec3 offset = kFarOffset) {
    Scene scene = makeBuiltinScene(name);
    transformScene(scene, glm::translate(glm::mat4(1.0f), offset), 1.0f);
    return scene;
}

// movedScene brought back by -offset exactly (in double): the scene as the move left it
// (each translation rounded to the float spacing at 1e4, about 1e-3), at the origin. The
// moved scene's image must match this one; the difference from the unmoved scene is the
// input's own rounding, which no renderer can undo.
inline Scene movedBack(const Scene& moved, glm::vec3 offset = kFarOffset) {
    Scene scene = moved;
    const glm::dvec3 o(offset);
    for (Instance& inst : scene.instances) {
        inst.transform = transformFrom(inst.transform, offset);
        inst.previousTransform = transformFrom(inst.previousTransform, offset);
    }
    for (Camera* cam : {&scene.camera, &scene.previousCamera}) {
        cam->position = glm::vec3(glm::dvec3(cam->position) - o);
        cam->target = glm::vec3(glm::dvec3(cam->target) - o);
    }
    return scene;
}

}  // namespace ssrt::test
