// Quality presets (issue 17): each a named set of field-table values (renderer/
// settings_fields.h) applied over the defaults, which are the default preset's. A flag or
// shot key given beside a preset overrides its value.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "renderer/settings.h"

namespace ssrt {

enum class Quality { Low, Medium, High, Ultra };

inline constexpr Quality kDefaultQuality = Quality::Medium;
inline constexpr int kQualityCount = 4;

// "low", "medium", "high", "ultra".
std::string_view qualityName(Quality q);
std::optional<Quality> parseQuality(std::string_view name);
// "low, medium, high, ultra".
std::string_view qualityList();

// One setting of a preset: a field key and its value (a choice as its index).
struct PresetValue {
    std::string_view key;
    double value;
};
std::span<const PresetValue> qualityValues(Quality q);

// The preset's values written into `s` (the others left as they are).
void applyQuality(Quality q, RenderSettings& s);

}  // namespace ssrt
