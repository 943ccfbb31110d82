// Limits as clear errors, decided before allocating (issue 33): an environment image whose
// header is over io/image_limits.h's limits, in every format, and a frame larger than the
// memory this process may use, each end in one line naming the file or the flags, the value
// and the limit, exit 3, with nothing written. (tests/cli/check_limits_ulimit.sh runs the
// same under `ulimit -v 4000000`; frame count and size limits are tested in cli_test.cpp and
// sequence_cli_test.cpp.)
#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "cli/memory_check.h"
#include "cli_run.h"
#include "renderer/memory_use.h"
#include "temp_dir.h"

using namespace ssrt;
using test::contains;
using test::isOneErrorLine;
using test::runSsrt;
using test::TempDir;

namespace {

const std::string kOversized = SSRT_SOURCE_DIR "/tests/io/data/oversized/";

}  // namespace

TEST_CASE("cli limits: an oversized environment image is one line and writes nothing") {
    for (const char* file : {"big.png", "big.jpg", "big.hdr", "big.exr", "big.bmp"}) {
        CAPTURE(file);
        TempDir dir;
        test::writeFile(dir.file("shot.json"),
                        R"({"scene": "spheres", "environment": {"type": "image", "file": ")" +
                            kOversized + file + R"("}, "render": {"width": 32, "height": 18}})");
        const test::CliResult r =
            runSsrt({"render", "--shot", dir.file("shot.json"), "-o", dir.file("out.exr")});
        CHECK(r.code == cli::kExitFailure);
        CHECK(isOneErrorLine(r.err));
        CHECK(contains(r.err, "cannot read '" + kOversized + file + "'"));
        CHECK(contains(r.err, "over the limit of 134217728 pixels (16384 x 8192)"));
        CHECK(dir.listing() == std::vector<std::string>{"shot.json"});
    }
}

TEST_CASE("cli limits: a frame is checked against the memory available before any work") {
    RenderSettings settings;
    settings.width = settings.height = 8192;
    settings.shadowMapSize = 2048;
    const FrameMemoryNeed need = frameMemoryNeed(8192, 8192, 2048);
    CHECK(need.planes > 50);  // the frame's and the history's tables
    // Each plane its element's bytes (the denoiser's f16 signals 2, the rest 4).
    CHECK(need.bytes == need.pixelBytes * 8192 * 8192 + std::size_t(2048 * 2048) * 4);
    CHECK(need.pixelBytes < std::size_t(need.planes) * 4);
    CHECK(need.pixelBytes > std::size_t(need.planes) * 2);
    try {
        cli::checkFrameMemory(settings, {std::size_t(4000000) * 1024, "ulimit -v"});
        FAIL("an 8192 x 8192 frame passed in 4 GB");
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        CHECK(message.rfind("--width, --height: a 8192 x 8192 frame needs about ", 0) == 0);
        CHECK(contains(message, "more than the 4.1 GB this process may use (ulimit -v)"));
    }
    settings.width = 320, settings.height = 180;
    CHECK_NOTHROW(cli::checkFrameMemory(settings, {std::size_t(4000000) * 1024, "ulimit -v"}));
    // The bound is the limit: one byte less refuses.
    settings.width = 1280, settings.height = 720;
    const std::size_t small = frameMemoryNeed(1280, 720, 2048).bytes;
    CHECK_THROWS_AS(cli::checkFrameMemory(settings, {small - 1, "MemAvailable"}),
                    std::runtime_error);
    CHECK_NOTHROW(cli::checkFrameMemory(settings, {small, "MemAvailable"}));
}

TEST_CASE("cli limits: ssrt diff of an EXR with a damaged attribute is one line at once") {
    // diff_fuzz's input (an out-of-memory report: 1.7 GB and 15 s in OpenEXR's InputFile): an
    // attribute whose size runs past the file, which OpenEXR's core library reports and skips.
    const std::string path = SSRT_SOURCE_DIR "/tests/io/data/damaged_attribute.exr";
    const test::CliResult r = runSsrt({"diff", path, path});
    CHECK(r.code == cli::kExitFailure);
    CHECK(isOneErrorLine(r.err));
    CHECK(contains(r.err, "cannot read '" + path + "': the header is damaged: Attribute "));
}
