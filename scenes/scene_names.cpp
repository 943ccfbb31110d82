#include "scenes/scene_names.h"

#include <algorithm>
#include <cctype>

#include "scenes/builtin_scenes.h"

namespace ssrt {

bool isSceneFile(const std::string& name) {
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    const auto endsWith = [&](const std::string& ext) {
        return lower.size() > ext.size() &&
               lower.compare(lower.size() - ext.size(), ext.size(), ext) == 0;
    };
    return endsWith(".gltf") || endsWith(".glb");
}

bool isBuiltinScene(const std::string& name) {
    const auto& scenes = builtinScenes();
    return std::any_of(scenes.begin(), scenes.end(), [&](const auto& s) { return s.name == name; });
}

std::string knownScenes() {
    std::string out;
    for (const std::string& name : knownSceneNames()) out += (out.empty() ? "" : ", ") + name;
    return out;
}

std::vector<std::string> knownSceneNames() {
    std::vector<std::string> out;
    for (const auto& s : builtinScenes()) out.push_back(s.name);
    return out;
}

}  // namespace ssrt
