// io/'s own decoders (libpng, libjpeg, stb_image, OpenEXR) against OpenImageIO, which read
// every image before them: the same size, channel names, colour space, sample type and
// samples, bit for bit, for every PNG colour type and depth, JPEG, Radiance HDR and EXR, the
// committed sky, the assimp sample files' textures, and bytes in memory; 8- and 16-bit
// samples as float against OpenImageIO's own conversion; damaged files give one line.
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "image_files.h"
#include "io/image_decode.h"
#include "io/image_io.h"
#include "io/oiio_module.h"
#include "io/texture_io.h"
#include "layered_image.h"
#include "png_files.h"
#include "temp_dir.h"

using namespace ssrt;
using namespace ssrt::io_detail;
using test::TempDir;

namespace {

constexpr AlphaMode kAlphaModes[] = {AlphaMode::Associated, AlphaMode::Straight};

// What OpenImageIO reads (through the module, as io/ read every file before).
DecodedImage oiioFile(const std::string& path, AlphaMode alpha) {
    DecodedImage image;
    std::string error;
    REQUIRE_MESSAGE(oiioModule().decodeFile(path, alpha, image, error), error);
    return image;
}

// Two sample vectors (io_detail::Samples or std::vector) hold the same bits.
template <class A, class B>
bool sameBytes(const A& a, const B& b) {
    static_assert(sizeof(*a.data()) == sizeof(*b.data()));
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(*a.data())) == 0);
}

void checkSame(const DecodedImage& ours, const DecodedImage& oiio) {
    CHECK(ours.width == oiio.width);
    CHECK(ours.height == oiio.height);
    CHECK(ours.channels == oiio.channels);
    CHECK(ours.channelNames == oiio.channelNames);
    CHECK(ours.srgb == oiio.srgb);
    REQUIRE(ours.type == oiio.type);
    CHECK(sameBytes(ours.u8, oiio.u8));
    CHECK(sameBytes(ours.u16, oiio.u16));
    CHECK(sameBytes(ours.f32, oiio.f32));
}

// The file through our decoder and through OpenImageIO, both alpha modes.
void checkFile(const std::string& path) {
    for (const AlphaMode alpha : kAlphaModes) {
        CAPTURE(path);
        CAPTURE(int(alpha));
        checkSame(decodeImageFile(path, alpha), oiioFile(path, alpha));
    }
}

// Every file under `dir` with one of the extensions; how many.
int checkFilesUnder(const std::filesystem::path& dir, const std::vector<std::string>& exts) {
    int count = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        std::string ext = entry.path().extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (!entry.is_regular_file() || std::find(exts.begin(), exts.end(), ext) == exts.end())
            continue;
        checkFile(entry.path().string());
        ++count;
    }
    return count;
}

}  // namespace

TEST_CASE("decoders vs OpenImageIO: PNG of every colour type, depth and chunk") {
    TempDir dir;
    std::vector<test::PngSpec> specs;
    for (const int depth : {1, 2, 4, 8, 16}) {
        specs.push_back({7, 3, PNG_COLOR_TYPE_GRAY, depth});
        specs.push_back({7, 3, PNG_COLOR_TYPE_GRAY, depth, false, true});  // tRNS
        if (depth <= 8) specs.push_back({7, 3, PNG_COLOR_TYPE_PALETTE, depth});
        if (depth <= 8) specs.push_back({7, 3, PNG_COLOR_TYPE_PALETTE, depth, false, true});
    }
    for (const int depth : {8, 16})
        for (const int type :
             {PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGBA}) {
            specs.push_back({9, 4, type, depth});
            specs.push_back({9, 4, type, depth, true});                     // interlaced
            specs.push_back({9, 4, type, depth, false, false, 1 / 2.2});    // gamma 2.2
            specs.push_back({9, 4, type, depth, false, false, 1.0});        // linear
            specs.push_back({9, 4, type, depth, false, false, 0.0, true});  // sRGB (and its gAMA)
        }
    specs.push_back({9, 4, PNG_COLOR_TYPE_RGB, 8, false, true});  // an RGB transparency key
    for (std::size_t i = 0; i < specs.size(); ++i) {
        const std::string path = dir.file("case" + std::to_string(i) + ".png");
        test::writePng(path, specs[i]);
        checkFile(path);
        // A transparency chunk becomes an alpha channel.
        if (specs[i].transparency)
            CHECK(decodeImageFile(path, AlphaMode::Straight).channelNames.back() == "A");
    }
}

