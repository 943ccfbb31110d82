// Shards of batch work (cli/shard.h) and `ssrt merge`, in-process on tiny frames: a sweep run
// as 3 shards and merged equals the unsharded CSV in every column but the timings; a
// reference rendered as 2 bands and merged is the unsharded file, byte for byte; a sharded
// multi-frame render writes exactly the unsharded run's files for its frames (across a camera
// cut too); Slurm's array variables choose the shard; bad parts are errors and write nothing.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <optional>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/cli_run.h"
#include "cli/shard.h"
#include "cli/sweep_command.h"
#include "io/image_io.h"
#include "temp_dir.h"

using namespace ssrt;
using test::contains;
using test::isOneErrorLine;
using test::runSsrt;
using test::ScopedEnv;
using test::TempDir;
using test::writeFile;

namespace {

// The columns whose values are measured times (they differ from run to run).
bool isTiming(const std::string& column) {
    return column == "frame_ms" || column.rfind("ms_", 0) == 0 || column == "march_mrays_s" ||
           column == "embree_mrays_s" || column == "march_vs_embree";
}

// A CSV with its timing cells blanked.
std::vector<std::vector<std::string>> withoutTimings(const std::string& csv) {
    std::vector<std::vector<std::string>> rows;
    for (const std::string& line : test::textLines(csv)) rows.push_back(test::csvCells(line));
    REQUIRE(!rows.empty());
    const std::vector<std::string> header = rows[0];
    for (auto& row : rows) {
        REQUIRE(row.size() == header.size());
        for (std::size_t c = 0; c < header.size(); ++c)
            if (isTiming(header[c])) row[c] = "";
    }
    return rows;
}

struct NoSlurm {
    ScopedEnv id{"SLURM_ARRAY_TASK_ID", nullptr}, count{"SLURM_ARRAY_TASK_COUNT", nullptr},
        min{"SLURM_ARRAY_TASK_MIN", nullptr};
};

std::vector<std::string> tinySweep(std::vector<std::string> args, const TempDir& dir) {
    args.insert(args.begin(), "sweep");
    for (const char* a :
         {"--scene", "cornell", "--width", "64", "--height", "36", "--reference-spp", "2",
          "--repeats", "1", "--shadow-map-size", "128", "-j", "2", "-q"})
        args.push_back(a);
    args.insert(args.end(), {"--cache-dir", dir.file("cache")});
    return args;
}

}  // namespace

