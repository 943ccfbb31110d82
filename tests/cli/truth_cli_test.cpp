// `ssrt compare` and `ssrt sweep`, in-process on tiny frames: the tables and the CSV hold
// what they promise, the reference comes back from the cache, and bad input is one error
// line with nothing written.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/cli_run.h"
#include "cli/sweep_command.h"
#include "io/image_io.h"
#include "temp_dir.h"

using namespace ssrt;
using test::contains;
using test::isOneErrorLine;
using test::runSsrt;
using test::TempDir;

namespace {

// Small and quick: the point is the plumbing, the physics is tested in tests/truth/.
std::vector<std::string> tiny(std::vector<std::string> args, const TempDir& dir) {
    for (const char* a : {"--width", "64", "--height", "36", "--reference-spp", "4", "--repeats",
                          "1", "--shadow-map-size", "256", "-j", "2"})
        args.push_back(a);
    args.insert(args.end(), {"--cache-dir", dir.file("cache")});
    return args;
}

std::vector<std::string> splitCsv(const std::string& line) { return test::csvCells(line); }

}  // namespace

TEST_CASE("compare: tables of ray classes, image error and times -- the reference is cached") {
    TempDir dir;
    // Every pixel traced: the ray check takes full-resolution rays only, and the default
    // preset's SSGI is traced at half resolution (its check layers would be missing).
    const auto args = tiny(
        {"compare", "--scene", "spheres", "--quality", "ultra", "-o", dir.file("cmp.exr")}, dir);
    const test::CliResult first = runSsrt(args);
    INFO(first.err);
    REQUIRE(first.code == 0);
    for (const char* part : {"BVH (Embree 3)", "agreed %", "false_hit %", "missed_on_screen %",
                             "true_miss %", "offscreen_truth %", "hit error px, p95", "relMSE",
                             "specular", "diffuse", "ssr march", "march / Embree"})
        CHECK_MESSAGE(contains(first.out, part), part);
    CHECK(contains(first.err, "reference: rendered"));
    const std::vector<std::string> channels = readChannelNames(dir.file("cmp.exr"));
    for (const char* layer :
         {"color.R", "ref.color.R", "ref.ssr.G", "ssrCheck.class", "ssgiCheck.pixelError"})
        CHECK_MESSAGE(std::find(channels.begin(), channels.end(), layer) != channels.end(), layer);

    // The same request again: the reference comes from the cache and the figures are equal.
    const test::CliResult second = runSsrt(args);
    REQUIRE(second.code == 0);
    CHECK(contains(second.err, "reference: from the cache"));
    const auto relMseLine = [](const std::string& out) {
        const std::size_t at = out.find("color (exposed)");
        return out.substr(at, out.find('\n', at) - at);
    };
    CHECK(relMseLine(first.out) == relMseLine(second.out));
}

TEST_CASE("compare: the reference's bounces follow --ssgi-feedback and are cached apart") {
    TempDir dir;
    const auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"compare", "--scene", "cornell"};
        args.insert(args.end(), extra.begin(), extra.end());
        return runSsrt(tiny(args, dir));
    };
    const test::CliResult one = run({});
    INFO(one.err);
    REQUIRE(one.code == 0);
    CHECK(contains(one.out, "reference 4 spp\n"));
    // Feedback's default: kFeedbackReferenceBounces, a reference of its own.
    const test::CliResult fed = run({"--ssgi-feedback"});
    REQUIRE(fed.code == 0);
    const std::string bounces = std::to_string(cli::kFeedbackReferenceBounces) + " bounces";
    CHECK(contains(fed.out, "ssgi feedback, reference 4 spp, " + bounces));
    CHECK(contains(fed.err, "reference: rendered (4 spp, " + bounces + ")"));
    // The same count asked for: from the cache; another: rendered.
    const test::CliResult same =
        run({"--reference-bounces", std::to_string(cli::kFeedbackReferenceBounces)});
    REQUIRE(same.code == 0);
    CHECK(contains(same.err, "reference: from the cache (4 spp, " + bounces + ")"));
    const test::CliResult three = run({"--ssgi-feedback", "--reference-bounces", "3"});
    REQUIRE(three.code == 0);
    CHECK(contains(three.err, "reference: rendered (4 spp, 3 bounces)"));
}

