// `ssrt check SUITE.json`, driven in-process with each case rendered by the built ssrt at 64x36:
// new cases, --update writing only the failing and new references with their provenance, a
// changed case failing by name and layer (first in the HTML report, counted in JUnit), a
// tolerance ten times too loose reported stale, a render that fails, and the exit statuses.
#include <doctest/doctest.h>

#if defined(SSRT_CLI_LIB) && defined(SSRT_CLI_PROGRAM)

#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_run.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "temp_dir.h"
#include "text_files.h"

using namespace ssrt;
namespace fs = std::filesystem;

namespace {

using test::contains;

// A case: name, `ssrt render` flags (64x36 added), the reference's extension and its layers rule.
struct TestCase {
    std::string name, flags, ext = ".exr", layers = {};
};

std::string suiteJson(const std::vector<TestCase>& cases) {
    std::string json = "{\"cases\": [\n";
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const TestCase& c = cases[i];
        json += "  {\"name\": \"" + c.name + "\", \"reference\": \"golden/" + c.name + c.ext +
                "\", \"render\": [\"--width\", \"64\", \"--height\", \"36\"" + c.flags + "]" +
                (c.layers.empty() ? "" : ", \"layers\": " + c.layers) + "}" +
                (i + 1 < cases.size() ? ",\n" : "\n");
    }
    return json + "]}\n";
}

// A suite in a fresh folder; runs `ssrt check` on it with the built ssrt.
struct SuiteDir {
    test::TempDir dir{"ssrt-check"};
    void write(const std::vector<TestCase>& cases) const {
        test::writeFile(dir.file("suite.json"), suiteJson(cases));
    }
    test::CliResult check(std::vector<std::string> more = {}) const {
        std::vector<std::string> args{"check",  dir.file("suite.json"), "--out", dir.file("out"),
                                      "--ssrt", SSRT_CLI_PROGRAM};
        args.insert(args.end(), more.begin(), more.end());
        return test::runSsrt(args);
    }
    std::string golden(const std::string& name) const { return dir.file("golden/" + name); }
    std::string out(const std::string& name) const { return dir.file("out/" + name); }
};

// The four cases most tests start from, their references written by --update.
const std::vector<TestCase> kCases = {
    {"spheres", ", \"--scene\", \"spheres\""},
    {"cornell", ", \"--scene\", \"cornell\""},
    {"cornell-png", ", \"--scene\", \"cornell\"", ".png"},
    {"fence", ", \"--scene\", \"fence\", \"--no-ssgi\""},
};

std::map<std::string, std::string> referenceBytes(const SuiteDir& s) {
    std::map<std::string, std::string> bytes;
    for (const TestCase& c : kCases) bytes[c.name] = test::readFile(s.golden(c.name + c.ext));
    return bytes;
}

}  // namespace

TEST_CASE("check: new cases fail until --update writes their references with provenance") {
    SuiteDir s;
    s.write(kCases);
    const std::string suite = test::readFile(s.dir.file("suite.json"));
    const test::CliResult fresh = s.check();
    CHECK(fresh.code == 1);
    CHECK(contains(fresh.out, "NEW      spheres  no reference golden/spheres.exr"));
    CHECK(contains(fresh.out, "check: 4 cases: 0 passed, 0 failed, 0 stale, 4 new, 0 errors"));
    CHECK(!fs::exists(s.golden("spheres.exr")));

    const test::CliResult updated = s.check({"--update"});
    CHECK(updated.code == 0);
    CHECK(contains(updated.out, "UPDATED  cornell-png  wrote golden/cornell-png.png (was NEW"));
    for (const std::string file : {"spheres.exr", "cornell-png.png"}) {
        CAPTURE(file);
        const auto attributes = readImageAttributes(s.golden(file));
        for (const std::string key : {"ssrt:version", "ssrt:commit", "ssrt:compiler", "ssrt:isa"}) {
            CAPTURE(key);
            REQUIRE(attributes.count(key) == 1);
            CHECK(!attributes.at(key).empty());
        }
    }
    // The reference holds exactly the render's values.
    CHECK(compareImages(s.out("cases/fence/rendered.exr"), s.golden("fence.exr")).identical());
    CHECK(test::readFile(s.dir.file("suite.json")) == suite);  // no rule touched

    const test::CliResult again = s.check();
    CHECK(again.code == 0);
    CHECK(contains(again.out, "PASS     spheres  "));
    CHECK(contains(again.out, "layers bit-identical"));
    CHECK(contains(again.out, "check: 4 cases: 4 passed"));
    CHECK(contains(test::readFile(s.out("junit.xml")), "tests=\"4\" failures=\"0\" errors=\"0\""));
}

