// `ssrt compare` and `ssrt sweep`, in-process on tiny frames: the tables and the CSV hold
// what they promise, the reference comes back from the cache, and bad input is one error
// line with nothing written.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <algorithm>
#include <cmath>
#include <filesystem>
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

// A sweep's CSV file: its header, its rows, and where a column of sweepColumns() lies.
struct SweepCsv {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    static std::size_t col(const char* name) {
        const auto& columns = cli::sweepColumns();
        return std::size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
    }
};

SweepCsv readSweep(const std::string& path) {
    std::ifstream in(path);
    SweepCsv csv;
    std::string line;
    if (std::getline(in, line)) csv.header = splitCsv(line);
    while (std::getline(in, line)) csv.rows.push_back(splitCsv(line));
    return csv;
}

// `ssrt sweep ARGS` at the tiny size, which must succeed: its CSV, with sweepColumns()'s header.
SweepCsv sweepOf(std::vector<std::string> args) {
    TempDir dir;
    const std::string csv = dir.file("s.csv");
    args.insert(args.begin(), "sweep");
    for (const char* a : {"-o", csv.c_str(), "-q"}) args.push_back(a);
    const test::CliResult r = runSsrt(tiny(args, dir));
    INFO(r.err);
    REQUIRE(r.code == 0);
    SweepCsv s = readSweep(csv);
    REQUIRE(s.header == cli::sweepColumns());
    return s;
}

// The ray-check table's row `label` of compare's output: its ssr and ssgi cells.
std::vector<std::string> checkRow(const std::string& out, const std::string& label) {
    for (const std::string& line : test::textLines(out)) {
        if (line.rfind("  " + label + " ", 0) != 0) continue;
        std::istringstream cells(line.substr(label.size() + 2));
        std::vector<std::string> row;
        for (std::string c; cells >> c;) row.push_back(c);
        return row;
    }
    return {};
}

}  // namespace