TEST_CASE("shard: K/N parsed, file names, blocks and Slurm's variables") {
    const NoSlurm clean;
    // Shards count from 1, as Jest's, Playwright's and Vitest's --shard do: 2/5 is the second.
    const cli::Shard s = cli::parseShard("--shard", "2/5");
    CHECK(s.index == 1);
    CHECK(s.number() == 2);
    CHECK(s.count == 5);
    CHECK(s.text() == "2/5");
    CHECK(cli::parseShard("--shard", "1/2").index == 0);
    CHECK(cli::parseShard("--shard", "2/2").index == 1);
    CHECK(cli::parseShard("--shard", "1/1").count == 1);
    for (const char* bad : {"6/5", "3/2", "-1/3", "1/0", "3", "a/b", "1/3/4", "", "/3", "1/"})
        CHECK_THROWS_AS(cli::parseShard("--shard", bad), std::invalid_argument);
    // 0/N is the old count from 0: the message says how shards count.
    try {
        cli::parseShard("--shard", "0/2");
        FAIL("0/2 was accepted");
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        CHECK(contains(what, "count from 1"));
        CHECK(contains(what, "1/2 is the first of 2 and 2/2 the last"));
    }
    CHECK(cli::shardFileName("out/s.csv", s) == "out/s.shard-2-of-5.csv");
    CHECK(cli::shardFileName("s.csv", cli::Shard{}) == "s.csv");
    const std::optional<cli::Shard> back = cli::shardOfFileName("out/s.shard-2-of-5.csv");
    REQUIRE(back);
    CHECK((back->index == 1 && back->count == 5));
    CHECK(!cli::shardOfFileName("s.csv"));
    CHECK(!cli::shardOfFileName("s.shard-6-of-5.csv"));
    CHECK(!cli::shardOfFileName("s.shard-0-of-5.csv"));
    CHECK(cli::shardOfFileName("s.shard-5-of-5.csv"));
    // Contiguous blocks cover every item once.
    for (int n : {1, 2, 3, 7})
        for (long long total : {0ll, 1ll, 5ll, 48ll}) {
            long long next = 0;
            for (int k = 0; k < n; ++k) {
                const cli::ItemRange r = cli::shardBlock(cli::Shard{k, n}, total);
                CHECK(r.begin == next);
                next = r.end;
            }
            CHECK(next == total);
        }
    // No --shard and no Slurm: the whole work.
    CHECK(!cli::shardFrom(std::nullopt).sharded());
    {
        const ScopedEnv id("SLURM_ARRAY_TASK_ID", "5"), count("SLURM_ARRAY_TASK_COUNT", "3"),
            min("SLURM_ARRAY_TASK_MIN", "4");
        std::string source;
        const cli::Shard t = cli::shardFrom(std::nullopt, &source);
        CHECK((t.number() == 2 && t.count == 3));  // task 5 of 4..6 is the second
        CHECK(source == "SLURM_ARRAY_TASK_ID");
        // --shard wins over the environment.
        CHECK(cli::shardFrom(std::string("1/2")).count == 2);
    }
    {
        const ScopedEnv id("SLURM_ARRAY_TASK_ID", "7"), count("SLURM_ARRAY_TASK_COUNT", "3");
        CHECK_THROWS_AS(cli::shardFrom(std::nullopt), std::invalid_argument);  // not contiguous
    }
    {
        const ScopedEnv id("SLURM_ARRAY_TASK_ID", "1");
        CHECK_THROWS_AS(cli::shardFrom(std::nullopt), std::invalid_argument);  // no count
    }
}

