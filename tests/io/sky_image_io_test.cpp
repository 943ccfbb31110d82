// Environment images through OpenImageIO: RGB by channel name, grey from one channel,
// negatives to 0, non-finite texels refused with one line naming the file; the committed
// example shots parse and their sky loads.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "renderer/layer_groups.h"
#include "renderer/sky_lighting.h"
#include "scenes/shot.h"
#include "temp_dir.h"

using namespace ssrt;
using test::TempDir;

namespace {

// A frame whose planes carry the given channel names, value = f(plane, x, y).
template <class F>
Frame planesFrame(int w, int h, const std::vector<std::string>& names, F value) {
    Frame frame;
    frame.width = w;
    frame.height = h;
    for (std::size_t c = 0; c < names.size(); ++c) {
        PlaneF plane(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) plane.at(x, y) = value(int(c), x, y);
        frame.extraLayers.push_back({names[c], std::move(plane)});
    }
    return frame;
}

// Writes the frame's planes as an EXR.
void writeFrame(const std::string& path, const Frame& frame) {
    writeImage(path, frameLayers(frame));
}

// The sky the command line makes of a file (cli/options.cpp): read, then made a SkyImage.
SkyImage readSky(const std::string& path) { return makeSkyImage(path, readSkyImage(path)); }

std::string errorOf(const std::string& path) {
    try {
        readSkyImage(path);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("sky image io: RGB by name, grey from one channel, negatives to zero") {
    TempDir dir;
    // EXR stores channels sorted by name (B, G, R, Z): the reader must pick them by name.
    const auto value = [](int c, int x, int y) { return float(c * 100 + y * 8 + x) + 0.25f; };
    writeFrame(dir.file("rgb.exr"), planesFrame(8, 4, {"Z", "R", "G", "B"}, value));
    const SkyImage rgb = readSky(dir.file("rgb.exr"));
    CHECK(rgb.width == 8);
    CHECK(rgb.height == 4);
    CHECK(rgb.source == dir.file("rgb.exr"));
    REQUIRE(rgb.rgb.size() == 3u * 8 * 4);
    bool exact = true;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c)
                exact &= rgb.rgb[(std::size_t(y) * 8 + x) * 3 + c] == value(c + 1, x, y);
    CHECK(exact);

    writeFrame(dir.file("grey.exr"), planesFrame(4, 2, {"Y"}, [](int, int x, int y) {
                   return x == 1 ? -3.0f : float(x + y);
               }));
    const SkyImage grey = readSky(dir.file("grey.exr"));
    REQUIRE(grey.rgb.size() == 3u * 4 * 2);
    CHECK(grey.rgb[3 * 2 + 0] == 2.0f);  // (2, 0)
    CHECK(grey.rgb[3 * 2 + 2] == 2.0f);
    CHECK(grey.rgb[3 * 1 + 1] == 0.0f);  // (1, 0) was negative
}

TEST_CASE("sky image io: a texel that is not finite, or no file, is one line naming it") {
    TempDir dir;
    const std::string nan = dir.file("nan.exr");
    writeFrame(nan, planesFrame(4, 2, {"R", "G", "B"}, [](int c, int x, int y) {
                   return c == 1 && x == 3 && y == 1 ? std::numeric_limits<float>::infinity()
                                                     : 1.0f;
               }));
    CHECK(errorOf(nan) == "cannot read '" + nan + "': texel (3, 1) is not finite");
    const std::string missing = dir.file("missing.hdr");
    const std::string message = errorOf(missing);
    CHECK(message.rfind("cannot read '" + missing + "': ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
}

#ifdef SSRT_SOURCE_DIR
TEST_CASE("examples: the committed shot files parse and their sky loads") {
    const std::string dir = std::string(SSRT_SOURCE_DIR) + "/examples/shots/";
    for (const char* name : {"spheres_sky.json", "spheres_orbit.json"}) {
        CAPTURE(name);
        CHECK_NOTHROW(loadShot(dir + name));
    }
    const Shot shot = loadShot(dir + "spheres_sky.json");
    REQUIRE(shot.environment.file);
    const SkyImage sky = readSky(*shot.environment.file);
    CHECK(sky.width == 2 * sky.height);
    CHECK(*std::max_element(sky.rgb.begin(), sky.rgb.end()) > 10.0f);  // the sun
}
#endif
