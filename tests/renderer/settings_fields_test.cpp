// The settings' field tables (renderer/settings_fields.h, trace/march_fields.h): every field
// round-trips through the command line, a shot file and the reference cache key (which it
// changes exactly when the table says it shapes the reference), validate() refuses its
// values out of range by name, and each table covers every member of its struct.
#include "renderer/settings_fields.h"

#include <doctest/doctest.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "cli/options.h"
#include "cli/shot_settings.h"
#include "scenes/builtin_scenes.h"
#include "truth/reference_image.h"

using namespace ssrt;

namespace {

// The defaults, with room for both Hi-Z levels to move (start >= most detailed).
RenderSettings testBase() {
    RenderSettings s;
    s.trace.march.hizStartLevel = 4;
    return s;
}

// A value of `f` in its range other than `d`.
double otherValue(const FieldInfo& f, double d) {
    switch (f.type) {
        case FieldType::Bool: return d != 0.0 ? 0.0 : 1.0;
        case FieldType::Choice: return double((int(d) + 1) % f.choiceCount);
        case FieldType::Int: return d + 1 <= f.range.hi ? d + 1 : d - 1;
        case FieldType::Float: {
            const double hi = f.range.hi == kFieldFloatMax ? 2 * d + 1 : f.range.hi;
            return double(float(d < hi ? (d + hi) / 2 : (f.range.lo + d) / 2));
        }
    }
    return d;
}

// The value as a JSON literal.
std::string json(const FieldInfo& f, double v) {
    return f.type == FieldType::Choice ? "\"" + f.text(v) + "\"" : f.text(v);
}

RenderSettings viaCli(std::vector<std::string> args, const RenderSettings& base) {
    CLI::App app;
    cli::RenderOptions options;
    cli::addRenderCommand(app, options);
    args.insert(args.begin(), "render");
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    app.parse(args);
    return cli::settingsFrom(options, base);
}

RenderSettings viaShot(const std::string& text, const RenderSettings& base) {
    RenderSettings s = base;
    applyShot(parseShot(text, "fields.json"), s);
    return s;
}

// Every field of `s` as in `base` but `changed`, which holds `value`.
void checkOnly(const RenderSettings& s, const RenderSettings& base,
               const Field<RenderSettings>& changed, double value) {
    for (const auto& g : kRenderFields) {
        CAPTURE(g.key);
        CHECK(g.get(s) == (&g == &changed ? value : g.get(base)));
    }
    CHECK(s.isa == base.isa);
}

}  // namespace

TEST_CASE("settings fields: each table covers its struct, keys and flags are unique") {
    // The static_asserts beside the tables say the same at compile time.
    CHECK(fieldCount<MarchSettings>() == kMarchFields.size());
    CHECK(fieldCount<SsrResolveSettings>() == kResolveFields.size());
    CHECK(fieldCount<DenoiseSettings>() == kDenoiseFields.size());
    CHECK(fieldCount<TraceSettings>() == kTraceOwnFields.size() + 3);  // + march, resolve, denoise
    CHECK(fieldCount<RenderSettings>() == kRenderOwnFields.size() + 2);  // + isa, trace
    CHECK(kRenderFields.size() == kRenderOwnFields.size() + kTraceOwnFields.size() +
                                      kMarchFields.size() + kResolveFields.size() +
                                      kDenoiseFields.size());
    // No two entries name one member (with the counts: every member is named once).
    const RenderSettings d;
    std::set<const void*> members;
    std::set<std::string> keys, flags;
    for (const auto& f : kRenderFields) {
        CAPTURE(f.key);
        const auto* p = static_cast<const char*>(f.address(d));
        CHECK(p >= reinterpret_cast<const char*>(&d));
        CHECK(p + f.size <= reinterpret_cast<const char*>(&d + 1));
        CHECK(members.insert(p).second);
        CHECK(keys.insert(std::string(f.key)).second);
        CHECK(flags.insert(cli::fieldOption(f)).second);
        CHECK(f.accepts(f.get(d)));  // the default is in range
        CHECK(!f.help.empty());
        if (f.type == FieldType::Choice)
            for (int i = 0; i < f.choiceCount; ++i) CHECK(f.choiceIndex(f.choiceName(i)) == i);
    }
    CHECK(keys.count("frames") == 0);  // the shot's own keys
    CHECK(keys.count("frame") == 0);
}

TEST_CASE("settings fields: every field round-trips through the CLI, a shot and the cache key") {
    const RenderSettings base = testBase();
    REQUIRE_NOTHROW(base.validate());
    const Scene scene = makeBuiltinScene("cornell");
    const ReferenceSettings ref;
    const uint64_t baseKey = referenceKey(scene, scene.camera, 0, base, ref);
    for (const auto& f : kRenderFields) {
        CAPTURE(f.key);
        const double value = otherValue(f, f.get(base));
        REQUIRE(value != f.get(base));
        REQUIRE(f.accepts(value));
        RenderSettings changed = base;
        f.set(changed, value);
        CHECK(f.get(changed) == value);
        CHECK_NOTHROW(changed.validate());

        // The command line: a flag for a bool (away from the default), else flag and value.
        if (f.has(kFieldCli)) {
            std::vector<std::string> args{cli::fieldOption(f)};
            if (f.type != FieldType::Bool) args.push_back(f.text(value));
            CAPTURE(args.back());
            checkOnly(viaCli(args, base), base, f, value);
        }
        // A shot file's render object.
        const std::string shot =
            "{\"render\": {\"" + std::string(f.key) + "\": " + json(f, value) + "}}";
        CAPTURE(shot);
        if (f.has(kFieldShot)) checkOnly(viaShot(shot, base), base, f, value);
        else CHECK_THROWS_AS(viaShot(shot, base), ShotError);
        // The reference cache key moves exactly for the fields that shape the reference.
        CHECK((referenceKey(scene, scene.camera, 0, changed, ref) != baseKey) == f.has(kFieldKey));
    }
}

TEST_CASE("settings fields: validate() refuses each field out of its range, by name") {
    const RenderSettings base = testBase();
    for (const auto& f : kRenderFields) {
        if (f.type == FieldType::Bool) continue;
        CAPTURE(f.key);
        std::vector<double> bad;
        if (f.type == FieldType::Choice) {
            bad = {-1.0, double(f.choiceCount)};
        } else {
            bad = {f.range.lo - 1.0};
            // NaN fits only a float member: converting it to an integer is undefined behaviour
            // (clang's UBSan stops there), and no parser hands an integer field one.
            if (f.type == FieldType::Float) bad.push_back(std::nan(""));
            if (f.range.loOpen) bad.push_back(f.range.lo);
            if (f.type == FieldType::Int || f.range.hi != kFieldFloatMax)
                bad.push_back(f.range.hiOpen ? f.range.hi : f.range.hi + 1.0);
            else bad.push_back(INFINITY);
        }
        for (double v : bad) {
            CAPTURE(v);
            RenderSettings s = base;
            f.set(s, v);
            std::string message;
            try {
                s.validate();
            } catch (const std::invalid_argument& e) {
                message = e.what();
            }
            // (built with append: GCC 12 gives a false -Wrestrict for "." + std::string)
            std::string expected = ".";
            expected.append(f.key).append(": expected ").append(f.expected());
            CHECK(message.find(expected) != std::string::npos);
        }
    }
}
