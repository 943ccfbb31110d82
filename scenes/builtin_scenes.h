// Built-in scenes, each a few lines to build.
#pragma once

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ssrt {

struct BuiltinSceneInfo {
    std::string name;
    std::string description;  // one line: what it shows and what it tests
};

// Every built-in scene, the default ("cornell") first.
const std::vector<BuiltinSceneInfo>& builtinScenes();

// Builds the named scene; throws std::invalid_argument naming the scene and listing the
// known ones when the name is unknown.
Scene makeBuiltinScene(const std::string& name);

// A benchmark scene: a torus knot of about `triangles` triangles on a ground plane, lit by
// the directional light (perf/ uses it at 3.7k and 121k triangles).
Scene makeKnotScene(int triangles);

}  // namespace ssrt
