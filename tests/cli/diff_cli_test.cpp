// `ssrt diff A B` and `ssrt render --compare FILE`, driven in-process: the table, the summary
// line and the exit status (0 within the thresholds, 1 beyond, 2 bad flags, 3 the work
// failed), the heat map, and the flags checked before any work.
#include <doctest/doctest.h>

#include "cli/cli_run.h"
#include "temp_dir.h"

// Needs the ssrt_cli_lib target, which defines SSRT_CLI_LIB for those linking it.
#ifdef SSRT_CLI_LIB

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/render_command.h"
#include "layered_image.h"

using namespace ssrt;
namespace fs = std::filesystem;

namespace {

using test::contains;
using test::isOneErrorLine;
using test::LayeredImage;
using test::TempDir;

const std::vector<std::string> kChannels{"color.R", "color.G", "color.B", "viewZ"};

test::CliResult run(std::vector<std::string> args) { return test::runSsrt(std::move(args)); }

// The table row of a layer (the line starting with its name and two spaces).
std::string rowOf(const std::string& out, const std::string& name) {
    std::size_t at = 0;
    while ((at = out.find(name + "  ", at)) != std::string::npos) {
        if (at == 0 || out[at - 1] == '\n') return out.substr(at, out.find('\n', at) - at);
        ++at;
    }
    return "";
}

// The table's columns, in order.
enum class Column { Layer, Channels, MaxError, At, RelMse, PixelsOver, Share, Verdict };

// One cell of a layer's row: the columns are two or more spaces apart, a cell holds single
// spaces at most.
std::string cell(const std::string& out, const std::string& name, Column column) {
    const std::string row = rowOf(out, name);
    std::vector<std::string> cells;
    std::size_t at = 0;
    while (at < row.size()) {
        std::size_t end = row.find("  ", at);
        if (end == std::string::npos) end = row.size();
        cells.push_back(row.substr(at, end - at));
        at = row.find_first_not_of(' ', end);
        if (at == std::string::npos) break;
    }
    return std::size_t(column) < cells.size() ? cells[std::size_t(column)] : "";
}

// a.exr and b.exr in `dir`, b the reference; `change` edits a first.
template <class Change>
void writePair(const TempDir& dir, Change change) {
    LayeredImage a(6, 4, kChannels);
    change(a);
    a.write(dir.file("a.exr"));
    LayeredImage(6, 4, kChannels).write(dir.file("b.exr"));
}

}  // namespace

TEST_CASE("cli diff: identical images are bit-identical, exit 0") {
    TempDir dir;
    writePair(dir, [](LayeredImage&) {});
    const auto r = run({"diff", dir.file("a.exr"), dir.file("b.exr")});
    CHECK(r.code == cli::kExitOk);
    CHECK(r.err.empty());
    CHECK(contains(r.out, "bit-identical: "));
    CHECK(cell(r.out, "color", Column::Verdict) == "bit-identical");
    CHECK(cell(r.out, "color", Column::Channels) == "R,G,B");
    CHECK(cell(r.out, "viewZ", Column::Verdict) == "bit-identical");
}

