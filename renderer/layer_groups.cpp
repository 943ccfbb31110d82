#include "renderer/layer_groups.h"

namespace ssrt {

namespace {

constexpr std::string_view kGroupNames[kLayerGroupCount] = {"color", "gbuffer", "trace", "truth"};

}  // namespace

std::string_view layerGroupName(LayerGroup group) { return kGroupNames[int(group)]; }

std::string layerGroupList() {
    std::string out;
    for (int g = 0; g < kLayerGroupCount; ++g) out.append(g ? ", " : "").append(kGroupNames[g]);
    return out;
}

std::optional<LayerGroup> parseLayerGroup(std::string_view name) {
    if (name == "colour") return LayerGroup::Color;
    for (int g = 0; g < kLayerGroupCount; ++g)
        if (name == kGroupNames[g]) return LayerGroup(g);
    return std::nullopt;
}

std::vector<LayerRef> chosenLayers(const std::vector<PlaneRef>& layers, const LayerGroups& groups) {
    std::vector<LayerRef> out;
    for (const PlaneRef& p : layers)
        if (hasGroup(groups, p.group)) out.push_back({p.name, p.plane});
    return out;
}

ImageLayers frameLayers(const Frame& frame, const LayerGroups& groups) {
    return ImageLayers{frame.width, frame.height, chosenLayers(frame.layers(), groups), {}};
}

}  // namespace ssrt
