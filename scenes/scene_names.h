// The names a scene request may use, for the shot parser and the command line alike: a
// built-in scene (scenes/builtin_scenes.h) or a glTF file.
#pragma once

#include <string>
#include <vector>

namespace ssrt {

// A name that is a glTF file rather than a built-in scene: it ends in .gltf or .glb (any case).
bool isSceneFile(const std::string& name);
// Whether a built-in scene has this name.
bool isBuiltinScene(const std::string& name);
// The built-in scenes' names, comma-separated ("cornell, spheres, ...").
std::string knownScenes();
// The same, one name each.
std::vector<std::string> knownSceneNames();

}  // namespace ssrt
