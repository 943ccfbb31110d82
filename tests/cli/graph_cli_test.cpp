// `ssrt graph` (cli/graph_command.h): the frame `ssrt render` would render with the same flags,
// as a table of passes and resources, before anything is rendered.
#include <doctest/doctest.h>

#include "cli_run.h"

using namespace ssrt::test;

namespace {

// The table's resource rows: from the "resources" heading to the blank line after it.
std::vector<std::string> resourceRows(const std::string& out) {
    std::vector<std::string> rows;
    bool in = false;
    for (const std::string& line : textLines(out)) {
        if (line == "resources") in = true;
        else if (in && line.empty()) break;
        else if (in && line.rfind("  resource ", 0) != 0) rows.push_back(line);
    }
    return rows;
}

bool anyRowStarts(const std::vector<std::string>& rows, const std::string& name) {
    for (const std::string& r : rows)
        if (r.rfind("  " + name + " ", 0) == 0) return true;
    return false;
}

}  // namespace

TEST_CASE("graph: the default render's passes, resources and memory") {
    const CliResult r = runSsrt({"graph"});
    REQUIRE(r.code == 0);
    CHECK(r.err.empty());
    CHECK(contains(r.out, "frame graph: cornell, 1280x720, a single image (no history)"));
    const auto rows = resourceRows(r.out);
    CHECK(anyRowStarts(rows, "viewZ"));
    CHECK(anyRowStarts(rows, "ssr"));
    // A PNG makes no debug or id planes, and a single image no history.
    CHECK_FALSE(anyRowStarts(rows, "ssrSteps"));
    CHECK_FALSE(anyRowStarts(rows, "instanceId"));
    CHECK_FALSE(anyRowStarts(rows, "history.color"));
    CHECK(contains(r.out, "  total      "));
}

TEST_CASE("graph: --no-ssr lists no SSR pass or resource, and an EXR and a sequence add theirs") {
    const CliResult r = runSsrt({"graph", "--no-ssr"});
    REQUIRE(r.code == 0);
    for (const std::string& row : resourceRows(r.out)) CHECK_FALSE(contains(row, "  ssr"));
    CHECK_FALSE(contains(r.out, "\n  ssr "));
    CHECK_FALSE(contains(r.out, "denoisedSpecular"));
    const CliResult exr = runSsrt({"graph", "-o", "frame.exr", "--frames", "8", "--ssgi-feedback"});
    REQUIRE(exr.code == 0);
    const auto rows = resourceRows(exr.out);
    CHECK(anyRowStarts(rows, "ssrSteps"));
    CHECK(anyRowStarts(rows, "instanceId"));
    CHECK(anyRowStarts(rows, "history.diffuse"));
    CHECK(contains(exr.out, "a frame of a sequence (history read and kept)"));
}

TEST_CASE("graph: bad flags are one usage line, and --dot is a digraph") {
    const CliResult bad = runSsrt({"graph", "--width", "0"});
    CHECK(bad.code == 2);
    CHECK(isOneErrorLine(bad.err));
    const CliResult dot = runSsrt({"graph", "--dot", "--quality", "ultra"});
    REQUIRE(dot.code == 0);
    CHECK(dot.out.rfind("digraph frame {", 0) == 0);
    // A single image: no temporal pass (no history to read or keep); a sequence's frame has one.
    CHECK(contains(dot.out, "\"denoise history fix\\nchain "));
    CHECK_FALSE(contains(dot.out, "\"denoise temporal"));
    const CliResult seq = runSsrt({"graph", "--dot", "--quality", "ultra", "--frames", "2"});
    REQUIRE(seq.code == 0);
    CHECK(contains(seq.out, "\"denoise temporal\\nchain "));
}
