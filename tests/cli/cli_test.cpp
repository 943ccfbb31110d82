// The ssrt command, driven in-process through runCli: bad input gives one error line, the
// right exit status and no file; help tells the truth about defaults; a render writes a file.
#include <doctest/doctest.h>

#include "cli/cli_run.h"
#include "temp_dir.h"

// Needs the ssrt_cli_lib target, which defines SSRT_CLI_LIB for those linking it.
#ifdef SSRT_CLI_LIB

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli.h"
#include "cli/render_command.h"
#include "io/image_io.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;
namespace fs = std::filesystem;

namespace {

using test::TempDir;

using Result = test::CliResult;
using test::contains;

Result run(std::vector<std::string> args) { return test::runSsrt(std::move(args)); }
using test::isOneErrorLine;

using test::ScopedEnv;

}  // namespace

TEST_CASE("cli: help lists the commands and tells the truth about defaults") {
    const Result top = run({"--help"});
    CHECK(top.code == 0);
    CHECK(contains(top.out, "render"));
    CHECK(contains(top.out, "scenes"));
    CHECK(top.err.empty());
    // The exit statuses the footer and README.md promise: 1 means only "the images differ".
    CHECK(cli::kExitDiffer == 1);
    CHECK(cli::kExitUsage == 2);
    CHECK(cli::kExitFailure == 3);
    CHECK(contains(top.out, "2 bad command line, 3 the work failed"));

    const Result help = run({"render", "--help"});
    CHECK(help.code == 0);
    const RenderSettings d;
    for (const std::string& part : std::vector<std::string>{
             "--width INT=" + std::to_string(d.width),
             "--height INT=" + std::to_string(d.height),
             "--threads INT=" + std::to_string(d.threads),
             "--isa ISA=auto",
             "--shadow-map-size INT=" + std::to_string(d.shadowMapSize),
             "--exposure FLOAT=1",
             "--frame INT=0",
             "--output FILE",
             "--scene NAME=" + builtinScenes().front().name,
             "--stats",
             "--quiet",
             "--marcher NAME=" + std::string(marcherName(d.trace.marcher)),
             "--ssr-method NAME=" + std::string(ssrMethodName(d.trace.ssrMethod)),
             "--ssr-spp INT=" + std::to_string(d.trace.ssrSpp),
             "--ssgi-spp INT=" + std::to_string(d.trace.ssgiSpp),
             "--max-steps INT=" + std::to_string(d.trace.march.maxSteps),
             "--no-ssr",
             "--no-ssgi",
             "--ssr-resolve MODE=reuse",
             "--hit-radiance SOURCE=current",
             "--trace-hidden"}) {
        CAPTURE(part);
        CHECK(contains(help.out, part));
    }
}

TEST_CASE("cli: no command, an unknown command or option is a usage error") {
    for (const auto& args : std::vector<std::vector<std::string>>{
             {}, {"draw"}, {"render", "--colour", "red"}, {"render", "--width"}}) {
        const Result r = run(args);
        CHECK(r.code == cli::kExitUsage);
        CHECK(isOneErrorLine(r.err));
    }
}

TEST_CASE("cli: a mistyped command is named, with the nearest one") {
    const Result r = run({"rendr", "--width", "64"});
    CHECK(r.code == cli::kExitUsage);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "'rendr'; did you mean render?"));
    CHECK(!contains(run({"paint"}).err, "did you mean"));  // nothing near
}

