// Sequences in `render`, `compare` and `sweep`, in-process on tiny frames: warm-up frames are
// the first frames of a longer sequence, bit for bit; a camera cut restarts the history, so
// the frame at the cut is that frame rendered fresh; compare and sweep report one row per
// frame, with the flicker of a still camera (0 when nothing is random).
//
// Today's history is the last colour, read by reprojected SSR hits: --hit-radiance
// reprojected makes the history change the image, so the tests below can tell whether it was
// carried or restarted.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/cli_run.h"
#include "cli/options.h"
#include "cli/sequence.h"
#include "io/image_io.h"
#include "renderer/layer_groups.h"
#include "temp_dir.h"

using namespace ssrt;
using test::contains;
using test::isOneErrorLine;
using test::runSsrt;
using test::TempDir;

namespace {

using Result = test::CliResult;

using test::writeFile;
std::string bytes(const std::string& path) { return test::readFile(path); }
std::vector<std::string> lines(const std::string& text) { return test::textLines(text); }
std::vector<std::string> cells(const std::string& line) { return test::csvCells(line); }

// A tiny render whose history shows in the image.
std::vector<std::string> tinyRender(std::vector<std::string> args) {
    for (const char* a :
         {"--scene", "cornell", "--width", "64", "--height", "36", "--shadow-map-size", "128",
          "--hit-radiance", "reprojected", "-j", "2", "-q"})
        args.push_back(a);
    return args;
}

// Small and quick, as tests/cli/truth_cli_test.cpp's.
std::vector<std::string> tinyTruth(std::vector<std::string> args, const TempDir& dir) {
    for (const char* a : {"--width", "64", "--height", "36", "--reference-spp", "2", "--repeats",
                          "1", "--shadow-map-size", "128", "-j", "2"})
        args.push_back(a);
    args.insert(args.end(), {"--cache-dir", dir.file("cache")});
    return args;
}

// Five frames over four keys of the cornell box, a cut at key 2 (t = 2): frame times 0, 0.75,
// 1.5, 2.25, 3, so frame 3 is the first of the second shot.
const char* const kCutShot = R"({
  "scene": "cornell",
  "camera": {
    "path": {
      "keys": [
        { "time": 0, "position": [0.0, 1.15, 3.2], "target": [0.0, 0.85, 0.0], "fovY": 40 },
        { "time": 1, "position": [0.3, 1.25, 3.0], "target": [0.1, 0.8, 0.0], "fovY": 38 },
        { "time": 2, "position": [-0.4, 1.0, 2.6], "target": [0.2, 0.9, 0.0], "cut": true },
        { "time": 3, "position": [-0.3, 1.05, 2.5], "target": [0.2, 0.9, 0.0] }
      ]
    }
  },
  "render": { "frames": 5, "frame": 3 }
})";

}  // namespace

TEST_CASE("cli sequence: render, compare and sweep take --frames and --warmup-frames") {
    for (const char* command : {"render", "compare", "sweep"}) {
        CAPTURE(command);
        const Result help = runSsrt({command, "--help"});
        CHECK(help.code == 0);
        CHECK(contains(help.out, "--frames INT=1"));
        CHECK(contains(help.out, "--warmup-frames INT=0"));
        CHECK(contains(help.out, "--per-frame") == (std::string(command) != "render"));
    }
}

