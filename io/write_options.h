// What an image file holds and how it is compressed: the layer groups an EXR keeps (`ssrt
// render --layers`), its compression (--exr-compression) and the threads that compress it.
// Names here are the command line's.
#pragma once

#include <bitset>
#include <optional>
#include <string>
#include <string_view>

#include "renderer/frame.h"  // LayerGroup

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

// OpenEXR's lossless compressions only: PXR24, B44(A) and DWAA/B would round or drop the
// float bits that ids and view depth need (B44 leaves float channels as they are, so it
// would only be "none" under another name).
enum class ExrCompression { None, Rle, Zips, Zip, Piz };
// The default: the 1080p all-layers frame (42 layers, 348 MB of floats) on 2 cores takes
// 0.7 s of CPU with RLE for a file of 61 % of the raw size; ZIP and PIZ make 35 % but take
// 4.3 and 2.6 s, none 0.2 s for 100 % (perf/README.md, "Image output and start-up").
inline constexpr ExrCompression kDefaultExrCompression = ExrCompression::Rle;

std::string_view exrCompressionName(ExrCompression c);  // "none", "rle", "zips", "zip", "piz"
std::optional<ExrCompression> parseExrCompression(std::string_view name);
std::string exrCompressionList();  // "none, rle, zips, zip, piz"

struct WriteOptions {
    LayerGroups layers = allLayerGroups();  // EXR only: a PNG is always the display planes
    ExrCompression compression = kDefaultExrCompression;
    int threads = 0;  // threads compressing an EXR; 0: every core
};

}  // namespace ssrt
