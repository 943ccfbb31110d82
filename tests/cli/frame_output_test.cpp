// A frame into an image file (cli/options.h writeFrame): an EXR holds the layer groups asked
// for (--layers, chosen by renderer/layer_groups.h before io/ sees the planes), in the
// frame's order; a PNG is the display planes whatever the groups.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/options.h"
#include "io/image_io.h"
#include "renderer/layer_groups.h"
#include "temp_dir.h"

using namespace ssrt;
using test::TempDir;

namespace {

// A frame whose extra layers carry the given names (each a constant plane).
Frame namedFrame(int width, int height, const std::vector<std::string>& names) {
    Frame frame;
    frame.width = width;
    frame.height = height;
    for (std::size_t c = 0; c < names.size(); ++c)
        frame.extraLayers.push_back({names[c], PlaneF(width, height, 0.25f * float(c))});
    return frame;
}

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> sortedChannels(const std::string& path) {
    std::vector<std::string> names = readChannelNames(path);
    std::sort(names.begin(), names.end());
    return names;
}

LayerGroups only(LayerGroup g) { return LayerGroups().set(int(g)); }

}  // namespace

TEST_CASE("an EXR holds exactly the layer groups asked for, in the frame's order") {
    TempDir dir;
    const Frame frame =
        namedFrame(4, 3, {"color.R", "viewZ", "materialId", "ssr.R", "ref.color.R"});
    const LayerGroup groups[] = {LayerGroup::Color, LayerGroup::GBuffer, LayerGroup::GBuffer,
                                 LayerGroup::Trace, LayerGroup::Truth};
    std::vector<PlaneRef> layers;
    for (std::size_t i = 0; i < frame.extraLayers.size(); ++i)
        layers.push_back({frame.extraLayers[i].name, &frame.extraLayers[i].plane, groups[i]});
    const auto names = [](const std::vector<LayerRef>& chosen) {
        std::vector<std::string> out;
        for (const LayerRef& l : chosen) out.emplace_back(l.name);
        return out;
    };
    CHECK(names(chosenLayers(layers, only(LayerGroup::Color))) ==
          std::vector<std::string>{"color.R"});
    CHECK(names(chosenLayers(layers, only(LayerGroup::GBuffer))) ==
          std::vector<std::string>{"viewZ", "materialId"});
    CHECK(names(chosenLayers(layers, only(LayerGroup::Trace))) ==
          std::vector<std::string>{"ssr.R"});
    CHECK(names(chosenLayers(layers, only(LayerGroup::Truth) | only(LayerGroup::Color))) ==
          std::vector<std::string>{"color.R", "ref.color.R"});
    CHECK(chosenLayers(layers, allLayerGroups()).size() == 5);
    CHECK(chosenLayers(layers, LayerGroups()).empty());

    // Through the command line's writer: the extra layers are the truth group.
    const std::string path = dir.file("frame.exr");
    cli::FrameWriteOptions options;
    options.file = WriteOptions{ExrCompression::Zips, 1};
    options.layers = only(LayerGroup::Truth);
    cli::writeFrame(path, frame, options);
    CHECK(sortedChannels(path) ==
          std::vector<std::string>{"color.R", "materialId", "ref.color.R", "ssr.R", "viewZ"});
    // No chosen plane: refused, the file as it was.
    const std::string before = fileBytes(path);
    options.layers = only(LayerGroup::Color);
    CHECK_THROWS_WITH_AS(cli::writeFrame(path, frame, options), doctest::Contains("no planes"),
                         std::invalid_argument);
    CHECK(fileBytes(path) == before);
    // A PNG is the display planes whatever the groups.
    const Frame preview = namedFrame(2, 2, {"display.R", "display.G", "display.B"});
    cli::writeFrame(dir.file("preview.png"), preview, options);
    CHECK(readChannelNames(dir.file("preview.png")) == std::vector<std::string>{"R", "G", "B"});
}

TEST_CASE("layer groups are parsed by the names they print") {
    for (int g = 0; g < kLayerGroupCount; ++g)
        CHECK(parseLayerGroup(layerGroupName(LayerGroup(g))) == LayerGroup(g));
    CHECK(parseLayerGroup("colour") == LayerGroup::Color);
    CHECK_FALSE(parseLayerGroup("Color").has_value());
    CHECK_FALSE(parseLayerGroup("all").has_value());  // a word of the command line's list
    CHECK(layerGroupList() == "color, gbuffer, trace, truth");
}
