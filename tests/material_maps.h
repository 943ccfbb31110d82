// Normal, occlusion and emissive textures for the tests' scenes: small maps (4x4 texels, so
// the views magnify them and the raster's trilinear lookup reads level 0 like the truth) with
// a different value in every texel, given to every material; every other mesh carries its
// tangents as an attribute (the generated ones), the rest have them generated.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "scenes/scene.h"
#include "scenes/tangents.h"

namespace ssrt::test {

inline void addMaterialMaps(Scene& scene) {
    std::vector<glm::vec4> normal, occlusion, emissive;
    for (int i = 0; i < 16; ++i) {
        const float a = float(i % 4) / 3.0f, b = float(i / 4) / 3.0f;
        // Tilts up to about 35 degrees each way, never below the surface.
        normal.emplace_back(0.3f + 0.4f * a, 0.7f - 0.4f * b, 0.9f, 1.0f);
        occlusion.emplace_back(0.2f + 0.8f * float((i * 7) % 16) / 15.0f, 0.0f, 0.0f, 1.0f);
        emissive.emplace_back(a, b, 1.0f - a, 1.0f);
    }
    const int32_t first = int32_t(scene.textures.size());
    scene.textures.emplace_back("normal", 4, 4, normal);
    scene.textures.emplace_back("occlusion", 4, 4, occlusion);
    scene.textures.emplace_back("emissive", 4, 4, emissive);
    for (std::size_t k = 0; k < scene.materials.size(); ++k) {
        Material& m = scene.materials[k];
        m.normalTexture = first;
        m.normalScale = 0.8f;
        m.occlusionTexture = first + 1;
        m.occlusionStrength = 0.9f;
        m.emissiveTexture = first + 2;
        if (k % 2 == 0) m.emissive = glm::vec3(0.6f, 0.4f, 0.2f);
        m.emissiveUv.offset = {0.25f, 0.0f};
    }
    for (std::size_t k = 0; k < scene.meshes.size(); k += 2)
        scene.meshes[k].tangents = generateTangents(scene.meshes[k], 0);
}

}  // namespace ssrt::test