TEST_CASE("shard: a sweep as 3 shards, merged, is the unsharded CSV but for the timings") {
    const NoSlurm clean;
    TempDir dir;
    // The grid, a preset and the Embree method: 5 points over 3 shards (2, 2 and 1).
    const std::vector<std::string> grid = {"--marchers", "off,hiz", "--max-steps",  "8,16",
                                           "--presets",  "low",     "--embree-spp", "1",
                                           "--frames",   "2",       "--per-frame",  ""};
    const auto run = [&](const std::string& name, std::optional<std::string> shard) {
        std::vector<std::string> g = grid;
        g.back() = dir.file(name + "_frames.csv");
        g.insert(g.end(), {"-o", dir.file(name + ".csv")});
        if (shard) g.insert(g.end(), {"--shard", *shard});
        const test::CliResult r = runSsrt(tinySweep(g, dir));
        INFO(r.err);
        REQUIRE(r.code == 0);
    };
    run("full", std::nullopt);
    for (int k = 1; k <= 3; ++k) run("part", std::to_string(k) + "/3");
    std::vector<std::string> parts, frameParts;
    for (int k = 1; k <= 3; ++k) {
        const std::string p = dir.file("part.shard-" + std::to_string(k) + "-of-3.csv");
        CHECK(test::textLines(test::readFile(p)).size() ==
              (k < 3 ? 3u : 2u));  // the header and its settings
        parts.push_back(p);
        frameParts.push_back(dir.file("part_frames.shard-" + std::to_string(k) + "-of-3.csv"));
    }
    // Given in any order.
    std::vector<std::string> merge = {"merge",  "-q",     "-o",    dir.file("merged.csv"),
                                      parts[2], parts[0], parts[1]};
    REQUIRE(runSsrt(merge).code == 0);
    const std::string full = test::readFile(dir.file("full.csv"));
    CHECK(test::textLines(full).size() == 6u);
    CHECK(withoutTimings(test::readFile(dir.file("merged.csv"))) == withoutTimings(full));
    // The marchers, the preset and the Embree method are all there.
    for (const char* part : {",off,", ",hiz,", ",low,", ",embree,"})
        CHECK_MESSAGE(contains(full, part), part);
    // The per-frame CSVs hold no timings: byte for byte.
    REQUIRE(runSsrt({"merge", "-q", "-o", dir.file("merged_frames.csv"), frameParts[0],
                     frameParts[1], frameParts[2]})
                .code == 0);
    CHECK(test::readFile(dir.file("merged_frames.csv")) ==
          test::readFile(dir.file("full_frames.csv")));

    SUBCASE("a missing, repeated or foreign part is an error, and nothing is written") {
        const std::string out = dir.file("bad.csv");
        const std::vector<std::vector<std::string>> bad = {
            {"merge", "-o", out, parts[0], parts[1]},                        // shard 3 missing
            {"merge", "-o", out, parts[0], parts[1], parts[1]},              // shard 2 twice
            {"merge", "-o", out, parts[0], parts[1], dir.file("full.csv")},  // not a part
            {"merge", "-o", out, parts[0], parts[1], frameParts[2]},         // another CSV's part
        };
        std::vector<std::string> errors;
        for (const auto& args : bad) {
            const test::CliResult r = runSsrt(args);
            INFO(args.back());
            CHECK(r.code != 0);
            CHECK(isOneErrorLine(r.err));
            errors.push_back(r.err);
        }
        CHECK(contains(errors[0], "shard 3 of 3 is missing"));
        CHECK(contains(errors[1], "shard 2/3 given twice"));
        // A part holding another shard's setting.
        writeFile(dir.file("x.shard-1-of-2.csv"),
                  test::textLines(full)[0] + "\n" + test::textLines(full)[2] + "\n");
        writeFile(dir.file("x.shard-2-of-2.csv"), test::textLines(full)[0] + "\n");
        const test::CliResult r = runSsrt(
            {"merge", "-o", out, dir.file("x.shard-1-of-2.csv"), dir.file("x.shard-2-of-2.csv")});
        CHECK(r.code != 0);
        CHECK(contains(r.err, "holds setting 1, not shard 1/2's"));
        CHECK(!std::filesystem::exists(out));
    }
}

TEST_CASE("shard: a reference as 2 bands, merged, is the unsharded file byte for byte") {
    const NoSlurm clean;
    TempDir dir;
    const auto reference = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {
            "reference",       "--scene", "spheres",           "--width", "48", "--height", "136",
            "--reference-spp", "2",       "--shadow-map-size", "128",     "-j", "2",        "-q",
            "--no-cache"};
        args.insert(args.end(), extra.begin(), extra.end());
        return runSsrt(args);
    };
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"-o", dir.file("full.exr")},
          {"-o", dir.file("ref.exr"), "--shard", "1/2"},
          {"-o", dir.file("ref.exr"), "--shard", "2/2"},
          {"-o", dir.file("other.exr"), "--shard", "2/2", "--frame", "9"}}) {
        const test::CliResult r = reference(extra);
        INFO(r.err);
        REQUIRE(r.code == 0);
    }
    const std::string band0 = dir.file("ref.shard-1-of-2.exr"),
                      band1 = dir.file("ref.shard-2-of-2.exr");
    REQUIRE(runSsrt({"merge", "-q", "-o", dir.file("merged.exr"), band1, band0, "--cache-dir",
                     dir.file("cache")})
                .code == 0);
    CHECK(test::readFile(dir.file("merged.exr")) == test::readFile(dir.file("full.exr")));
    // Its plain R, G, B (the colour again, for viewers: io/image_io.h) are the merged colour.
    int w = 0, h = 0;
    const std::vector<std::vector<float>> rgb = readChannels(
        dir.file("merged.exr"), {"R", "G", "B", "ref.color.R", "ref.color.G", "ref.color.B"}, w, h);
    for (int c = 0; c < 3; ++c) CHECK(rgb[std::size_t(c)] == rgb[std::size_t(c) + 3]);
    // The merged reference lands in the cache under the name compare looks for: a compare
    // with that cache takes it from there.
    const test::CliResult c =
        runSsrt({"compare", "--scene", "spheres", "--width", "48", "--height", "136",
                 "--reference-spp", "2", "--shadow-map-size", "128", "-j", "2", "--repeats", "1",
                 "--cache-dir", dir.file("cache")});
    INFO(c.err);
    CHECK(c.code == 0);
    CHECK(contains(c.err, "reference: from the cache"));
    // More bands than tile rows (3 of 64 pixels) is a usage error; bands of two references do
    // not merge.
    const test::CliResult tooMany = reference({"-o", dir.file("r.exr"), "--shard", "1/64"});
    CHECK(tooMany.code == cli::kExitUsage);
    CHECK(contains(tooMany.err, "at most 3 shards"));
    const test::CliResult mixed =
        runSsrt({"merge", "-o", dir.file("mixed.exr"), band0, dir.file("other.shard-2-of-2.exr")});
    CHECK(mixed.code != 0);
    CHECK(contains(mixed.err, "another reference"));
    CHECK(!std::filesystem::exists(dir.file("mixed.exr")));
}