TEST_CASE(
    "check: a changed case fails by name and layer, leads the report, and --update rewrites only "
    "failing ones") {
    SuiteDir s;
    s.write(kCases);
    REQUIRE(s.check({"--update"}).code == 0);
    const auto before = referenceBytes(s);

    std::vector<TestCase> changed = kCases;
    changed[1].flags += ", \"--exposure\", \"1.5\"";
    s.write(changed);
    const test::CliResult one = s.check({"--jobs", "3"});
    CHECK(one.code == 1);
    CHECK(contains(one.out, "FAIL     cornell  color: not bit-identical"));
    CHECK(contains(one.out, "check: 4 cases: 3 passed, 1 failed"));
    const std::string html = test::readFile(s.out("report.html"));
    const std::string failing = "<section class=\"case FAIL\" id=\"case-cornell\">";
    CHECK(html.find("<section class=\"case ") == html.find(failing));
    CHECK(contains(html, "cases/cornell/difference.png"));
    CHECK(contains(test::readFile(s.out("junit.xml")), "tests=\"4\" failures=\"1\" errors=\"0\""));
    // The lines come in the suite's order whatever finished first.
    CHECK(one.out.find("spheres") < one.out.find("cornell  "));
    CHECK(one.out.find("cornell  ") < one.out.find("cornell-png"));
    CHECK(one.out.find("cornell-png") < one.out.find("fence"));

    changed[3].flags += ", \"--exposure\", \"0.5\"";
    s.write(changed);
    CHECK(s.check({"--update"}).code == 0);
    const auto after = referenceBytes(s);
    for (const TestCase& c : kCases) {
        CAPTURE(c.name);
        CHECK((before.at(c.name) == after.at(c.name)) ==
              (c.name != "cornell" && c.name != "fence"));
    }
    CHECK(s.check().code == 0);
}

TEST_CASE("check: a tolerance ten times looser than the difference is stale") {
    SuiteDir s;
    s.write({{"spheres", ", \"--scene\", \"spheres\""}});
    REQUIRE(s.check({"--update"}).code == 0);
    // The same scene a little brighter: its colour differs by a measured amount.
    const auto withRule = [&](const std::string& rule) {
        s.write({{"spheres", ", \"--scene\", \"spheres\", \"--exposure\", \"1.02\"", ".exr",
                  "{\"color\": " + rule + ", \"*\": {\"hardLimit\": 1}}"}});
        return s.check();
    };
    const test::CliResult exact = withRule("\"exact\"");
    CHECK(exact.code == 1);
    ImageCompareOptions only;
    only.layers = {"color"};
    const double measured =
        compareImages(s.out("cases/spheres/rendered.exr"), s.golden("spheres.exr"), only)
            .layers.front()
            .maxError;
    REQUIRE(measured > 0.0);
    // Printed to round trip: ten times the measured value divides back to it exactly.
    const auto number = [](double v) {
        std::ostringstream text;
        text << std::setprecision(17) << v;
        return text.str();
    };
    const test::CliResult loose = withRule("{\"maxDifference\": " + number(10.0 * measured) + "}");
    CHECK(loose.code == 1);
    CHECK(contains(loose.out, "STALE    spheres  color: max difference"));
    CHECK(contains(loose.out, "the rule's lower end: tighten it"));
    const test::CliResult fits = withRule("{\"maxDifference\": " + number(2.0 * measured) + "}");
    CHECK(fits.code == 0);
    CHECK(contains(fits.out, "PASS     spheres  "));
    const test::CliResult tight = withRule("{\"maxDifference\": " + number(0.5 * measured) + "}");
    CHECK(tight.code == 1);
    CHECK(contains(tight.out, "FAIL     spheres  color: max difference"));
    // --update rewrites a stale case's reference no more than a passing one's.
    const std::string reference = test::readFile(s.golden("spheres.exr"));
    withRule("{\"maxDifference\": " + number(10.0 * measured) + "}");
    CHECK(s.check({"--update"}).code == 1);
    CHECK(test::readFile(s.golden("spheres.exr")) == reference);
}

TEST_CASE("check: a frame of a sequence is the one compared") {
    SuiteDir s;
    const std::string frames = ", \"--scene\", \"cornell\", \"--frames\", \"3\"";
    test::writeFile(s.dir.file("suite.json"),
                    "{\"cases\": [{\"name\": \"seq\", \"frame\": 2, \"reference\": "
                    "\"golden/seq.exr\", \"render\": [\"--width\", \"64\", \"--height\", "
                    "\"36\"" +
                        frames + "]}]}");
    REQUIRE(s.check({"--update"}).code == 0);
    CHECK(compareImages(s.out("cases/seq/rendered_0002.exr"), s.golden("seq.exr")).identical());
    CHECK(!compareImages(s.out("cases/seq/rendered_0000.exr"), s.golden("seq.exr")).identical());
    test::writeFile(s.dir.file("suite.json"),
                    "{\"cases\": [{\"name\": \"seq\", \"frame\": 3, \"reference\": "
                    "\"golden/seq.exr\", \"render\": [\"--width\", \"64\", \"--height\", "
                    "\"36\"" +
                        frames + "]}]}");
    const test::CliResult r = s.check();
    CHECK(r.code == 3);
    CHECK(contains(r.out, "ERROR    seq  the render wrote 3 frames, no frame 3"));
}

TEST_CASE("check: a render that fails is an error (exit 3), bad flags are usage errors (exit 2)") {
    SuiteDir s;
    s.write({{"spheres", ", \"--scene\", \"spheres\""}, {"broken", ", \"--scene\", \"nosuch\""}});
    const test::CliResult r = s.check();
    CHECK(r.code == 3);
    CHECK(contains(r.out, "ERROR    broken  the render failed (exit 2): ssrt: error:"));
    CHECK(contains(test::readFile(s.out("junit.xml")), "errors=\"1\""));
    CHECK(s.check({"--jobs", "-1"}).code == 2);
    CHECK(s.check({"--ssrt", s.dir.file("nosuch")}).code == 2);
    test::writeFile(s.dir.file("suite.json"), "{\"cases\": [{\"name\": \"x\"}]}");
    const test::CliResult bad = s.check();
    CHECK(bad.code == 3);
    CHECK(test::isOneErrorLine(bad.err));
    CHECK(contains(bad.err, "cases[0]: a case needs a reference"));
}

#endif