TEST_CASE("cli diff: a slight difference passes within a threshold, fails beyond it") {
    TempDir dir;
    writePair(dir, [](LayeredImage& a) {
        a.at("color.G", 3, 2) += 0.01f;
        a.at("color.R", 0, 0) += 0.001f;
    });
    const std::vector<std::string> pair{"diff", dir.file("a.exr"), dir.file("b.exr")};

    // Default: any difference is beyond.
    auto r = run(pair);
    CHECK(r.code == cli::kExitDiffer);
    CAPTURE(r.out);
    CHECK(cell(r.out, "color", Column::MaxError) == "0.01");
    CHECK(cell(r.out, "color", Column::At) == "(3, 2) color.G");
    CHECK(cell(r.out, "color", Column::PixelsOver) == "2");  // over the threshold 0
    CHECK(cell(r.out, "color", Column::Share) == "8.333%");  // 2 of 24
    CHECK(cell(r.out, "color", Column::Verdict) == "beyond: share over threshold");
    CHECK(cell(r.out, "viewZ", Column::Verdict) == "bit-identical");
    CHECK(contains(r.out, "DIFFER: "));
    CHECK(contains(r.out, "1 of 2 beyond a threshold"));

    // A threshold above both: within, exit 0.
    auto args = pair;
    args.insert(args.end(), {"--threshold", "0.02"});
    r = run(args);
    CHECK(r.code == cli::kExitOk);
    CHECK(cell(r.out, "color", Column::Verdict) == "within");
    CHECK(contains(r.out, "within thresholds: "));

    // Between the two: one pixel over; allowed by --max-share, refused by --max-error.
    args = pair;
    args.insert(args.end(), {"--threshold", "0.005"});
    r = run(args);
    CHECK(r.code == cli::kExitDiffer);
    CHECK(cell(r.out, "color", Column::PixelsOver) == "1");
    args.insert(args.end(), {"--max-share", "0.05"});
    CHECK(run(args).code == cli::kExitOk);
    args.insert(args.end(), {"--max-error", "0.005"});
    r = run(args);
    CHECK(r.code == cli::kExitDiffer);
    CHECK(cell(r.out, "color", Column::Verdict) == "beyond: max error");
}

TEST_CASE("cli diff: very different images fail every limit") {
    TempDir dir;
    writePair(dir, [](LayeredImage& a) {
        for (auto& [name, plane] : a.planes)
            for (int y = 0; y < plane.height(); ++y)
                for (int x = 0; x < plane.width(); ++x) plane.at(x, y) = 5.0f;
    });
    auto r = run({"diff", dir.file("a.exr"), dir.file("b.exr"), "--threshold", "0.1", "--max-share",
                  "0.5", "--max-relmse", "10"});
    CHECK(r.code == cli::kExitDiffer);
    CHECK(cell(r.out, "color", Column::Share) == "100%");
    CHECK(contains(r.out, "2 of 2 beyond a threshold"));
    r = run(
        {"diff", dir.file("a.exr"), dir.file("b.exr"), "--threshold", "10", "--max-relmse", "10"});
    CHECK(r.code == cli::kExitDiffer);
    CHECK(cell(r.out, "color", Column::Verdict) == "beyond: relMSE");
}

TEST_CASE("cli diff: a NaN in one image differs, said in words") {
    TempDir dir;
    writePair(dir, [](LayeredImage& a) {
        a.at("viewZ", 5, 1) = std::numeric_limits<float>::quiet_NaN();
    });
    const auto r = run({"diff", dir.file("a.exr"), dir.file("b.exr"), "--threshold", "1000",
                        "--max-share", "0.5"});
    CHECK(r.code == cli::kExitDiffer);
    CAPTURE(r.out);
    CHECK(cell(r.out, "viewZ", Column::MaxError) == "inf");
    CHECK(cell(r.out, "viewZ", Column::At) == "(5, 1) viewZ");
    CHECK(cell(r.out, "viewZ", Column::RelMse) == "inf");
    CHECK(cell(r.out, "viewZ", Column::PixelsOver) == "1");  // over the threshold, whatever it is
    CHECK(cell(r.out, "viewZ", Column::Share) == "4.167%");
    // 1 of 24 pixels is within --max-share 0.5, yet a NaN never passes.
    CHECK(cell(r.out, "viewZ", Column::Verdict) == "beyond: NaN or inf");
    CHECK(contains(r.out, "viewZ: 1 pixel has a NaN or infinity against a different value"));
    CHECK(cell(r.out, "color", Column::Verdict) == "bit-identical");
}