TEST_CASE(
    "cli: a mistyped option, scene or shot key names the nearest one, and the command's help") {
    TempDir dir;
    const std::string out = dir.file("never.png");
    struct Case {
        std::vector<std::string> args;
        std::string says;
    };
    const std::string shot = dir.file("typo.json");
    std::FILE* f = std::fopen(shot.c_str(), "w");
    REQUIRE(f);
    std::fputs("{ \"scene\": \"cornell\", \"render\": { \"expsure\": 2 } }", f);
    std::fclose(f);
    for (const Case& c : std::vector<Case>{
             {{"render", "--widht", "320", "-o", out},
              "unknown option '--widht' for 'ssrt render'; did you mean --width? (see 'ssrt "
              "render --help')"},
             {{"render", "--quallity=high", "-o", out}, "did you mean --quality?"},
             {{"compare", "--scnee", "cornell"},
              "did you mean --scene? (see 'ssrt compare --help')"},
             {{"render", "-s", "cornel", "-o", out},
              "unknown scene 'cornel'; did you mean cornell?"},
             {{"render", "--shot", shot, "-o", out}, "did you mean exposure?"}}) {
        CAPTURE(c.args);
        const Result r = run(c.args);
        CHECK(r.code != 0);
        CHECK(isOneErrorLine(r.err));
        CHECK(contains(r.err, c.says));
    }
    // Nothing near: no suggestion.
    CHECK(!contains(run({"render", "--frobnicate", "-o", out}).err, "did you mean"));
    CHECK(dir.empty() == false);  // (the shot file alone)
}

TEST_CASE("cli: every bad number is one error line naming the option and value, no file") {
    TempDir dir;
    const std::string output = dir.file("out.png");
    const std::vector<std::pair<std::string, std::vector<std::string>>> bad{
        {"--width", {"0", "-5", "8193", "abc", "12px", "1e3", "99999999999999999999", "", "7.5"}},
        {"--height", {"nan", "0"}},
        {"--threads", {"-1", "257"}},
        {"--exposure", {"nan", "inf", "0", "-1", "bright", "1e39"}},
        {"--shadow-map-size", {"8", "9000"}},
        {"--frame", {"-1", "4294967296"}},
        {"--isa", {"avx9"}},
        {"--scene", {"nosuch"}},
        {"--marcher", {"bvh", "HIZ"}},
        {"--ssr-method", {"phong"}},
        {"--ssr-spp", {"0", "65"}},
        {"--ssgi-spp", {"-1", "x"}},
        {"--max-steps", {"0", "1048577"}},  // MarchSettings's range, 1 to 2^20
        {"--thickness", {"0", "nan", "-0.1"}},
        {"--ssr-resolve", {"blur"}},
        {"--hit-radiance", {"previous"}},
        {"--quality", {"extreme", ""}}};
    // (no structured binding: clang 14 cannot capture one in CAPTURE's lambda)
    for (const auto& entry : bad) {
        const std::string& option = entry.first;
        const std::vector<std::string>& values = entry.second;
        for (const std::string& value : values) {
            CAPTURE(option);
            CAPTURE(value);
            const Result r = run({"render", option, value, "-o", output, "--quiet"});
            CHECK(r.code == cli::kExitUsage);
            CHECK(isOneErrorLine(r.err));
            CHECK(contains(r.err, option));
            CHECK(contains(r.err, "'" + value + "'"));
        }
    }
    CHECK(dir.empty());
}

TEST_CASE("cli: an unknown scene is named and the known ones listed") {
    TempDir dir;
    const Result r = run({"render", "--scene", "teapot", "-o", dir.file("never.png")});
    CHECK(r.code == cli::kExitUsage);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "teapot"));
    for (const auto& scene : builtinScenes()) CHECK(contains(r.err, scene.name));
    CHECK(dir.empty());
}

TEST_CASE("cli: a glTF scene that cannot be loaded is one error line, exit 3, no file") {
    TempDir dir;
    const std::string broken = dir.file("broken.gltf");
    std::FILE* f = std::fopen(broken.c_str(), "w");
    REQUIRE(f);
    std::fputs("{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": 5 }", f);
    std::fclose(f);
    for (const std::string& scene : {broken, dir.file("missing.glb")}) {
        CAPTURE(scene);
        const Result r = run({"render", "--scene", scene, "-o", dir.file("out.png")});
        CHECK(r.code == cli::kExitFailure);
        CHECK(isOneErrorLine(r.err));
        CHECK(contains(r.err, scene));
        CHECK_FALSE(fs::exists(dir.file("out.png")));
    }
}

