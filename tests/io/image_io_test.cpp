// Image files: EXR keeps every plane's name and bits, PNG quantises the display planes, and a
// write that cannot succeed throws a clear error and leaves the directory as it was.
#include "io/image_io.h"

#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/layer_groups.h"
#include "temp_dir.h"

using namespace ssrt;
namespace fs = std::filesystem;

namespace {

using test::TempDir;

// A value per (plane, pixel) that no other (plane, pixel) shares, plus a few that must survive
// bit for bit: -1 (background ids), a denormal and the largest float.
float probeValue(int plane, int x, int y, int width) {
    const int i = y * width + x;
    if (i == 0) return -1.0f;
    if (i == 1) return std::numeric_limits<float>::denorm_min() * float(plane + 1);
    if (i == 2) return std::numeric_limits<float>::max();
    return float(plane * 1000 + i) + 0.1f;
}

Frame makeFrame(int width, int height, const std::vector<std::string>& names) {
    Frame frame;
    frame.width = width;
    frame.height = height;
    for (std::size_t c = 0; c < names.size(); ++c) {
        PlaneF plane(width, height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) plane.at(x, y) = probeValue(int(c), x, y, width);
        frame.extraLayers.push_back({names[c], std::move(plane)});
    }
    return frame;
}

// A frame's every layer (renderer/layer_groups.h), as the command line writes an EXR of it.
void writeImage(const std::string& path, const Frame& frame, const WriteOptions& options = {}) {
    ssrt::writeImage(path, frameLayers(frame), options);
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("EXR round trip keeps every plane's name and bits") {
    TempDir dir;
    const std::vector<std::string> names{"color.R",  "color.G",  "color.B",    "viewZ",
                                         "normal.X", "normal.Y", "materialId", "shadow"};
    const Frame frame = makeFrame(5, 3, names);
    const std::string path = dir.file("frame.exr");
    writeImage(path, frame);
    CHECK(dir.listing() == std::vector<std::string>{"frame.exr"});

    // OpenEXR stores channels sorted, so compare as sets; the colour layer comes again as the
    // default channels R, G, B (checked below).
    std::vector<std::string> got = readChannelNames(path);
    std::vector<std::string> want = names;
    want.insert(want.end(), {"R", "G", "B"});
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    CHECK(got == want);

    for (std::size_t c = 0; c < names.size(); ++c) {
        CAPTURE(names[c]);
        int width = 0, height = 0;
        const std::vector<float> values = readChannel(path, names[c], width, height);
        REQUIRE(width == 5);
        REQUIRE(height == 3);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                CHECK(sameBits(values[y * width + x], probeValue(int(c), x, y, width)));
    }
}

TEST_CASE("EXR: the colour layer again as plain R, G, B, for viewers, and none without one") {
    TempDir dir;
    const std::vector<std::string> names{"viewZ",     "color.R",   "color.G",  "color.B",
                                         "display.R", "display.G", "display.B"};
    const std::string path = dir.file("frame.exr");
    writeImage(path, makeFrame(6, 4, names));
    const std::vector<std::string> got = readChannelNames(path);
    for (const char* c : {"R", "G", "B"}) CHECK(std::count(got.begin(), got.end(), c) == 1);
    CHECK(std::count(got.begin(), got.end(), "A") == 0);
    for (const std::string c : {"R", "G", "B"}) {
        CAPTURE(c);
        int width = 0, height = 0;
        const std::vector<std::vector<float>> values =
            readChannels(path, {c, "color." + c}, width, height);
        REQUIRE(values[0].size() == std::size_t(6 * 4));
        for (std::size_t i = 0; i < values[0].size(); ++i)
            CHECK(sameBits(values[0][i], values[1][i]));
        // Not the display's (which the frame fills with other values).
        CHECK(values[0] != readChannel(path, "display." + c, width, height));
    }
    // A reference's colour, ref.color, the same way.
    const std::string ref = dir.file("ref.exr");
    writeImage(ref, makeFrame(6, 4, {"ref.color.R", "ref.color.G", "ref.color.B", "ref.ssr.R"}));
    CHECK(readChannelNames(ref).size() == 7);
    int width = 0, height = 0;
    CHECK(readChannel(ref, "G", width, height) == readChannel(ref, "ref.color.G", width, height));
    // Without a colour layer, or with R, G, B of the file's own, nothing is added.
    const std::string none = dir.file("none.exr");
    writeImage(none, makeFrame(6, 4, {"albedo.R", "albedo.G", "albedo.B", "ref.ssr.R"}));
    CHECK(readChannelNames(none).size() == 4);
    const std::string own = dir.file("own.exr");
    writeImage(own, makeFrame(6, 4, {"R", "G", "B", "color.R", "color.G", "color.B"}));
    CHECK(readChannelNames(own).size() == 6);
}

TEST_CASE("readChannels reads several channels at once, each as readChannel would") {
    TempDir dir;
    const std::vector<std::string> names{"ref.color.R", "ref.color.G", "ref.ssr.B", "viewZ"};
    const std::string path = dir.file("frame.exr");
    writeImage(path, makeFrame(7, 4, names));
    // In an order of our own, not the file's (sorted) one, and one channel twice.
    const std::vector<std::string> asked{"viewZ", "ref.color.R", "ref.ssr.B", "viewZ"};
    int width = 0, height = 0;
    const std::vector<std::vector<float>> got = readChannels(path, asked, width, height);
    REQUIRE(width == 7);
    REQUIRE(height == 4);
    REQUIRE(got.size() == asked.size());
    for (std::size_t k = 0; k < asked.size(); ++k) {
        CAPTURE(asked[k]);
        int w = 0, h = 0;
        const std::vector<float> one = readChannel(path, asked[k], w, h);
        REQUIRE(got[k].size() == one.size());
        CHECK(std::equal(one.begin(), one.end(), got[k].begin(), sameBits));
    }
    CHECK_THROWS_WITH_AS(readChannels(path, {"viewZ", "normal.X"}, width, height),
                         doctest::Contains("it has no channel 'normal.X'"), std::runtime_error);
}

TEST_CASE("an EXR file's bytes do not depend on when it was written") {
    // A writer may stamp EXR headers with the current time (capDate, as OpenImageIO does
    // unless told a DateTime); the same frame must give the same file at any hour (golden
    // files compare bytes).
    TempDir dir;
    const std::string path = dir.file("frame.exr");
    writeImage(path, makeFrame(4, 2, {"color.R", "viewZ"}));
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // An attribute is name\0 type\0 int32 size, value. capDate may be there, empty.
    const std::string key("capDate\0string\0", 15);
    const std::size_t at = bytes.find(key);
    if (at != std::string::npos) {
        REQUIRE(at + key.size() + 4 <= bytes.size());
        int32_t size = -1;
        std::memcpy(&size, bytes.data() + at + key.size(), sizeof size);
        CHECK(size == 0);
    }
}

namespace {

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("every EXR compression keeps every bit, and its bytes do not depend on the threads") {
    TempDir dir;
    // Rows enough for many blocks of every compression (zip and piz take 16 or 32 rows), and
    // planes that compress differently: the probe values, a constant, and noise-like bits.
    const int width = 33, height = 100;
    Frame frame = makeFrame(width, height, {"viewZ", "normal.X", "materialId"});
    frame.extraLayers[1].plane.fill(0.5f);
    uint32_t state = 12345;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            state = state * 1664525u + 1013904223u;
            float v;
            const uint32_t bits = (state & 0x807fffffu) | 0x3f000000u;  // finite, any mantissa
            std::memcpy(&v, &bits, sizeof v);
            frame.extraLayers[2].plane.at(x, y) = v;
        }
    std::vector<std::size_t> sizes;
    for (int c = 0; c <= int(ExrCompression::Piz); ++c) {
        const ExrCompression compression = ExrCompression(c);
        CAPTURE(exrCompressionName(compression));
        std::string first;
        for (int threads : {1, 3}) {
            const std::string path = dir.file("frame.exr");
            writeImage(path, frame, WriteOptions{compression, threads});
            const std::string bytes = fileBytes(path);
            if (threads == 1) first = bytes;
            else CHECK(bytes == first);
            for (const NamedPlane& p : frame.extraLayers) {
                CAPTURE(p.name);
                int w = 0, h = 0;
                const std::vector<float> got = readChannel(path, p.name, w, h);
                REQUIRE(w == width);
                REQUIRE(h == height);
                bool same = true;
                for (int y = 0; y < height; ++y)
                    for (int x = 0; x < width; ++x)
                        same = same && sameBits(got[std::size_t(y) * width + x], p.plane.at(x, y));
                CHECK(same);
            }
        }
        sizes.push_back(first.size());
    }
    // The choice reaches the file: none stores every byte, the others fewer.
    CHECK(sizes[0] >= std::size_t(3) * width * height * sizeof(float));
    for (std::size_t c = 1; c < sizes.size(); ++c) CHECK(sizes[c] < sizes[0]);
    CHECK(dir.listing() == std::vector<std::string>{"frame.exr"});
}

TEST_CASE("compressions are parsed by the names they print") {
    for (int c = 0; c <= int(ExrCompression::Piz); ++c)
        CHECK(parseExrCompression(exrCompressionName(ExrCompression(c))) == ExrCompression(c));
    CHECK_FALSE(parseExrCompression("dwaa").has_value());  // lossy: not offered
    CHECK_FALSE(parseExrCompression("pxr24").has_value());
    CHECK(exrCompressionList() == "none, rle, zips, zip, piz");
}

TEST_CASE("PNG quantises display planes as round(clamp(v, 0, 1) * 255)") {
    TempDir dir;
    // Truncating instead of rounding, or not clamping, changes at least one of these.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> in{-1.0f,  0.0019f, 0.0021f, 0.2f, 0.998f,
                                0.999f, 1.0f,    2.0f,    nan,  inf};
    const std::vector<int> want{0, 0, 1, 51, 254, 255, 255, 255, 0, 255};
    // The values three times, at 0, 16 and 32: rows are quantised 16 values at a time in
    // lanes and the rest one by one, and each way must give these bytes.
    const int n = int(in.size()), width = 32 + n;
    const auto value = [&](int x) { return x % 16 < n ? in[std::size_t(x % 16)] : 0.2f; };
    const auto wanted = [&](int x) { return x % 16 < n ? want[std::size_t(x % 16)] : 51; };
    Frame frame = makeFrame(width, 1, {"display.R", "display.G", "display.B", "viewZ"});
    for (int x = 0; x < width; ++x) {
        frame.extraLayers[0].plane.at(x, 0) = value(x);
        frame.extraLayers[1].plane.at(x, 0) = value(width - 1 - x);  // channels not mixed up
        frame.extraLayers[2].plane.at(x, 0) = 0.2f;
    }
    const std::string path = dir.file("preview.png");
    writeImage(path, frame);
    CHECK(readChannelNames(path) == std::vector<std::string>{"R", "G", "B"});

    int w = 0, h = 0;
    const auto r = readChannel(path, "R", w, h);
    const auto g = readChannel(path, "G", w, h);
    const auto b = readChannel(path, "B", w, h);
    REQUIRE(w == width);
    REQUIRE(h == 1);
    for (int x = 0; x < width; ++x) {
        CAPTURE(x);
        CHECK(std::lround(r[x] * 255.0f) == wanted(x));
        CHECK(std::lround(g[x] * 255.0f) == wanted(width - 1 - x));
        CHECK(std::lround(b[x] * 255.0f) == 51);
    }
}

TEST_CASE("PNG: halves round away from zero, and the bytes do not depend on the thread count") {
    TempDir dir;
    // Every level's half-way value and its neighbours (rounding to even, or adding 0.5 in
    // float, gets some of them wrong), in rows enough for several of the writer's bands.
    std::vector<float> values;
    for (int k = 0; k < 255; ++k) {
        const float half = (float(k) + 0.5f) / 255.0f;
        values.push_back(std::nextafter(half, 0.0f));
        values.push_back(half);
        values.push_back(std::nextafter(half, 1.0f));
    }
    const int width = 61, height = 200;
    Frame frame = makeFrame(width, height, {"display.R", "display.G", "display.B"});
    const auto at = [&](int c, int x, int y) {
        return values[std::size_t((y * width + x) * 3 + c) % values.size()];
    };
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) frame.extraLayers[c].plane.at(x, y) = at(c, x, y);
    WriteOptions one, three;
    one.threads = 1;
    three.threads = 3;
    writeImage(dir.file("one.png"), frame, one);
    writeImage(dir.file("three.png"), frame, three);
    const auto bytes = [&](const char* name) {
        std::ifstream in(dir.file(name), std::ios::binary);
        return std::vector<char>(std::istreambuf_iterator<char>(in), {});
    };
    CHECK(bytes("one.png") == bytes("three.png"));
    int w = 0, h = 0;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const auto got = readChannel(dir.file("three.png"), names[c], w, h);
        REQUIRE(w == width);
        REQUIRE(h == height);
        int wrong = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                wrong += std::lround(got[std::size_t(y * width + x)] * 255.0f) !=
                         std::lround(at(c, x, y) * 255.0f);
        CHECK(wrong == 0);
    }
}