TEST_CASE("cli diff: a layer missing in one image fails, named") {
    TempDir dir;
    LayeredImage(6, 4, {"color.R", "color.G", "color.B"}).write(dir.file("a.exr"));
    LayeredImage(6, 4, {"color.R", "color.G", "color.B", "normal.X"}).write(dir.file("b.exr"));
    auto r =
        run({"diff", dir.file("a.exr"), dir.file("b.exr"), "--threshold", "1", "--max-share", "1"});
    CHECK(r.code == cli::kExitDiffer);
    CHECK(cell(r.out, "normal", Column::Verdict) == "missing in A");
    CHECK(cell(r.out, "normal", Column::Channels) == "X");
    CHECK(cell(r.out, "color", Column::Verdict) == "bit-identical");
    r = run({"diff", dir.file("b.exr"), dir.file("a.exr")});
    CHECK(r.code == cli::kExitDiffer);
    CHECK(cell(r.out, "normal", Column::Verdict) == "missing in B");
    // --layers leaves it out.
    r = run({"diff", dir.file("b.exr"), dir.file("a.exr"), "--layers", "color"});
    CHECK(r.code == cli::kExitOk);
    CHECK(contains(r.out, "bit-identical"));
}

TEST_CASE("cli diff: images of different sizes are an error, exit 3, no heat map") {
    TempDir dir;
    LayeredImage(6, 4, kChannels).write(dir.file("a.exr"));
    LayeredImage(6, 5, kChannels).write(dir.file("b.exr"));
    auto r = run({"diff", dir.file("a.exr"), dir.file("b.exr"), "--heatmap", dir.file("h.png")});
    CHECK(r.code == 3);
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "6x4"));
    CHECK(contains(r.err, "6x5"));
    CHECK(r.out.empty());
    CHECK(dir.listing() == std::vector<std::string>{"a.exr", "b.exr"});
    // A file that does not exist or is no image: exit 3 too.
    r = run({"diff", dir.file("a.exr"), dir.file("none.exr")});
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
}

TEST_CASE("cli diff: the heat map is written and its scale printed") {
    TempDir dir;
    writePair(dir, [](LayeredImage& a) { a.at("color.B", 2, 2) += 0.25f; });
    const auto r =
        run({"diff", dir.file("a.exr"), dir.file("b.exr"), "--heatmap", dir.file("heat.png")});
    CHECK(r.code == cli::kExitDiffer);
    CHECK(fs::exists(dir.file("heat.png")));
    CHECK(contains(r.out, "heat map " + dir.file("heat.png") + " of layer color"));
    CHECK(contains(r.out, "a difference up to 0.25"));
    const auto fixed =
        run({"diff", dir.file("a.exr"), dir.file("b.exr"), "--heatmap", dir.file("fixed.png"),
             "--heatmap-layer", "color", "--heatmap-scale", "2"});
    CHECK(fixed.code == cli::kExitDiffer);
    CHECK(contains(fixed.out,
                   "of layer color: black = equal, dark red to white = a difference "
                   "up to 2 (--heatmap-scale"));
}

TEST_CASE("cli diff: bad flags are one line, exit 2, before any file is read") {
    TempDir dir;
    const std::string a = dir.file("missing_a.exr"), b = dir.file("missing_b.exr");
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"diff", a},
             {"diff", a, b, "--threshold", "-1"},
             {"diff", a, b, "--threshold", "nan"},
             {"diff", a, b, "--threshold", "0.1x"},
             {"diff", a, b, "--max-error", "inf"},
             {"diff", a, b, "--max-relmse", ""},
             {"diff", a, b, "--max-share", "1.5"},
             {"diff", a, b, "--heatmap", dir.file("heat.jpg")},
             {"diff", a, b, "--heatmap-layer", "color"},  // without --heatmap
             {"diff", a, b, "--heatmap", dir.file("h.png"), "--heatmap-scale", "0"},
             {"diff", a, b, "--heatmap", dir.file("h.png"), "--heatmap-scale", "inf"},
             {"diff", a, b, "--layers", "color,,viewZ"},
             {"diff", a, dir.file("b.png"), "--heatmap", dir.file("./b.png")},
             {"diff", dir.file("a.png"), b, "--heatmap", dir.file("a.png")}}) {
        CAPTURE(args);
        const auto r = run(args);
        CHECK(r.code == cli::kExitUsage);
        CHECK(isOneErrorLine(r.err));
    }
    CHECK(dir.empty());
}