TEST_CASE("decoders vs OpenImageIO: JPEG, Radiance HDR and EXR files") {
    TempDir dir;
    std::vector<uint8_t> grey(17 * 9), rgb(17 * 9 * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 7 + (i / 51) * 13);
    for (std::size_t i = 0; i < grey.size(); ++i) grey[i] = uint8_t(i * 5);
    test::writeImage(dir.file("grey.jpg"), 17, 9, 1, grey);
    test::writeImage(dir.file("rgb.jpg"), 17, 9, 3, rgb);
    // A Radiance file as OpenImageIO writes it, over a wide range of exponents.
    std::vector<float> hdr(40 * 3 * 3);
    for (std::size_t i = 0; i < hdr.size(); ++i)
        hdr[i] = std::ldexp(float(i % 17) + 0.3f, int(i % 41) - 20);
    {
        auto out = OIIO::ImageOutput::create(dir.file("wide.hdr"));
        REQUIRE(out->open(dir.file("wide.hdr"), OIIO::ImageSpec(40, 3, 3, OIIO::TypeDesc::FLOAT)));
        REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, hdr.data()));
        out->close();
    }
    // An EXR of ssrt's with channels whose order OpenImageIO rearranges.
    test::LayeredImage exr(6, 4,
                           {"color.R", "color.G", "color.B", "normal.X", "normal.Y", "normal.Z",
                            "viewZ", "A", "Z", "albedo.B", "id"});
    exr.write(dir.file("layers.exr"));
    for (const char* name : {"grey.jpg", "rgb.jpg", "wide.hdr", "layers.exr"})
        checkFile(dir.file(name));
#ifdef SSRT_SOURCE_DIR
    checkFile(SSRT_SOURCE_DIR "/examples/shots/sky.hdr");
#endif
}

namespace {

// An EXR as OpenImageIO writes it, in the layouts other programs' files come in.
struct ExrLayout {
    std::string compression = "zip";
    int tile = 0;             // square tiles of this side; 0: scanlines
    bool mipmap = false;      // with its smaller levels after level 0 (tiled)
    bool decreasing = false;  // rows stored bottom first
    int x = 0, y = 0;         // the data window's origin
};

void writeExr(const std::string& path, const ExrLayout& layout) {
    // 45 x 70: more than one chunk of every compression but DWAB's 256 rows, none full.
    OIIO::ImageSpec spec(45, 70, 5, OIIO::TypeDesc::HALF);
    spec.channelnames = {"R", "G", "B", "A", "id"};
    spec.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF,
                           OIIO::TypeDesc::HALF, OIIO::TypeDesc::UINT};
    spec.x = layout.x, spec.y = layout.y;
    spec.attribute("compression", layout.compression);
    if (layout.decreasing) spec.attribute("openexr:lineOrder", "decreasingY");
    if (layout.tile) spec.tile_width = spec.tile_height = layout.tile;
    std::vector<float> values(std::size_t(spec.width) * spec.height * 5);
    for (std::size_t i = 0; i < values.size(); ++i)  // in [0, 1) for the unsigned channel
        values[i] = float((i * 7919) % 1000) / 1000.0f + (i % 5 == 4 ? 0.0f : float(i % 3));
    if (layout.mipmap) {  // every level, as a texture tool writes it
        const OIIO::ImageBuf level0(spec, values.data());
        OIIO::ImageSpec config;
        config.tile_width = config.tile_height = layout.tile;
        config.attribute("compression", layout.compression);
        REQUIRE_MESSAGE(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, level0,
                                                         path, config),
                        OIIO::geterror());
        return;
    }
    auto out = OIIO::ImageOutput::create(path);
    REQUIRE(out);
    REQUIRE_MESSAGE(out->open(path, spec), out->geterror());
    REQUIRE_MESSAGE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()), out->geterror());
    REQUIRE(out->close());
}

}  // namespace

