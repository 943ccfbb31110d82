// Which of a frame's layers an image file holds: the layer groups (`ssrt render --layers`)
// chosen here, on the renderer's side, so that io/ takes plain named layers (core/image.h)
// and never sees a Frame. Names here are the command line's.
#pragma once

#include <bitset>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"
#include "renderer/frame.h"

namespace ssrt {

// A set of LayerGroup, indexed by the enum's value.
using LayerGroups = std::bitset<kLayerGroupCount>;
inline LayerGroups allLayerGroups() { return LayerGroups().set(); }
inline bool hasGroup(const LayerGroups& groups, LayerGroup g) { return groups.test(int(g)); }

// "color", "gbuffer", "trace", "truth".
std::string_view layerGroupName(LayerGroup group);
// The group a name gives ("colour" is "color" too), or none.
std::optional<LayerGroup> parseLayerGroup(std::string_view name);
// "color, gbuffer, trace, truth" (for help and errors).
std::string layerGroupList();

// The layers of the chosen groups, in the order given, without their groups.
std::vector<LayerRef> chosenLayers(const std::vector<PlaneRef>& layers, const LayerGroups& groups);

// A frame as an image file takes it (io/image_io.h writeImage): its layers (Frame::layers())
// of the chosen groups, in the frame's order. The planes are borrowed from the frame.
ImageLayers frameLayers(const Frame& frame, const LayerGroups& groups = allLayerGroups());

}  // namespace ssrt