TEST_CASE("extensions are checked, case-insensitively, before anything is written") {
    TempDir dir;
    const Frame frame = makeFrame(2, 2, {"display.R", "display.G", "display.B"});
    for (const char* name : {"out.jpg", "out", "out.png.bak", "out.tiff"}) {
        CAPTURE(name);
        CHECK_THROWS_AS(writeImage(dir.file(name), frame), std::invalid_argument);
        CHECK_THROWS_AS(checkWritable(dir.file(name)), std::invalid_argument);
    }
    CHECK(dir.listing().empty());
    try {
        writeImage(dir.file("out.jpg"), frame);
    } catch (const std::invalid_argument& e) {
        const std::string message = e.what();
        CHECK(message.find(".jpg") != std::string::npos);
        CHECK(message.find(".png") != std::string::npos);
        CHECK(message.find(".exr") != std::string::npos);
    }
    CHECK_THROWS_WITH_AS(writeImage(dir.file("out"), frame),
                         doctest::Contains("out' has no extension (supported: .png, .exr)"),
                         std::invalid_argument);
    writeImage(dir.file("upper.PNG"), frame);
    writeImage(dir.file("upper.EXR"), frame);
    CHECK(dir.listing() == std::vector<std::string>{"upper.EXR", "upper.PNG"});
}