TEST_CASE("compare: tables of ray classes, image error and times -- the reference is cached") {
    TempDir dir;
    // (Every pixel traced; the default preset's layouts: below.)
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

// The default preset traces SSR on a checkerboard and SSGI on the half frame: both passes'
// rays are checked, every one in a class, and the check layers are written.
TEST_CASE("compare: the default preset's checkerboard and half-resolution rays are checked") {
    TempDir dir;
    const test::CliResult r =
        runSsrt(tiny({"compare", "--scene", "cornell", "-o", dir.file("cmp.exr")}, dir));
    INFO(r.err);
    REQUIRE(r.code == 0);
    const std::vector<std::string> rays = checkRow(r.out, "rays");
    REQUIRE(rays.size() == 2);
    for (int pass = 0; pass < 2; ++pass) {
        CAPTURE(pass);
        CHECK(std::stoll(rays[std::size_t(pass)]) > 0);
        double sum = 0.0;
        for (const char* cls :
             {"agreed", "false_hit", "missed_on_screen", "true_miss", "offscreen_truth"}) {
            const std::vector<std::string> row = checkRow(r.out, std::string(cls) + " %");
            REQUIRE(row.size() == 2);
            sum += std::stod(row[std::size_t(pass)]);
        }
        CHECK(std::abs(sum - 100.0) <= 0.05);  // (five shares printed to 0.01)
    }
    CHECK(!contains(r.err, "warning"));
    const std::vector<std::string> channels = readChannelNames(dir.file("cmp.exr"));
    for (const char* layer : {"ssrCheck.class", "ssgiCheck.class", "ssgiCheck.pixelError"})
        CHECK_MESSAGE(std::find(channels.begin(), channels.end(), layer) != channels.end(), layer);
}

// Figures that judge nothing are said so: a pass without a checked ray is a warning naming
// it, a frame without a surface pixel an error with nothing written.
TEST_CASE(
    "compare: a pass without rays is warned about, a frame without surface refused (sweep too)") {
    TempDir dir;
    const test::CliResult off = runSsrt(tiny({"compare", "--scene", "cornell", "--no-ssr"}, dir));
    REQUIRE(off.code == 0);
    CHECK(contains(off.err, "ssrt: warning: ssr is off (--no-ssr): none of its rays is checked\n"));
    CHECK(!contains(off.err, "warning: ssgi"));
    // SSR on, but no pixel below the roughness fade: no ray to check.
    const test::CliResult none =
        runSsrt(tiny({"compare", "--scene", "cornell", "--roughness-fade-start", "0",
                      "--roughness-fade-end", "0", "-q"},
                     dir));
    REQUIRE(none.code == 0);
    CHECK(contains(none.err, "ssrt: warning: ssr traced no ray, so none is checked"));
    CHECK(contains(none.err, "are past the roughness fade"));
    // The camera turned away from the box: every pixel sky.
    test::writeFile(dir.file("away.json"),
                    R"({"scene": "cornell", "camera": )"
                    R"({"position": [0, 1, 3.2], "target": [0, 1, 10], "fovY": 40}})");
    const std::string exr = dir.file("away.exr"), csv = dir.file("away.csv");
    const test::CliResult empty = runSsrt(tiny(
        {"compare", "--shot", dir.file("away.json"), "-q", "-o", exr, "--per-frame", csv}, dir));
    CHECK(empty.code == cli::kExitFailure);
    CHECK(isOneErrorLine(empty.err));
    CHECK(contains(empty.err, "the frame shows no surface"));
    CHECK(empty.out.empty());
    CHECK(!std::filesystem::exists(exr));
    CHECK(!std::filesystem::exists(csv));
    // sweep the same: no CSV of zeros.
    const std::string sweepCsv = dir.file("sweep.csv");
    const test::CliResult sweep = runSsrt(
        tiny({"sweep", "--shot", dir.file("away.json"), "--marchers", "hiz", "-q", "-o", sweepCsv},
             dir));
    CHECK(sweep.code == cli::kExitFailure);
    CHECK(isOneErrorLine(sweep.err));
    CHECK(contains(sweep.err, "the frame shows no surface"));
    CHECK(!std::filesystem::exists(sweepCsv));
}

// The relMSE cells of a row of compare's "one-bounce model" table: method, then model.
std::vector<double> modelRow(const std::string& out, const std::string& label) {
    const std::size_t table = out.find("one-bounce model");
    if (table == std::string::npos) return {};
    std::vector<double> cells;
    for (const std::string& c : checkRow(out.substr(table), label)) cells.push_back(std::stod(c));
    return cells;
}

TEST_CASE("compare: the reference is all the light -- the one-bounce model's error beside it") {
    TempDir dir;
    const auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"compare", "--scene", "cornell"};
        args.insert(args.end(), extra.begin(), extra.end());
        return runSsrt(tiny(args, dir));
    };
    // The default: all bounces, and the one-bounce reference for the model's error.
    const test::CliResult full = run({});
    INFO(full.err);
    REQUIRE(full.code == 0);
    CHECK(contains(full.out, "reference 4 spp, all bounces\n"));
    CHECK(contains(full.err, "reference: rendered (4 spp, all bounces)"));
    CHECK(contains(full.err, "reference: rendered (4 spp, one bounce, for the model's error)"));
    const std::vector<double> color = modelRow(full.out, "color (exposed)");
    const std::vector<double> direct = modelRow(full.out, "direct");
    const std::vector<double> diffuse = modelRow(full.out, "diffuse");
    REQUIRE(color.size() == 2);
    REQUIRE(direct.size() == 2);
    REQUIRE(diffuse.size() == 2);
    // Cornell's walls bounce light further: the one-bounce model misses some of it, in its
    // diffuse part only.
    CHECK(color[1] > 1e-3);
    CHECK(diffuse[1] > color[1]);
    CHECK(direct[1] == 0.0);
    // One bounce asked for: the method's error is the image error itself, and no model table.
    const test::CliResult one = run({"--reference-bounces", "1"});
    REQUIRE(one.code == 0);
    CHECK(contains(one.out, "reference 4 spp, one bounce\n"));
    CHECK(contains(one.err, "reference: from the cache (4 spp, one bounce)"));
    CHECK(!contains(one.out, "one-bounce model"));
    // ... and the same frame against the same one-bounce reference as the table's method cell.
    const std::vector<std::string> oneColor = checkRow(one.out, "color (exposed)");
    REQUIRE(!oneColor.empty());
    CHECK(std::stod(oneColor[0]) == color[0]);
    // The full reference again: from the cache, both of them.
    const test::CliResult again = run({});
    REQUIRE(again.code == 0);
    CHECK(contains(again.err, "reference: from the cache (4 spp, all bounces)"));
    CHECK(contains(again.err, "reference: from the cache (4 spp, one bounce, for the model's"));
    // A fixed count: cached apart.
    const test::CliResult three = run({"--ssgi-feedback", "--reference-bounces", "3"});
    REQUIRE(three.code == 0);
    CHECK(contains(three.err, "reference: rendered (4 spp, 3 bounces)"));
    // What the option used to take is refused in one line.
    const test::CliResult old = run({"--reference-bounces", "auto"});
    CHECK(old.code == cli::kExitUsage);
    CHECK(isOneErrorLine(old.err));
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
        CHECK(row[col("reference_bounces")] == "full");
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