namespace {

// A triangle and a POINTS primitive over the same three vertices (tri.bin beside it), in a
// file that also lists an extension ssrt does not support: two warnings.
std::string writeWarningGltf(const TempDir& dir) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::FILE* bin = std::fopen(dir.file("tri.bin").c_str(), "wb");
    REQUIRE(bin);
    std::fwrite(positions, sizeof positions, 1, bin);
    std::fclose(bin);
    const std::string path = dir.file("warn.gltf");
    std::FILE* f = std::fopen(path.c_str(), "w");
    REQUIRE(f);
    std::fputs(R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}},
                                   {"attributes": {"POSITION": 0}, "mode": 0}]}],
        "buffers": [{"uri": "tri.bin", "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3}],
        "extensionsUsed": ["KHR_materials_clearcoat"]})",
               f);
    std::fclose(f);
    return path;
}

}  // namespace

TEST_CASE("cli: a glTF file's warnings are 'ssrt: warning:' lines, even with --quiet") {
    TempDir dir;
    const std::string scene = writeWarningGltf(dir);
    const Result r = run({"render", "--scene", scene, "--width", "8", "--height", "8", "--threads",
                          "1", "-o", dir.file("out.png"), "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(r.err == "ssrt: warning: " + scene +
                       ": extension KHR_materials_clearcoat is used but not supported: ignored\n"
                       "ssrt: warning: " +
                       scene +
                       ": 1 point or line primitive skipped (only triangles, strips and fans are "
                       "rendered)\n");
    CHECK(fs::exists(dir.file("out.png")));
    // A built-in scene warns of nothing.
    const Result plain = run({"render", "--width", "8", "--height", "8", "--threads", "1", "-o",
                              dir.file("plain.png"), "-q", "--strict"});
    CHECK(plain.code == 0);
    CHECK(plain.err.empty());
}

TEST_CASE("cli: --strict makes a glTF warning an error: exit 3, one line, no file") {
    TempDir dir;
    const std::string scene = writeWarningGltf(dir);
    const std::string shot = dir.file("shot.json");
    std::FILE* f = std::fopen(shot.c_str(), "w");
    REQUIRE(f);
    std::fputs(("{\"scene\": \"" + scene + "\"}").c_str(), f);
    std::fclose(f);
    const std::vector<std::vector<std::string>> commands = {
        {"render", "--scene", scene}, {"render", "--shot", shot}, {"compare", "--scene", scene}};
    for (std::vector<std::string> args : commands) {
        args.insert(args.end(), {"--width", "8", "--height", "8", "--threads", "1", "--strict",
                                 "-o", dir.file("out.exr")});
        CAPTURE(args[2]);
        const Result r = run(args);
        CHECK(r.code == cli::kExitFailure);
        CHECK(isOneErrorLine(r.err));
        CHECK(contains(r.err, scene + ": extension KHR_materials_clearcoat is used"));
        CHECK(contains(r.err, "strict"));
        CHECK_FALSE(fs::exists(dir.file("out.exr")));
    }
}

TEST_CASE("cli: a bad output path fails before rendering and leaves no file") {
    TempDir dir;
    Result r = run({"render", "-o", dir.file("out.jpg")});
    CHECK(r.code == cli::kExitUsage);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, ".jpg"));

    r = run({"render", "-o", dir.file("missing/out.png")});
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "does not exist"));
    CHECK_FALSE(contains(r.err, "rendering"));  // no progress: it failed before any work
    CHECK(dir.empty());
}

TEST_CASE("cli: a bad SSRT_ISA is named when --isa is auto") {
    TempDir dir;
    ScopedEnv env("SSRT_ISA", "mmx");
    const Result r = run({"render", "-o", dir.file("out.png")});
    CHECK(r.code == cli::kExitUsage);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "SSRT_ISA"));
    CHECK(contains(r.err, "mmx"));
    CHECK(dir.empty());
}

TEST_CASE("cli: an ISA this CPU lacks is a runtime error that lists what it runs") {
    std::optional<Isa> missing;
    for (Isa isa : kAllIsas)
        if (isaBuilt(isa) && !isaSupported(isa)) missing = isa;
    if (!missing) return;  // this machine runs them all
    TempDir dir;
    const Result r =
        run({"render", "--isa", std::string(isaName(*missing)), "-o", dir.file("out.png")});
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "scalar"));
    CHECK(dir.empty());
}