TEST_CASE("a PNG needs the display planes") {
    TempDir dir;
    const Frame frame = makeFrame(2, 2, {"display.R", "display.G", "viewZ"});
    CHECK_THROWS_WITH_AS(writeImage(dir.file("x.png"), frame), doctest::Contains("display.B"),
                         std::invalid_argument);
    CHECK(dir.listing().empty());
}

TEST_CASE("a frame whose planes disagree with it is refused") {
    TempDir dir;
    Frame frame = makeFrame(4, 4, {"viewZ", "shadow"});
    frame.extraLayers[1].plane = PlaneF(3, 4);
    CHECK_THROWS_WITH_AS(writeImage(dir.file("x.exr"), frame), doctest::Contains("shadow"),
                         std::invalid_argument);
    frame = makeFrame(4, 4, {"viewZ", "viewZ"});
    CHECK_THROWS_AS(writeImage(dir.file("x.exr"), frame), std::invalid_argument);
    CHECK(dir.listing().empty());
}

TEST_CASE("a missing directory fails with one line naming the path, and creates nothing") {
    TempDir dir;
    const Frame frame = makeFrame(2, 2, {"display.R", "display.G", "display.B"});
    const std::string path = dir.file("missing/out.exr");
    for (int check = 0; check < 2; ++check) {
        try {
            if (check) checkWritable(path);
            else writeImage(path, frame);
            FAIL("no exception");
        } catch (const std::runtime_error& e) {
            const std::string message = e.what();
            CHECK(message.find(path) != std::string::npos);
            CHECK(message.find("does not exist") != std::string::npos);
            CHECK(message.find('\n') == std::string::npos);
        }
    }
    CHECK(dir.listing().empty());
}