TEST_CASE("sweep: one CSV row per setting, the columns it names, 'off' once") {
    TempDir dir;
    const std::string csv = dir.file("s.csv");
    const test::CliResult r =
        runSsrt(tiny({"sweep", "--scene", "cornell", "--marchers", "off,hiz,linear", "--max-steps",
                      "16,128", "-o", csv, "-q"},
                     dir));
    INFO(r.err);
    REQUIRE(r.code == 0);
    std::ifstream in(csv);
    std::string line;
    REQUIRE(std::getline(in, line));
    const auto& columns = cli::sweepColumns();
    CHECK(splitCsv(line) == columns);
    std::vector<std::vector<std::string>> rows;
    while (std::getline(in, line)) rows.push_back(splitCsv(line));
    REQUIRE(rows.size() == 5);  // off + 2 marchers x 2 step counts
    const auto col = [&](const char* name) {
        return std::size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
    };
    for (const auto& row : rows) {
        REQUIRE(row.size() == columns.size());
        const double relMse = std::stod(row[col("relmse")]);
        CHECK(std::isfinite(relMse));
        CHECK(relMse >= 0.0);
        CHECK(std::stod(row[col("frame_ms")]) > 0.0);
        CHECK(row[col("reference_bounces")] == "1");
        // (The rays the composite hides are not traced unless --trace-hidden.)
        CHECK(row[col("trace_hidden")] == (row[col("marcher")] == "off" ? "" : "0"));
        if (row[col("marcher")] == "off") {
            CHECK(row[col("ssr_agreed")].empty());
            CHECK(row[col("march_vs_embree")].empty());
        } else {
            // Shares of the five classes add up to 1.
            double sum = 0.0;
            for (const char* c : {"ssr_agreed", "ssr_false_hit", "ssr_missed_on_screen",
                                  "ssr_true_miss", "ssr_offscreen_truth"})
                sum += std::stod(row[col(c)]);
            CHECK(sum == doctest::Approx(1.0).epsilon(1e-4));
            CHECK(std::stod(row[col("embree_mrays_s")]) > 0.0);
        }
    }
    CHECK(rows[0][col("marcher")] == "off");
    CHECK(rows[1][col("max_steps")] == "16");
    CHECK(rows[2][col("max_steps")] == "128");
}

TEST_CASE("compare and sweep: bad input is one error line and nothing is written") {
    TempDir dir;
    const std::string csv = dir.file("s.csv");
    for (const auto& args :
         std::vector<std::vector<std::string>>{{"sweep", "--marchers", "hiz,,dda", "-o", csv},
                                               {"sweep", "--marchers", "hiz,march", "-o", csv},
                                               {"sweep", "--max-steps", "0", "-o", csv},
                                               {"sweep", "-o", dir.file("s.txt")},
                                               {"sweep", "--reference-spp", "0", "-o", csv},
                                               {"sweep", "--reference-bounces", "0", "-o", csv},
                                               {"compare", "--reference-bounces", "257"},
                                               {"compare", "--reference-bounces", "many"},
                                               {"compare", "--no-ssr", "--no-ssgi"},
                                               {"compare", "--visibility", "raytraced"},
                                               {"compare", "--depth-tolerance", "1.5"},
                                               {"compare", "--scene", "nowhere"}}) {
        const test::CliResult r = runSsrt(args);
        CAPTURE(args[1]);
        CHECK(r.code == cli::kExitUsage);
        CHECK(isOneErrorLine(r.err));
    }
    CHECK(dir.empty());
}

#endif  // SSRT_CLI_LIB