TEST_CASE("cli: an ISA left out of the build is a runtime error naming the build option") {
    CHECK(isaBuilt(Isa::Scalar));
    for (Isa isa : supportedIsas()) CHECK(isaBuilt(isa));
    std::optional<Isa> left;
    for (Isa isa : kAllIsas)
        if (isaOfThisArchitecture(isa) && !isaBuilt(isa)) left = isa;
    if (!left) return;  // a build of every family (cmake/kernels.cmake's default)
    TempDir dir;
    const Result r =
        run({"render", "--isa", std::string(isaName(*left)), "-o", dir.file("out.png")});
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "not built"));
    CHECK(contains(r.err, "SSRT_ISAS"));
    CHECK(dir.empty());
}

TEST_CASE("cli: an ISA of the other architecture is a runtime error naming it") {
    // NEON in an x86-64 binary, SSE2 in an aarch64 one.
    const Isa other = isaOfThisArchitecture(Isa::NEON) ? Isa::SSE2 : Isa::NEON;
    CHECK(!isaBuilt(other));
    CHECK(!isaSupported(other));
    TempDir dir;
    const Result r =
        run({"render", "--isa", std::string(isaName(other)), "-o", dir.file("out.png")});
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, other == Isa::NEON ? "for aarch64 CPUs" : "for x86-64 CPUs"));
    CHECK(contains(r.err, "scalar"));
    CHECK(dir.empty());
}

TEST_CASE("cli: --help names the ISAs of this architecture") {
    const Result r = run({"render", "--help"});
    CHECK(r.code == 0);
    CHECK(contains(r.out, "auto, " + isaChoices()));
    CHECK(contains(isaChoices(), isaOfThisArchitecture(Isa::NEON) ? "neon" : "avx512"));
    CHECK(!contains(isaChoices(), isaOfThisArchitecture(Isa::NEON) ? "avx512" : "neon"));
}

TEST_CASE("cli: scenes lists every built-in scene with its description") {
    const Result r = run({"scenes"});
    CHECK(r.code == 0);
    for (const auto& scene : builtinScenes()) {
        CHECK(contains(r.out, scene.name));
        CHECK(contains(r.out, scene.description));
    }
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == long(builtinScenes().size()));
}

TEST_CASE("cli: --stats prints every pass and every raster counter of both passes") {
    FrameStats stats;
    stats.passes = {{"shadow", 1.25}, {"visibility", 2.5}, {"resolve", 0.125}};
    stats.isa = Isa::SSE2;
    stats.threads = 3;
    // Distinct values per counter, so a row missing or printed from the wrong pass shows.
    uint64_t* vis = &stats.visibility.trianglesIn;
    uint64_t* sha = &stats.shadow.trianglesIn;
    constexpr int kCounters = sizeof(RasterStats) / sizeof(uint64_t);
    for (int i = 0; i < kCounters; ++i) {
        vis[i] = 1000 + i;
        sha[i] = 2000 + i;
    }
    stats.memory = {{"gbuffer", 3000000}, {"denoise scratch", 1000000}};
    std::ostringstream out;
    cli::printStats(out, stats, 1.0e6, 4.5, 7.25);
    const std::string text = out.str();
    // The memory table: bytes per pixel of the million pixels, megabytes, the sum.
    CHECK(contains(text, "gbuffer"));
    CHECK(contains(text, "denoise scratch"));
    CHECK(contains(text, "in all"));
    CHECK(contains(text, "3.0"));
    CHECK(contains(text, "4.0\n"));
    CHECK(contains(text, "sse2"));
    CHECK(contains(text, "3 threads"));
    for (const char* part : {"shadow", "visibility", "resolve", "1.250", "2.500", "0.125", "3.875",
                             "4.500", "image write", "7.250"})
        CHECK(contains(text, part));
    for (int i = 0; i < kCounters; ++i) {
        CAPTURE(i);
        CHECK(contains(text, std::to_string(1000 + i) + " "));
        CHECK(contains(text, std::to_string(2000 + i) + "\n"));
    }
}