TEST_CASE("unwritable places fail with runtime_error and leave nothing behind") {
    TempDir dir;
    const Frame frame = makeFrame(2, 2, {"display.R", "display.G", "display.B"});

    // A "directory" that is a regular file.
    { std::ofstream(dir.file("plain")) << "x"; }
    CHECK_THROWS_AS(writeImage(dir.file("plain/out.png"), frame), std::runtime_error);
    CHECK_THROWS_AS(checkWritable(dir.file("plain/out.png")), std::runtime_error);
    // The target is a directory.
    fs::create_directory(dir.path / "sub.png");
    CHECK_THROWS_AS(writeImage(dir.file("sub.png"), frame), std::runtime_error);
    CHECK_THROWS_AS(checkWritable(dir.file("sub.png")), std::runtime_error);
    CHECK(fs::is_directory(dir.path / "sub.png"));
    CHECK(dir.listing() == std::vector<std::string>{"plain", "sub.png"});

    // /proc refuses new files even to root.
    CHECK_THROWS_WITH_AS(writeImage("/proc/ssrt-io-test.png", frame),
                         doctest::Contains("cannot create a file in '/proc' ("),
                         std::runtime_error);
    CHECK_THROWS_AS(checkWritable("/proc/ssrt-io-test.png"), std::runtime_error);
    CHECK_FALSE(fs::exists("/proc/ssrt-io-test.png"));

    // A read-only directory (root ignores permissions, so only as another user).
    if (::geteuid() != 0) {
        fs::create_directory(dir.path / "ro");
        fs::permissions(dir.path / "ro", fs::perms::owner_read | fs::perms::owner_exec);
        CHECK_THROWS_AS(writeImage(dir.file("ro/out.png"), frame), std::runtime_error);
        CHECK_THROWS_AS(checkWritable(dir.file("ro/out.png")), std::runtime_error);
        fs::permissions(dir.path / "ro", fs::perms::owner_all);
        CHECK(fs::is_empty(dir.path / "ro"));
    }
}

