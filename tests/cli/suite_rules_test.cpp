// A golden-image suite's file and rules (cli/suite_file.h, cli/suite_rules.h) without
// rendering: exact by default, two-sided ranges whose lower end reports a stale tolerance,
// buckets, a hard limit, FLIP ranges, alternate references, and one-line errors naming the
// field of a bad suite file.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <string>
#include <vector>

#include "cli/suite_file.h"
#include "cli/suite_rules.h"
#include "temp_dir.h"
#include "text_files.h"

using namespace ssrt;
using namespace ssrt::cli;

namespace {

// A layer in both files whose largest difference is `maxError`, with `over` pixels over each of
// `thresholds`' values.
LayerDiff layer(double maxError, std::vector<uint64_t> over) {
    LayerDiff l;
    l.name = "color";
    l.identical = maxError == 0.0;
    l.maxError = maxError;
    l.hashA = 1;
    l.hashB = maxError == 0.0 ? 1 : 2;
    l.pixelsOverEach = std::move(over);
    return l;
}

// The suite `json` in a file of a fresh folder (with an empty shot file beside it), loaded.
Suite suiteOf(const test::TempDir& dir, const std::string& json) {
    test::writeFile(dir.file("shot.json"), "{}");
    test::writeFile(dir.file("suite.json"), json);
    return loadSuite(dir.file("suite.json"));
}

std::string loadError(const std::string& json) {
    test::TempDir dir;
    try {
        suiteOf(dir, json);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("suite rules: exact is the default and takes the same bits") {
    const LayerRule exact;
    CHECK(judgeLayer(layer(0.0, {0}), exact, {0.0}).verdict == Verdict::Pass);
    const LayerJudgement off = judgeLayer(layer(1e-7, {1}), exact, {0.0});
    CHECK(off.verdict == Verdict::Fail);
    CHECK(off.why.find("not bit-identical") != std::string::npos);
    LayerDiff missing = layer(0.0, {0});
    missing.presence = LayerDiff::Presence::MissingInB;
    CHECK(judgeLayer(missing, exact, {0.0}).verdict == Verdict::Fail);
}

TEST_CASE("suite rules: a range fails above its top and is stale below its bottom") {
    LayerRule rule;
    rule.exact = false;
    rule.maxDifference = Range{0.001, 0.01};
    CHECK(judgeLayer(layer(0.005, {3}), rule, {0.0}).verdict == Verdict::Pass);
    CHECK(judgeLayer(layer(0.02, {3}), rule, {0.0}).verdict == Verdict::Fail);
    const LayerJudgement stale = judgeLayer(layer(0.0005, {3}), rule, {0.0});
    CHECK(stale.verdict == Verdict::Stale);
    CHECK(stale.why.find("max difference") != std::string::npos);
    // A tolerance on a bit-identical layer is stale, whatever its range.
    rule.maxDifference = Range{0.0, 0.01};
    CHECK(judgeLayer(layer(0.0, {0}), rule, {0.0}).verdict == Verdict::Stale);
    // The pixel count has its own range, counted over the rule's threshold.
    rule.maxDifference.reset();
    rule.threshold = 0.1;
    rule.pixels = Range{10, 100};
    CHECK(judgeLayer(layer(0.5, {500, 50}), rule, {0.0, 0.1}).verdict == Verdict::Pass);
    CHECK(judgeLayer(layer(0.5, {500, 101}), rule, {0.0, 0.1}).verdict == Verdict::Fail);
    CHECK(judgeLayer(layer(0.5, {500, 9}), rule, {0.0, 0.1}).verdict == Verdict::Stale);
}

TEST_CASE("suite rules: buckets and the hard limit") {
    LayerRule rule;
    rule.exact = false;
    rule.buckets = {{0.01, 100}, {0.2, 2}};
    const std::vector<double> t{0.0, 0.01, 0.2};
    CHECK(judgeLayer(layer(0.3, {150, 100, 2}), rule, t).verdict == Verdict::Pass);
    CHECK(judgeLayer(layer(0.3, {150, 101, 2}), rule, t).verdict == Verdict::Fail);
    CHECK(judgeLayer(layer(0.3, {150, 50, 3}), rule, t).verdict == Verdict::Fail);
    rule.hardLimit = 0.25;
    const LayerJudgement hard = judgeLayer(layer(0.3, {150, 50, 1}), rule, t);
    CHECK(hard.verdict == Verdict::Fail);
    CHECK(hard.why.find("hard limit") != std::string::npos);
    // A NaN against a number passes no rule.
    LayerDiff nan = layer(0.0, {1, 1, 1});
    nan.nonFinite = 1;
    nan.identical = false;
    CHECK(judgeLayer(nan, rule, t).verdict == Verdict::Fail);
}

TEST_CASE("suite rules: FLIP's ranges") {
    FlipRule rule;
    rule.mean = Range{0.001, 0.01};
    FlipStats s;
    s.mean = 0.005;
    CHECK(judgeFlip(s, rule).verdict == Verdict::Pass);
    s.mean = 0.02;
    CHECK(judgeFlip(s, rule).verdict == Verdict::Fail);
    s.mean = 0.0;
    CHECK(judgeFlip(s, rule).verdict == Verdict::Stale);
}

TEST_CASE("suite file: one number N is the range [N/10, N], the rules by layer and '*'") {
    test::TempDir dir;
    const Suite s = suiteOf(dir, R"({"cases": [
        {"name": "a", "shot": "shot.json", "render": ["--width", "64"], "reference": "a.exr",
         "layers": {"color": {"maxDifference": 0.02, "pixels": [3, 40], "threshold": 0.001},
                    "*": {"hardLimit": 0.5}},
         "flip": {"mean": 0.01},
         "alternates": [{"arch": "aarch64", "reference": "a.arm.exr"},
                        {"cpu": "avx512", "arch": "x86_64", "reference": "a.avx512.exr"}]},
        {"name": "b", "reference": "b.png", "frame": 3}]})");
    REQUIRE(s.cases.size() == 2);
    const SuiteCase& a = s.cases[0];
    CHECK(*a.shot == "shot.json");
    CHECK(a.args == std::vector<std::string>{"--width", "64"});
    const LayerRule& color = ruleFor(a, "color");
    CHECK(!color.exact);
    CHECK(color.maxDifference->lo == doctest::Approx(0.002));
    CHECK(color.maxDifference->hi == 0.02);
    CHECK(color.pixels->lo == 3);
    CHECK(*ruleFor(a, "viewZ").hardLimit == 0.5);
    CHECK(ruleFor(s.cases[1], "color").exact);
    CHECK(!a.frame);
    CHECK(*s.cases[1].frame == 3);
    CHECK(caseThresholds(a) == std::vector<double>{0.0, 0.001});
    CHECK(a.flip->mean->hi == 0.01);
    CHECK(chosenReference(a, {{"arch", "aarch64"}, {"cpu", "scalar"}}) == "a.arm.exr");
    CHECK(chosenReference(a, {{"arch", "x86_64"}, {"cpu", "avx512"}}) == "a.avx512.exr");
    CHECK(chosenReference(a, {{"arch", "x86_64"}, {"cpu", "avx2"}}) == "a.exr");
    const auto keys = suiteMachineKeys();
    CHECK(keys.count("arch") == 1);
    CHECK(keys.count("cpu") == 1);
}

TEST_CASE("suite file: a bad file is one line naming the field") {
    CHECK(loadError("[]").find("suite.json: ") != std::string::npos);
    CHECK(loadError(R"({"cases": []})").find("cases: expected a non-empty array") !=
          std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.exr", "rneder": []}]})")
              .find("cases[0].rneder: unknown key") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a/b", "reference": "a.exr"}]})")
              .find("cases[0].name: expected a name") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.jpg"}]})")
              .find("cases[0].reference: expected an .exr or .png") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.exr", "shot": "none.json"}]})")
              .find("cases[0].shot: no such file") != std::string::npos);
    CHECK(
        loadError(R"({"cases": [{"name": "a", "reference": "a.exr", "render": ["-o", "x.exr"]}]})")
            .find("cases[0].render[0]: '-o' is the runner's") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.exr",
                        "layers": {"color": {"maxDifference": [0.5, 0.1]}}}]})")
              .find("cases[0].layers.color.maxDifference: expected lo <= hi") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.exr", "layers": {"color": {}}}]})")
              .find("cases[0].layers.color: expected \"exact\" or") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.exr", "frame": -1}]})")
              .find("cases[0].frame: expected an integer from 0") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "reference": "a.exr"},
                                  {"name": "a", "reference": "b.exr"}]})")
              .find("cases[1].name: 'a' names another case too") != std::string::npos);
    CHECK(loadError(R"({"cases": [{"name": "a", "name": "b", "reference": "a.exr"}]})")
              .find("duplicate key 'name'") != std::string::npos);
}

#endif  // SSRT_CLI_LIB
