// The command line parsed apart from running it (cli/command_line.h): what the fuzzer of the
// command line relies on, parsing many command lines with one app.
#include "cli/command_line.h"

#include <doctest/doctest.h>

#include <CLI/CLI.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/render_command.h"

using namespace ssrt::cli;

namespace {

std::optional<int> parse(CommandLine& line, std::vector<const char*> args) {
    args.insert(args.begin(), "ssrt");
    std::ostringstream out, err;
    return line.parse(int(args.size()), args.data(), out, err);
}

}  // namespace

TEST_CASE("command line: parses the command and its options without running it") {
    CommandLine line;
    REQUIRE(!parse(line, {"render", "--width", "100", "--scene", "cornell", "--frames", "3"}));
    CHECK(line.command() == Command::Render);
    CHECK(line.render.settings.at("width") == "100");
    CHECK(line.render.scene == "cornell");
    CHECK(line.render.frames == "3");
}

TEST_CASE("command line: after reset() a parse starts as in a new one") {
    CommandLine line;
    REQUIRE(!parse(line, {"render", "--width", "100", "--shard", "1/2", "-o", "a.exr"}));
    line.reset();
    REQUIRE(!parse(line, {"diff", "a.exr", "b.exr"}));
    CHECK(line.command() == Command::Diff);
    CHECK(line.diff.a == "a.exr");
    line.reset();
    REQUIRE(!parse(line, {"render"}));  // nothing of the first render's options is left
    CHECK(line.render.settings.empty());
    CHECK(!line.render.shard);
    CHECK(line.render.output == RenderOptions{}.output);
    line.reset();
    CHECK(parse(line, {"render", "--no-such-flag"}) == kExitUsage);
    line.reset();
    CHECK(parse(line, {"--help"}) == kExitOk);
}

TEST_CASE("command line: a switch a preset turns on can be turned off beside it") {
    CommandLine line;
    REQUIRE(!parse(line, {"render", "--quality", "ultra"}));
    CHECK(settingsFrom(line.render).trace.march.backFaces);  // ultra's
    line.reset();
    REQUIRE(!parse(line, {"render", "--quality", "ultra", "--no-back-faces"}));
    CHECK(!settingsFrom(line.render).trace.march.backFaces);
    line.reset();
    REQUIRE(!parse(line, {"render", "--back-faces"}));
    CHECK(settingsFrom(line.render).trace.march.backFaces);
    line.reset();
    CHECK(parse(line, {"render", "--back-faces", "--no-back-faces"}) == kExitUsage);
}

// runCli builds the command named by the first argument alone; the completion script and the
// man page, which walk every command, and anything else get them all.
TEST_CASE("command line: a command named first is built alone, the same options as in the whole") {
    const auto commands = [](const CommandLine& line) {
        std::vector<std::string> names;
        for (const CLI::App* c : line.app().get_subcommands({})) names.push_back(c->get_name());
        return names;
    };
    CHECK(commands(CommandLine("render")) == std::vector<std::string>{"render"});
    CHECK(commands(CommandLine("diff")) == std::vector<std::string>{"diff"});
    for (const char* all : {"", "man", "completion", "--help", "rendr"})
        CHECK(commands(CommandLine(all)).size() == std::size_t(kCommandCount));
    // The one command's options are the whole app's, by name and help.
    const auto options = [](const CLI::App& app, const std::string& name) {
        std::vector<std::string> text;
        for (const CLI::Option* o : app.get_subcommand(name)->get_options())
            text.push_back(o->get_name() + " " + o->get_description());
        return text;
    };
    for (int c = 0; c < kCommandCount; ++c) {
        const std::string name(kCommandNames[c]);
        CAPTURE(name);
        const CommandLine whole;
        const CommandLine alone(name);
        CHECK(options(alone.app(), name) == options(whole.app(), name));
    }
    CommandLine line("render");
    REQUIRE(!parse(line, {"render", "--width", "100"}));
    CHECK(line.command() == Command::Render);
    CHECK(line.render.settings.at("width") == "100");
}
