#include "cli/json_output.h"

#include <cctype>
#include <ostream>

#include "scenes/builtin_scenes.h"

namespace ssrt::cli {

void printJson(std::ostream& out, const Json& document) {
    // (nlohmann-json writes a NaN or infinity as null by itself; the indent keeps a diff of two
    // runs' documents readable line by line.)
    out << document.dump(2) << "\n";
}

std::string jsonKey(std::string_view label) {
    std::string key;
    bool gap = false;  // characters between words since the last one kept
    for (const char c : label) {
        const auto u = static_cast<unsigned char>(c);
        const bool word = std::isalnum(u) || c == '%';
        if (!word) {
            gap = true;
            continue;
        }
        if (gap && !key.empty()) key.push_back('_');
        gap = c == '%';  // "percent" is a word of its own
        if (c == '%') key.append("percent");
        else key.push_back(char(std::tolower(u)));
    }
    return key;
}

Json imageErrorJson(const ImageError& error) {
    return {{"rel_mse", error.relMse}, {"rmse", error.rmse}, {"non_finite", error.nonFinite}};
}

Json errorTableJson(const ErrorTable& table) {
    Json out = {{"color", imageErrorJson(table.color)}};
    if (table.parts) {
        out["direct"] = imageErrorJson(table.direct);
        out["specular"] = imageErrorJson(table.specular);
        out["diffuse"] = imageErrorJson(table.diffuse);
    }
    return out;
}

Json layerDiffJson(const LayerDiff& layer, const DiffThresholds& limits) {
    std::string why;
    const bool passed = withinThresholds(layer, limits, &why);
    return {{"channels", layer.channels},
            {"present", layer.presence == LayerDiff::Presence::Both},
            {"identical", layer.identical},
            {"passed", passed},
            {"why", why},
            {"max_error", layer.maxError},
            {"max_at", Json::array({layer.maxX, layer.maxY, layer.maxChannel})},
            {"rel_mse", layer.relMse},
            {"non_finite", layer.nonFinite},
            {"pixels_over", layer.pixelsOver},
            {"share_over", layer.shareOver}};
}

Json imageDiffJson(const ImageDiff& diff, const DiffThresholds& limits) {
    Json layers = Json::object();
    bool passed = true;
    for (const LayerDiff& l : diff.layers) {
        Json layer = layerDiffJson(l, limits);
        passed = passed && layer["passed"].get<bool>();
        layers[l.name] = std::move(layer);
    }
    return {{"width", diff.width},
            {"height", diff.height},
            {"identical", diff.identical()},
            {"passed", passed},
            {"layers", std::move(layers)}};
}

Json builtinScenesJson() {
    Json scenes = Json::object();
    for (const BuiltinSceneInfo& s : builtinScenes()) scenes[s.name] = s.description;
    return scenes;
}

}  // namespace ssrt::cli
