// Quality presets: named sets of field values; the defaults are the default preset's, every
// preset sets the same keys, and the CLI and shot files take them with flags overriding.
#include "renderer/quality.h"

#include <doctest/doctest.h>

#include <set>
#include <string>

#include "cli/render_command.h"
#include "cli/shot_settings.h"
#include "renderer/settings_fields.h"
#include "scenes/shot.h"

using namespace ssrt;

namespace {

// Every field's value, in table order.
std::vector<double> values(const RenderSettings& s) {
    std::vector<double> v;
    for (const auto& f : kRenderFields) v.push_back(f.get(s));
    return v;
}

}  // namespace

TEST_CASE("quality: the defaults are the default preset's, and the presets differ") {
    const RenderSettings d;
    RenderSettings s = d;
    applyQuality(kDefaultQuality, s);
    CHECK(values(s) == values(d));
    std::set<std::vector<double>> seen;
    for (int i = 0; i < kQualityCount; ++i) {
        const Quality q = Quality(i);
        CAPTURE(std::string(qualityName(q)));
        CHECK(parseQuality(qualityName(q)) == q);
        RenderSettings p = d;
        applyQuality(q, p);
        p.validate();
        seen.insert(values(p));
    }
    CHECK(seen.size() == std::size_t(kQualityCount));
    CHECK(!parseQuality("extreme"));
    // Ultra traces every pixel (as before the presets); the others cut.
    RenderSettings ultra;
    applyQuality(Quality::Ultra, ultra);
    CHECK(ultra.trace.ssrLayout == TraceLayout::Full);
    CHECK(ultra.trace.ssgiLayout == TraceLayout::Full);
    CHECK(d.trace.ssgiLayout == TraceLayout::Half);
}

TEST_CASE(
    "quality: every preset sets the same keys, so one applied after another leaves no trace") {
    std::set<std::string_view> keys;
    for (const PresetValue& v : qualityValues(Quality::Ultra)) keys.insert(v.key);
    for (int i = 0; i < kQualityCount; ++i) {
        std::set<std::string_view> k;
        for (const PresetValue& v : qualityValues(Quality(i))) k.insert(v.key);
        CHECK(k == keys);
        RenderSettings a, b;
        applyQuality(Quality::Low, a);
        applyQuality(Quality(i), a);
        applyQuality(Quality(i), b);
        CHECK(values(a) == values(b));
    }
}

TEST_CASE("quality: --quality and the shot key set a preset, and fields beside it override") {
    cli::RenderOptions o;
    o.quality = "ultra";
    o.settings["ssgiLayout"] = "checkerboard";
    const RenderSettings s = cli::settingsFrom(o);
    CHECK(s.trace.ssrLayout == TraceLayout::Full);
    CHECK(s.trace.ssgiLayout == TraceLayout::Checkerboard);
    o.quality = "extreme";
    CHECK_THROWS_WITH_AS(cli::settingsFrom(o), doctest::Contains("--quality: 'extreme'"),
                         std::invalid_argument);

    const Shot shot = parseShot(R"({"render": {"quality": "low", "maxSteps": 100}})", "shot.json");
    RenderSettings fromShot;
    applyShot(shot, fromShot);
    CHECK(fromShot.trace.march.maxSteps == 100);
    CHECK(fromShot.trace.ssgiLayout == TraceLayout::Half);
    const Shot bad = parseShot(R"({"render": {"quality": 3}})", "shot.json");
    RenderSettings unused;
    CHECK_THROWS_WITH_AS(applyShot(bad, unused),
                         doctest::Contains("render.quality: expected one of"), ShotError);
}
