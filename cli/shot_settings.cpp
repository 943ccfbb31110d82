#include "cli/shot_settings.h"

#include <algorithm>
#include <stdexcept>

#include "core/suggest.h"
#include "renderer/quality.h"
#include "renderer/settings_fields.h"

namespace ssrt {

namespace {

const Field<RenderSettings>* shotField(const std::string& key) {
    for (const auto& f : kRenderFields)
        if (f.has(kFieldShot) && f.key == key) return &f;
    return nullptr;
}

// The value the JSON wrote, if the field takes it: integers written as integers, numbers
// finite and in range, booleans as true/false, choices by name.
bool valueOf(const FieldInfo& f, const ShotValue& v, double& out) {
    using Kind = ShotValue::Kind;
    switch (f.type) {
        case FieldType::Bool:
            if (v.kind != Kind::Bool) return false;
            out = v.number;
            return true;
        case FieldType::Int:
            if (v.kind != Kind::Integer || !f.accepts(v.number)) return false;
            out = v.number;
            return true;
        case FieldType::Float:
            if ((v.kind != Kind::Integer && v.kind != Kind::Number) || !f.accepts(v.number))
                return false;
            out = v.number;
            return true;
        case FieldType::Choice: {
            const int i = v.kind == Kind::String ? f.choiceIndex(v.text) : -1;
            out = i;
            return i >= 0;
        }
    }
    return false;
}

}  // namespace

std::vector<std::string> shotRenderKeyList() {
    std::vector<std::string> out;
    for (const auto& f : kRenderFields)
        if (f.has(kFieldShot)) out.emplace_back(f.key);
    for (const char* key : {"quality", "frames", "frame", "warmupFrames"}) out.emplace_back(key);
    return out;
}

std::string shotRenderKeys() {
    std::string out;
    for (const std::string& key : shotRenderKeyList())
        out.append(out.empty() ? "" : ", ").append(key);
    return out;
}

void applyShot(const Shot& shot, RenderSettings& s) {
    const auto fail = [&](const std::string& key, const std::string& problem) {
        throw ShotError(shot.file + ": render" + (key.empty() ? "" : "." + key) + ": " + problem);
    };
    const auto& settings = shot.render.settings;
    // Unknown keys first, as the parser reports them at every other level.
    for (const auto& [key, value] : settings)
        if (key != "quality" && !shotField(key))
            fail(key, "unknown key" + didYouMean(key, shotRenderKeyList()) +
                          " (expected one of: " + shotRenderKeys() + ")");
    // A preset first, then the keys given beside it.
    for (const auto& [key, value] : settings) {
        if (key != "quality") continue;
        const std::optional<Quality> q =
            value.kind == ShotValue::Kind::String ? parseQuality(value.text) : std::nullopt;
        if (!q) fail(key, "expected one of " + std::string(qualityList()));
        applyQuality(*q, s);
    }
    for (const auto& f : kRenderFields) {
        if (!f.has(kFieldShot)) continue;
        const auto it = std::find_if(settings.begin(), settings.end(),
                                     [&](const auto& kv) { return kv.first == f.key; });
        if (it == settings.end()) continue;
        double value = 0.0;
        if (!valueOf(f, it->second, value)) fail(it->first, "expected " + f.expected());
        f.set(s, value);
    }
    // What one field cannot say alone (the Hi-Z levels' order).
    try {
        s.validate();
    } catch (const std::invalid_argument& e) {
        fail("", e.what());
    }
}

}  // namespace ssrt