TEST_CASE("decoders vs OpenImageIO: EXR in every compression, tiles, levels, types, windows") {
    TempDir dir;
    std::vector<std::pair<std::string, ExrLayout>> files;
    for (const char* c :
         {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"})
        files.push_back({std::string(c) + ".exr", ExrLayout{c}});
    files.push_back({"tiled.exr", ExrLayout{"zip", 16}});
    files.push_back({"mipmapped.exr", ExrLayout{"piz", 8, true}});
    files.push_back({"bottom_first.exr", ExrLayout{"rle", 0, false, true}});
    files.push_back({"window.exr", ExrLayout{"zips", 0, false, false, -3, 5}});
    files.push_back({"tiled_window.exr", ExrLayout{"none", 16, false, false, 7, -2}});
    for (const auto& [name, layout] : files) {
        const std::string path = dir.file(name);
        writeExr(path, layout);
        checkFile(path);
        // The same bytes in memory, as a glTF file embeds an image.
        const std::vector<unsigned char> bytes = test::fileBytes(path);
        checkSame(decodeImageBytes(bytes.data(), bytes.size(), "x.png", AlphaMode::Associated),
                  oiioFile(path, AlphaMode::Associated));
    }
}

TEST_CASE("decoders vs OpenImageIO: the assimp sample files' images") {
    const std::filesystem::path models = "/usr/share/assimp/models";
    if (!std::filesystem::is_directory(models)) {
        MESSAGE("assimp-testmodels is not installed: skipped");
        return;
    }
    // BMP and TGA go to OpenImageIO itself: the module against OpenImageIO linked here.
    CHECK(checkFilesUnder(models, {".png", ".jpg", ".jpeg", ".bmp", ".tga"}) >= 60);
}

TEST_CASE("decoders vs OpenImageIO: bytes in memory") {
    TempDir dir;
    test::writePng(dir.file("a.png"), {5, 3, PNG_COLOR_TYPE_RGBA, 16});
    test::writeImage(dir.file("b.jpg"), 2, 2, 3, std::vector<uint8_t>(12, 99));
    for (const char* name : {"a.png", "b.jpg"}) {
        const std::vector<unsigned char> bytes = test::fileBytes(dir.file(name));
        for (const AlphaMode alpha : kAlphaModes) {
            DecodedImage oiio;
            std::string error;
            REQUIRE(oiioModule().decodeBytes(bytes.data(), bytes.size(), name, alpha, oiio, error));
            checkSame(decodeImageBytes(bytes.data(), bytes.size(), name, alpha), oiio);
        }
    }
}

TEST_CASE("decoders vs OpenImageIO: 8- and 16-bit samples as float are its own conversion") {
    TempDir dir;
    std::vector<uint8_t> all8(256);
    std::vector<uint16_t> all16(65536);
    for (std::size_t i = 0; i < all8.size(); ++i) all8[i] = uint8_t(i);
    for (std::size_t i = 0; i < all16.size(); ++i) all16[i] = uint16_t(i);
    test::writeImage(dir.file("all8.png"), 256, 1, 1, all8);
    test::writeImage(dir.file("all16.png"), 256, 256, 1, all16);
    for (const char* name : {"all8.png", "all16.png"}) {
        const std::string path = dir.file(name);
        auto in = OIIO::ImageInput::open(path);
        REQUIRE(in);
        std::vector<float> oiio(std::size_t(in->spec().image_pixels()));
        REQUIRE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, oiio.data()));
        CHECK(sameBytes(readFloatImage(path).values, oiio));
    }
}