TEST_CASE("checkWritable accepts a good path and leaves no file") {
    TempDir dir;
    checkWritable(dir.file("out.png"));
    checkWritable(dir.file("out.exr"));
    CHECK(dir.listing().empty());

    // An existing file is fine (it will be replaced) and is left untouched.
    { std::ofstream(dir.file("old.png")) << "old"; }
    checkWritable(dir.file("old.png"));
    CHECK(dir.listing() == std::vector<std::string>{"old.png"});
    CHECK(fs::file_size(dir.path / "old.png") == 3);
}

TEST_CASE("writing over an existing file replaces it and leaves no temporary") {
    TempDir dir;
    const std::string path = dir.file("frame.exr");
    { std::ofstream(path) << "not an image"; }
    writeImage(path, makeFrame(3, 2, {"viewZ"}));
    writeImage(path, makeFrame(4, 2, {"viewZ", "shadow"}));
    CHECK(dir.listing() == std::vector<std::string>{"frame.exr"});
    int w = 0, h = 0;
    readChannel(path, "shadow", w, h);
    CHECK(w == 4);
}

TEST_CASE("reading names the path and the missing channel") {
    TempDir dir;
    const std::string path = dir.file("frame.exr");
    writeImage(path, makeFrame(2, 2, {"viewZ"}));
    int w = 0, h = 0;
    CHECK_THROWS_WITH_AS(readChannel(path, "normal.X", w, h), doctest::Contains("normal.X"),
                         std::runtime_error);
    CHECK_THROWS_AS(readChannelNames(dir.file("none.exr")), std::runtime_error);
}