TEST_CASE("sweep: --ssgi-feedback off,on is an axis of the grid (column ssgi_feedback)") {
    const SweepCsv s = sweepOf({"--scene", "cornell", "--marchers", "hiz", "--ssgi-feedback",
                                "off,on", "--warmup-frames", "3"});
    const auto& rows = s.rows;
    const auto col = SweepCsv::col;
    REQUIRE(rows.size() == 2);
    CHECK(rows[0][col("ssgi_feedback")] == "0");
    CHECK(rows[1][col("ssgi_feedback")] == "1");
    // Three frames of history: feedback has reflected light to add, so the images differ.
    CHECK(rows[0][col("relmse")] != rows[1][col("relmse")]);
    CHECK(rows[0][col("relmse_direct")] == rows[1][col("relmse_direct")]);
}

TEST_CASE("sweep: --ssr-trace screen,mixed,world is an axis of the grid (column ssr_trace)") {
    const SweepCsv s =
        sweepOf({"--scene", "fence", "--marchers", "hiz", "--ssr-trace", "screen,mixed,world"});
    const auto& rows = s.rows;
    const auto col = SweepCsv::col;
    REQUIRE(rows.size() == 3);
    const auto at = [&](int row, const char* name) { return std::stod(rows[row][col(name)]); };
    CHECK(rows[0][col("ssr_trace")] == "screen");
    CHECK(rows[1][col("ssr_trace")] == "mixed");
    CHECK(rows[2][col("ssr_trace")] == "world");
    // The screen sends no ray to world space, world mode every one; mixed some, and its
    // screen-answered rays are rarely wrong where the screen's alone are often wrong.
    CHECK(at(0, "ssr_world_rays") == 0.0);
    CHECK(at(1, "ssr_world_rays") > 0.0);
    CHECK(at(1, "ssr_world_rays") < 1.0);
    CHECK(at(2, "ssr_world_rays") == 1.0);
    CHECK(at(0, "ssr_screen_false_hit") == at(0, "ssr_false_hit"));
    CHECK(at(0, "ssr_false_hit") > 0.0);
    CHECK(at(1, "ssr_false_hit") < 0.5 * at(0, "ssr_false_hit"));
    CHECK(at(2, "ssr_screen_false_hit") == 0.0);
    // The world stage's time is its own column; the screen runs none.
    CHECK(rows[0][col("ms_ssr_world")].empty());
    CHECK(at(1, "ms_ssr_world") > 0.0);
    for (int i = 0; i < 3; ++i) CHECK(rows[i][col("ssgi_trace")] == "screen");
}

TEST_CASE("sweep: --ssgi-trace is an axis of the grid (column ssgi_trace), SSR's beside it") {
    const SweepCsv s = sweepOf({"--scene", "fence", "--marchers", "hiz", "--ssr-trace", "screen",
                                "--ssgi-trace", "screen,world"});
    const auto& rows = s.rows;
    const auto col = SweepCsv::col;
    REQUIRE(rows.size() == 2);
    const auto at = [&](int row, const char* name) { return std::stod(rows[row][col(name)]); };
    CHECK(rows[0][col("ssgi_trace")] == "screen");
    CHECK(rows[1][col("ssgi_trace")] == "world");
    CHECK(rows[1][col("ssr_trace")] == "screen");
    CHECK(at(0, "ssgi_world_rays") == 0.0);
    CHECK(at(1, "ssgi_world_rays") == 1.0);
    CHECK(at(1, "ssr_world_rays") == 0.0);
    CHECK(at(0, "ssgi_false_hit") > 0.0);
    CHECK(at(1, "ssgi_false_hit") == 0.0);
    CHECK(rows[0][col("ms_ssgi_world")].empty());
    CHECK(at(1, "ms_ssgi_world") > 0.0);
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
                                               {"sweep", "--ssgi-feedback", "yes", "-o", csv},
                                               {"sweep", "--ssr-trace", "hybrid", "-o", csv},
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