TEST_CASE("shard: a multi-frame render in 3 shards writes the unsharded files, across a cut") {
    const NoSlurm clean;
    TempDir dir;
    // Six frames over four keys at times 0, 0.6, ..., 3, a cut at key 1 (t = 1): frames 0-1
    // one shot, 2-5 the next (the history restarts at frame 2), so shard 2/3's block [2, 4)
    // starts at the cut and shard 3/3's [4, 6) replays frames 2-3 for their history.
    writeFile(dir.file("cut.json"), R"({
  "scene": "cornell",
  "camera": { "path": { "keys": [
    { "time": 0, "position": [0.0, 1.15, 3.2], "target": [0.0, 0.85, 0.0] },
    { "time": 1, "position": [0.3, 1.25, 3.0], "target": [0.1, 0.8, 0.0], "cut": true },
    { "time": 2, "position": [-0.4, 1.0, 2.6], "target": [0.2, 0.9, 0.0] },
    { "time": 3, "position": [-0.3, 1.05, 2.5], "target": [0.2, 0.9, 0.0] } ] } },
  "render": { "frames": 6, "warmupFrames": 1 }
})");
    const auto render = [&](const std::string& out, std::optional<std::string> shard) {
        std::vector<std::string> args = {"render",
                                         "--shot",
                                         dir.file("cut.json"),
                                         "--width",
                                         "64",
                                         "--height",
                                         "36",
                                         "--shadow-map-size",
                                         "128",
                                         "--hit-radiance",
                                         "reprojected",
                                         "-j",
                                         "2",
                                         "-o",
                                         dir.file(out)};
        if (shard) args.insert(args.end(), {"--shard", *shard});
        const test::CliResult r = runSsrt(args);
        INFO(r.err);
        REQUIRE(r.code == 0);
        return r.err;
    };
    render("full.exr", std::nullopt);
    std::filesystem::create_directory(dir.file("s"));
    std::vector<std::string> progress;
    for (int k = 1; k <= 3; ++k) progress.push_back(render("s/full.exr", std::to_string(k) + "/3"));
    CHECK(contains(progress[0], "frames 0 to 1..."));
    CHECK(contains(progress[1], "frames 2 to 3..."));
    CHECK(contains(progress[2], "frames 4 to 5 (history from frame 2)"));
    CHECK(contains(progress[2], "history frame 4/6"));  // frame 3, 1-based
    for (int i = 0; i < 6; ++i) {
        const std::string name = "full_000" + std::to_string(i) + ".exr";
        INFO(name);
        REQUIRE(std::filesystem::exists(dir.file("s/" + name)));
        CHECK(test::readFile(dir.file("s/" + name)) == test::readFile(dir.file(name)));
    }
    CHECK(std::distance(std::filesystem::directory_iterator(dir.file("s")),
                        std::filesystem::directory_iterator()) == 6);
}

#endif  // SSRT_CLI_LIB