TEST_CASE("cli sequence: warm-up frames are the first frames of a longer sequence, bit for bit") {
    TempDir dir;
    // Two warm-up frames before frame 5 take indices 3 and 4: the last of frames 3, 4, 5.
    Result r = runSsrt(
        tinyRender({"render", "--frame", "5", "--warmup-frames", "2", "-o", dir.file("warm.exr")}));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(dir.listing() == std::vector<std::string>{"warm.exr"});  // warm-up frames not written
    r = runSsrt(
        tinyRender({"render", "--frame", "3", "--frames", "3", "-o", dir.file("long.exr")}));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const std::string warm = bytes(dir.file("warm.exr"));
    CHECK(!warm.empty());
    CHECK(warm == bytes(dir.file("long_0002.exr")));

    // The warm-up changes the image (the history is read) and --warmup-frames 0 is the plain
    // render's bits.
    r = runSsrt(tinyRender({"render", "--frame", "5", "-o", dir.file("cold.exr")}));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    r = runSsrt(
        tinyRender({"render", "--frame", "5", "--warmup-frames", "0", "-o", dir.file("zero.exr")}));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(warm != bytes(dir.file("cold.exr")));
    CHECK(bytes(dir.file("zero.exr")) == bytes(dir.file("cold.exr")));

    // Progress: a line per warm-up frame, then the frames'
    r = runSsrt({"render", "--width", "16", "--height", "16", "--shadow-map-size", "64",
                 "--warmup-frames", "2", "--frames", "2", "-o", dir.file("p.png")});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(contains(r.err, "2 frames after 2 warm-up frames"));
    CHECK(contains(r.err, "warm-up 1/2\nwarm-up 2/2\nframe 1/2: wrote "));
}

TEST_CASE("cli sequence: warm-up frames look from frame 0's camera, numbered just before it") {
    TempDir dir;
    writeFile(dir.file("cut.json"), kCutShot);
    cli::RenderOptions o;
    o.shot = dir.file("cut.json");
    cli::SceneRequest request = cli::loadSceneRequest(o);
    std::ostringstream err;
    cli::loadScene(request, err);
    REQUIRE(request.firstFrame == 3u);
    o.warmupFrames = "4";
    const cli::SequencePlan plan = cli::sequencePlanFrom(o, request);
    CHECK(plan.frames == 5);
    CHECK(plan.warmup == 4);
    const cli::FrameSequence sequence(request, plan);
    REQUIRE(sequence.steps() == 9);
    const Camera first = request.path.at(0.0, request.scene.camera);
    for (int step = 0; step < 4; ++step) {
        CAPTURE(step);
        const FrameInput in = sequence.input(step);
        CHECK(sequence.isWarmup(step));
        CHECK(cli::sameCamera(in.camera, first));
        CHECK(cli::sameCamera(in.previousCamera, first));
        CHECK(!in.resetHistory);
        // 3 - 4 + step, modulo 2^32: 4294967295, 0, 1, 2
        CHECK(in.frameIndex == uint32_t(3u - 4u + uint32_t(step)));
    }
    CHECK(sequence.input(0).frameIndex == 4294967295u);
    CHECK(sequence.input(4).frameIndex == 3u);
    CHECK(cli::sameCamera(sequence.input(4).camera, first));
    CHECK(sequence.stillSincePrevious(4));   // frame 0 looks from the warm-up's camera
    CHECK(!sequence.stillSincePrevious(5));  // the camera moves from frame 1 on
    // The cut: frame 3 (step 7) restarts the history and has no motion
    for (int step = 4; step < 9; ++step) {
        CAPTURE(step);
        const FrameInput in = sequence.input(step);
        CHECK(in.resetHistory == (step == 7));
        CHECK(cli::sameCamera(
            in.camera, request.path.at(request.path.frameTime(step - 4, 5), request.scene.camera)));
        if (step == 7) CHECK(cli::sameCamera(in.previousCamera, in.camera));
        else CHECK(cli::sameCamera(in.previousCamera, sequence.input(step - 1).camera));
    }
}