TEST_CASE("cli render --compare: the written frame against a golden image") {
    TempDir dir;
    const std::vector<std::string> small{"render", "--width",   "16", "--height",
                                         "12",     "--threads", "1",  "-q"};
    auto args = small;
    args.insert(args.end(), {"-o", dir.file("golden.exr")});
    REQUIRE(run(args).code == cli::kExitOk);

    // The same render: bit-identical.
    args = small;
    args.insert(args.end(), {"-o", dir.file("again.exr"), "--compare", dir.file("golden.exr")});
    auto r = run(args);
    CHECK(r.code == cli::kExitOk);
    CHECK(contains(r.out, "bit-identical: " + dir.file("again.exr")));

    // Brighter: beyond, exit 1, and the file is still written.
    args = small;
    args.insert(args.end(), {"--exposure", "2", "-o", dir.file("bright.exr"), "--compare",
                             dir.file("golden.exr"), "--heatmap", dir.file("heat.png")});
    r = run(args);
    CHECK(r.code == cli::kExitDiffer);
    CHECK(contains(cell(r.out, "color", Column::Verdict), "beyond"));
    CHECK(fs::exists(dir.file("bright.exr")));
    CHECK(fs::exists(dir.file("heat.png")));
}

TEST_CASE("cli render --compare: one frame, flags that need it, a reference that exists") {
    TempDir dir;
    const std::vector<std::string> small{"render", "--width", "16", "--height",
                                         "12",     "-q",      "-o", dir.file("out.exr")};
    const std::string golden = dir.file("golden.exr");
    LayeredImage(16, 12, kChannels).write(golden);
    for (const auto& extra : std::vector<std::vector<std::string>>{
             {"--compare", golden, "--frames", "2"},
             {"--threshold", "0.1"},
             {"--heatmap", dir.file("h.png")},
             {"--compare", golden, "--max-share", "-0.5"},
             {"--compare", dir.file("out.exr")},  // the output itself
             {"--compare", dir.file("g.png"), "--heatmap", dir.file("g.png")},
             {"--compare", dir.file("g.png"), "--heatmap", dir.file("./g.png")}}) {
        CAPTURE(extra);
        auto args = small;
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run(args);
        CHECK(r.code == cli::kExitUsage);
        CHECK(isOneErrorLine(r.err));
    }
    auto args = small;
    args.insert(args.end(), {"--compare", dir.file("none.exr")});
    const auto r = run(args);
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(dir.listing() == std::vector<std::string>{"golden.exr"});

    // Without -o the output is named after the scene and takes the reference's format.
    cli::RenderOptions o;
    CHECK(cli::renderOutput(o) == "cornell.png");
    o.compare = golden;
    CHECK(cli::renderOutput(o) == "cornell.exr");
    o.compare = dir.file("golden.png");
    CHECK(cli::renderOutput(o) == "cornell.png");
    o.scene = "spheres";
    CHECK(cli::renderOutput(o) == "spheres.png");
    o.scene = "/models/Box.glb";
    CHECK(cli::renderOutput(o) == "Box.png");
    o.shot = "examples/shots/spheres_orbit.json";  // the shot names it, over its scene
    CHECK(cli::renderOutput(o) == "spheres_orbit.png");
    CHECK(cli::sequenceFileName(cli::renderOutput(o), 0, 49) == "spheres_orbit_0000.png");
    o.compare = golden;
    o.output = "mine.png";
    o.outputGiven = true;
    CHECK(cli::renderOutput(o) == "mine.png");
}

#endif  // SSRT_CLI_LIB