TEST_CASE("decoders: a damaged PNG or JPEG is one line naming the file, a cut-short one too") {
    TempDir dir;
    test::writePng(dir.file("ok.png"), {64, 64, PNG_COLOR_TYPE_RGB, 8});
    std::vector<uint8_t> rgb(64 * 64 * 3, 77);
    test::writeImage(dir.file("ok.jpg"), 64, 64, 3, rgb);
    for (const char* name : {"ok.png", "ok.jpg"}) {
        const std::vector<unsigned char> good = test::fileBytes(dir.file(name));
        std::vector<std::vector<unsigned char>> bad;
        for (const std::size_t size : {std::size_t(4), std::size_t(20), good.size() / 2})
            bad.emplace_back(good.begin(), good.begin() + std::ptrdiff_t(size));
        bad.push_back(good);
        for (std::size_t i = 40; i < good.size(); i += 3) bad.back()[i] ^= 0x5a;  // scrambled
        for (std::size_t k = 0; k < bad.size(); ++k) {
            const std::string path = dir.file("bad" + std::to_string(k) + "_" + name);
            std::ofstream(path, std::ios::binary)
                .write(reinterpret_cast<const char*>(bad[k].data()),
                       std::streamsize(bad[k].size()));
            std::string message;
            try {
                readSkyImage(path);
            } catch (const std::runtime_error& e) {
                message = e.what();
            }
            CAPTURE(message);
            // Cut short (k < 3), both are refused: libjpeg would fill a JPEG's missing rows
            // with grey, as it did for OpenImageIO. Scrambled, a JPEG may still decode.
            if (k == 3 && message.empty()) continue;
            CHECK(message.rfind("cannot read '" + path + "': ", 0) == 0);
            CHECK(message.find('\n') == std::string::npos);
        }
    }
}

TEST_CASE("decoders: OpenImageIO reads the format a name says, EXR bytes go by their own") {
    // OpenImageIO's default is to try every reader after the named one refuses a file (raw
    // camera files, DICOM, video...): an embedded image glTF calls a PNG would be parsed by any
    // of them. ssrt turns that off; its own decoders go by the bytes.
    TempDir dir;
    const std::vector<uint8_t> rgb = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120};
    test::writeImage(dir.file("real.bmp"), 2, 2, 3, rgb);
    test::writeImage(dir.file("real.exr"), 2, 2, 3, rgb);
    const std::vector<unsigned char> bmp = test::fileBytes(dir.file("real.bmp"));
    std::ofstream(dir.file("bmp_named.png"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bmp.data()), std::streamsize(bmp.size()));

    CHECK(readSkyImage(dir.file("real.bmp")).width == 2);  // named for what it holds: read
    std::string message;
    try {
        readSkyImage(dir.file("bmp_named.png"));
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    INFO(message);
    CHECK(message.rfind("cannot read '" + dir.file("bmp_named.png") + "': ", 0) == 0);
    CHECK(message.find('\n') == std::string::npos);
    CHECK_THROWS_AS(
        decodeTextureImage("image 0", bmp.data(), bmp.size(), "image.png", TextureEncoding::Srgb),
        std::runtime_error);

    // EXR bytes under a PNG's name are still an EXR (by their first bytes, as PNG, JPEG and
    // Radiance are).
    const std::vector<unsigned char> exr = test::fileBytes(dir.file("real.exr"));
    const InterleavedImage fromBytes =
        decodeTextureImage("image 1", exr.data(), exr.size(), "image.png", TextureEncoding::Linear);
    CHECK(fromBytes.width == 2);
    CHECK(fromBytes.pixels[0] ==
          readTextureImage(dir.file("real.exr"), TextureEncoding::Linear).pixels[0]);
}