TEST_CASE("cli sequence: the frame at a camera cut is that frame rendered with a fresh history") {
    TempDir dir;
    writeFile(dir.file("cut.json"), kCutShot);
    const std::vector<std::string> args = {"render",
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
                                           "2"};
    std::vector<std::string> render = args;
    render.insert(render.end(), {"-o", dir.file("seq.exr")});
    const Result r = runSsrt(render);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(contains(r.err, "frame 4/5: wrote " + dir.file("seq_0003.exr") +
                              " (camera cut: history restarted)"));

    // Frames 3 (at the cut) and 4 rendered alone, from the same inputs, without a history.
    // (The shot's frame index is 3; there is no warm-up, so step i is frame i.)
    cli::RenderOptions o;
    o.shot = dir.file("cut.json");
    o.settings = {{"width", "64"},
                  {"height", "36"},
                  {"shadowMapSize", "128"},
                  {"hitRadiance", "reprojected"},
                  {"threads", "2"}};
    cli::SceneRequest request = cli::loadSceneRequest(o);
    std::ostringstream err;
    cli::loadScene(request, err);
    const cli::FrameSequence sequence(request, cli::sequencePlanFrom(o, request));
    const Renderer renderer(request.settings);
    for (int i : {3, 4}) {
        CAPTURE(i);
        // Frame 3's previous camera is its own (the cut), frame 4's frame 3's: only the
        // history differs from the sequence's render.
        const FrameInput in = sequence.input(i);
        Frame fresh = renderer.renderWithoutHistory(request.scene, in);
        const std::string file = dir.file("fresh_" + std::to_string(i) + ".exr");
        writeImage(file, frameLayers(fresh));
        const std::string inSequence = bytes(dir.file("seq_000" + std::to_string(i) + ".exr"));
        // At the cut: the same bits. The frame after it read the cut frame's history.
        if (i == 3) CHECK(bytes(file) == inSequence);
        else CHECK(bytes(file) != inSequence);
    }
}

TEST_CASE("cli sequence: bad --frames and --warmup-frames are one error line, nothing written") {
    TempDir dir;
    for (const char* value : {"-1", "1.5", "x", "", "100001", "1e3"}) {
        for (const char* command : {"render", "compare", "sweep"}) {
            CAPTURE(value);
            CAPTURE(command);
            std::vector<std::string> args = {command, "--warmup-frames", value};
            args.insert(args.end(),
                        {"-o", dir.file(std::string(command) == "sweep" ? "s.csv" : "o.png")});
            const Result r = runSsrt(args);
            CHECK(r.code == cli::kExitUsage);
            CHECK(isOneErrorLine(r.err));
            CHECK(contains(r.err, std::string("--warmup-frames: invalid value '") + value +
                                      "' (expected an integer from 0 to 100000)"));
        }
    }
    for (const char* command : {"compare", "sweep"}) {
        const Result r = runSsrt({command, "--frames", "0"});
        CHECK(r.code == cli::kExitUsage);
        CHECK(contains(r.err, "--frames: invalid value '0'"));
    }
    const Result p = runSsrt({"compare", "--per-frame", dir.file("frames.txt")});
    CHECK(p.code == cli::kExitUsage);
    CHECK(contains(p.err, "--per-frame: '" + dir.file("frames.txt") + "' must end in .csv"));
    CHECK(dir.empty());
}

TEST_CASE("compare --frames: one row per frame, flicker on a still camera, the last evaluated") {
    TempDir dir;
    const Result r =
        runSsrt(tinyTruth({"compare", "--scene", "spheres", "--frames", "3", "--warmup-frames", "1",
                           "--per-frame", dir.file("frames.csv")},
                          dir));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(contains(r.out, "frame 2 of 3 frames after 1 warm-up frame"));
    CHECK(contains(r.out, "per frame"));
    // One reference serves the still camera's frames
    CHECK(contains(r.err, "reference: rendered (2 spp, all bounces) for frame 0 (frame index 0)"));
    CHECK(!contains(r.err, "for frame 1"));
    const std::vector<std::string> csv = lines(bytes(dir.file("frames.csv")));
    REQUIRE(csv.size() == 4);
    CHECK(csv[0] == "frame,frame_index,cut,relmse,flicker");
    for (int i = 0; i < 3; ++i) {
        CAPTURE(i);
        const std::vector<std::string> row = cells(csv[std::size_t(i) + 1]);
        REQUIRE(row.size() == 5);
        CHECK(row[0] == std::to_string(i));
        CHECK(row[1] == std::to_string(i));
        CHECK(row[2] == "0");
        CHECK(std::stod(row[3]) > 0.0);
        // One ray per pixel, a new frame index each frame: the frames differ by noise.
        CHECK(std::stod(row[4]) > 0.0);
    }
    // The table's last row is the evaluated frame: its relMSE is the colour's
    const std::size_t at = r.out.find("color (exposed)");
    REQUIRE(at != std::string::npos);
    std::istringstream colorLine(r.out.substr(at + 15));
    std::string relMse;
    colorLine >> relMse;
    std::ostringstream fromCsv;
    fromCsv << std::scientific;
    fromCsv.precision(3);
    fromCsv << std::stod(cells(csv[3])[3]);
    CHECK(relMse == fromCsv.str());

    // A single frame prints no per-frame table
    const Result one = runSsrt(tinyTruth({"compare", "--scene", "spheres", "-q"}, dir));
    REQUIRE(one.code == 0);
    CHECK(!contains(one.out, "per frame"));
}