TEST_CASE("cli: a PNG render makes no plane only an EXR shows (the --stats memory table)") {
    TempDir dir;
    for (const char* name : {"frame.png", "frame.exr"}) {
        const bool exr = std::string(name).find(".exr") != std::string::npos;
        CAPTURE(std::string(name));
        const Result r = run({"render", "--width", "24", "--height", "16", "--threads", "1", "-o",
                              dir.file(name), "--stats"});
        REQUIRE_MESSAGE(r.code == 0, r.err);
        // (a PNG's G-buffer and traced planes went back to the pool once read)
        CHECK(contains(r.out, "  normal ") == exr);
        CHECK(contains(r.out, "  instanceId ") == exr);
        CHECK(contains(r.out, "  denoisedDiffuse ") == exr);
    }
}

TEST_CASE("cli: render writes the file, reports progress and stats") {
    TempDir dir;
    const std::string path = dir.file("frame.exr");
    Result r =
        run({"render", "--width", "24", "--height", "16", "--threads", "1", "-o", path, "--stats"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(contains(r.err, "rendering " + builtinScenes().front().name + " 24x16 on "));
    CHECK(contains(r.err, ", 1 thread..."));
    CHECK(contains(r.err, "wrote " + path));
    CHECK(contains(r.out, "pixels written"));
    CHECK(contains(r.out, "image write"));
    const auto channels = readChannelNames(path);
    for (const char* name : {"display.R", "color.R", "viewZ"})
        CHECK(std::find(channels.begin(), channels.end(), name) != channels.end());

    r = run({"render", "--width", "8", "--height", "8", "-o", dir.file("quiet.png"), "-q"});
    CHECK(r.code == 0);
    CHECK(r.err.empty());
    CHECK(r.out.empty());
    CHECK(fs::exists(dir.file("quiet.png")));
}

TEST_CASE("cli: --layers writes exactly the groups named, and a bad group writes nothing") {
    TempDir dir;
    const std::vector<std::string> size{"render", "--width", "24", "--height",
                                        "16",     "-j",      "1",  "-q"};
    const auto render = [&](const std::string& file, std::vector<std::string> extra) {
        std::vector<std::string> args = size;
        args.insert(args.end(), extra.begin(), extra.end());
        args.insert(args.end(), {"-o", dir.file(file)});
        return run(args);
    };
    const auto names = [&](const std::string& file) {
        std::vector<std::string> n = readChannelNames(dir.file(file));
        std::sort(n.begin(), n.end());
        return n;
    };
    REQUIRE(render("all.exr", {}).code == 0);
    const std::vector<std::string> all = names("all.exr");
    // Each group alone: its own planes, none of another's; together they are every layer.
    std::vector<std::string> united;
    const std::pair<const char*, const char*> groups[] = {
        {"color", "display.R"}, {"gbuffer", "viewZ"}, {"trace", "ssr.R"}};
    for (const auto& entry : groups) {
        // (not a structured binding: clang 14 cannot capture one in CAPTURE's lambda)
        const char* const group = entry.first;
        const char* const member = entry.second;
        CAPTURE(group);
        const Result r = render(std::string(group) + ".exr", {"--layers", group});
        REQUIRE_MESSAGE(r.code == 0, r.err);
        const std::vector<std::string> got = names(std::string(group) + ".exr");
        CHECK(std::find(got.begin(), got.end(), member) != got.end());
        for (const auto& [other, otherMember] : groups)
            if (std::string(other) != group)
                CHECK(std::find(got.begin(), got.end(), otherMember) == got.end());
        united.insert(united.end(), got.begin(), got.end());
    }
    std::sort(united.begin(), united.end());
    CHECK(united == all);  // disjoint (no name twice) and complete
    REQUIRE(render("two.exr", {"--layers", "gbuffer,colour"}).code == 0);
    CHECK(names("two.exr").size() == names("color.exr").size() + names("gbuffer.exr").size());
    REQUIRE(render("every.exr", {"--layers", "all", "--exr-compression", "none"}).code == 0);
    CHECK(names("every.exr") == all);
    CHECK(fs::file_size(dir.file("every.exr")) > fs::file_size(dir.file("all.exr")));

    const auto listing = dir.listing();
    for (const std::vector<std::string>& bad :
         {std::vector<std::string>{"--layers", "color,shading"},
          std::vector<std::string>{"--layers", "color,"},
          std::vector<std::string>{"--exr-compression", "dwaa"},
          std::vector<std::string>{"--layers", "truth"}}) {
        CAPTURE(bad[1]);
        const Result r = render("bad.exr", bad);
        CHECK(r.code == cli::kExitUsage);
        CHECK(isOneErrorLine(r.err));
        CHECK(contains(r.err, bad[0]));
        CHECK_FALSE(contains(r.err, "rendering"));
    }
    CHECK(contains(render("bad.exr", {"--layers", "shading"}).err,
                   "one of color, gbuffer, trace, truth"));
    CHECK(dir.listing() == listing);

    // A PNG is the preview whatever --layers says: written, with a warning.
    const Result png = render("preview.png", {"--layers", "gbuffer"});
    CHECK(png.code == 0);
    CHECK(contains(png.err, "ssrt: warning: --layers and --exr-compression apply to EXR"));
    CHECK(fs::exists(dir.file("preview.png")));
}

TEST_CASE("cli: the screen-space passes write their layers and counters, and can be turned off") {
    TempDir dir;
    const std::string path = dir.file("trace.exr");
    Result r = run({"render", "--width", "48", "--height", "32", "--threads", "1", "--marcher",
                    "dda", "--ssr-method", "ggx_ndf", "--ssr-spp", "2", "--ssr-resolve", "mip",
                    "-o", path, "--stats", "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    for (const char* part : {"ssr march", "ssgi march", "composite", "trace counter",
                             "miss: left_screen", "steps per ray, p95", "lanes active %"})
        CHECK(contains(r.out, part));
    auto channels = readChannelNames(path);
    for (const char* name : {"ssr.R", "ssrOpacity", "ssrHit", "ssrHitDistance", "ssrSteps",
                             "ssgi.G", "ssgiHit", "ssgiHitDistance", "ssgiSteps"})
        CHECK(std::find(channels.begin(), channels.end(), name) != channels.end());

    r = run({"render", "--width", "48", "--height", "32", "--no-ssr", "--no-ssgi", "-o", path,
             "--stats", "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_FALSE(contains(r.out, "trace counter"));
    channels = readChannelNames(path);
    CHECK(std::find(channels.begin(), channels.end(), "ssr.R") == channels.end());
    CHECK(std::find(channels.begin(), channels.end(), "ssgi.R") == channels.end());
}

TEST_CASE("cli: --trace-hidden traces the rays the composite hides, and --stats counts them") {
    // Cornell's walls are past the SSR roughness fade and its mirror is a metal: by default
    // they get no SSR / SSGI ray, counted on the "hidden, no ray" row; --trace-hidden traces
    // them (the row reads 0).
    TempDir dir;
    const auto hiddenRow = [](const std::string& out) {
        const std::size_t at = out.find("hidden, no ray");
        REQUIRE(at != std::string::npos);
        std::istringstream row(out.substr(at + std::string("hidden, no ray").size()));
        long long ssr = -1, ssgi = -1;
        row >> ssr >> ssgi;
        return std::pair{ssr, ssgi};
    };
    const std::vector<std::string> base{"render",    "--width", "64",      "--height", "40",
                                        "--threads", "1",       "--stats", "-q"};
    std::vector<std::string> cut = base, all = base;
    cut.insert(cut.end(), {"-o", dir.file("cut.png")});
    all.insert(all.end(), {"--trace-hidden", "-o", dir.file("all.png")});
    const Result a = run(cut), b = run(all);
    REQUIRE_MESSAGE(a.code == 0, a.err);
    REQUIRE_MESSAGE(b.code == 0, b.err);
    const auto [ssrCut, ssgiCut] = hiddenRow(a.out);
    const auto [ssrAll, ssgiAll] = hiddenRow(b.out);
    CHECK(ssrCut > 100);
    CHECK(ssgiCut > 0);
    CHECK(ssrAll == 0);
    CHECK(ssgiAll == 0);
}

#else
#pragma message("tests/cli/cli_test.cpp skipped: link ssrt_cli_lib (defines SSRT_CLI_LIB)")
#endif