TEST_CASE("compare --frames on a moving path: a reference per frame, cached -- no flicker") {
    TempDir dir;
    writeFile(dir.file("cut.json"), kCutShot);
    const auto args = tinyTruth({"compare", "--shot", dir.file("cut.json"), "--frames", "4",
                                 "--per-frame", dir.file("frames.csv")},
                                dir);
    const Result first = runSsrt(args);
    REQUIRE_MESSAGE(first.code == 0, first.err);
    const Result second = runSsrt(args);
    REQUIRE_MESSAGE(second.code == 0, second.err);
    for (int i = 0; i < 4; ++i) {
        CAPTURE(i);
        const std::string frame =
            " for frame " + std::to_string(i) + " (frame index " + std::to_string(3 + i) + ")";
        CHECK(contains(first.err, "reference: rendered (2 spp, all bounces)" + frame));
        CHECK(contains(second.err, "reference: from the cache (2 spp, all bounces)" + frame));
    }
    const std::vector<std::string> csv = lines(bytes(dir.file("frames.csv")));
    REQUIRE(csv.size() == 5);
    for (int i = 0; i < 4; ++i) {
        const std::vector<std::string> row = cells(csv[std::size_t(i) + 1]);
        REQUIRE(row.size() == 5);
        CHECK(row[4].empty());  // the camera moves: flicker is not measured
        // 4 frames: times 0, 1, 2, 3; the cut at t = 2 is frame 2's
        CHECK(row[2] == (i == 2 ? "1" : "0"));
    }
    CHECK(contains(first.out, "camera cut"));
}

TEST_CASE("sweep --frames: the last frame's row, flicker 0 with the passes off") {
    TempDir dir;
    const Result r = runSsrt(tinyTruth(
        {"sweep", "--scene", "cornell", "--marchers", "off,hiz", "--frames", "3", "--warmup-frames",
         "1", "--per-frame", dir.file("frames.csv"), "-o", dir.file("s.csv"), "-q"},
        dir));
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const std::vector<std::string> csv = lines(bytes(dir.file("s.csv")));
    REQUIRE(csv.size() == 3);
    const std::vector<std::string> header = cells(csv[0]);
    const auto col = [&](const char* name) {
        return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    REQUIRE(col("flicker") < header.size());
    const std::vector<std::string> off = cells(csv[1]), hiz = cells(csv[2]);
    CHECK(off[col("marcher")] == "off");
    CHECK(off[col("frames")] == "3");
    CHECK(off[col("warmup_frames")] == "1");
    // Without the screen-space passes nothing is random: a still camera's frames are equal.
    CHECK(off[col("flicker")] == "0");
    CHECK(std::stod(hiz[col("flicker")]) > 0.0);

    const std::vector<std::string> frames = lines(bytes(dir.file("frames.csv")));
    REQUIRE(frames.size() == 7);
    CHECK(frames[0] == "setting,frame,frame_index,cut,relmse,flicker");
    for (int i = 0; i < 6; ++i) {
        CAPTURE(i);
        const std::vector<std::string> row = cells(frames[std::size_t(i) + 1]);
        REQUIRE(row.size() == 6);
        CHECK(row[0] == std::to_string(i / 3));
        CHECK(row[1] == std::to_string(i % 3));
        if (i < 3) CHECK(row[5] == "0");  // frame 0's flicker: against the warm-up frame
        else CHECK(std::stod(row[5]) > 0.0);
    }
    // The evaluated frame's relMSE is the last frame's of its setting
    CHECK(std::stod(hiz[col("relmse")]) == doctest::Approx(std::stod(cells(frames[6])[4])));
}

#endif  // SSRT_CLI_LIB
