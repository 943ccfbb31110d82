// Texture images through OpenImageIO (io/texture_io.h): 8- and 16-bit values normalized by
// one division, sRGB decoded for base colour only, grey and RGB expanded to RGBA, the same
// texels from a file and from bytes in memory, and one-line errors for what cannot be read.
#include "io/texture_io.h"

#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/color.h"
#include "image_files.h"
#include "scenes/texture.h"
#include "temp_dir.h"

using namespace ssrt;
using test::TempDir;
using test::writeImage;

namespace {

// What the glTF loader does with a decoded image (scenes/gltf_textures.cpp): a Texture of it.
Texture readTexture(const std::string& path, TextureEncoding encoding) {
    return makeTexture(path, readTextureImage(path, encoding));
}
Texture decodeTexture(const std::string& name, const void* bytes, std::size_t size,
                      const std::string& formatHint, TextureEncoding encoding) {
    return makeTexture(name, decodeTextureImage(name, bytes, size, formatHint, encoding));
}

std::string errorOf(const std::string& path) {
    try {
        readTexture(path, TextureEncoding::Linear);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("texture io: 8-bit RGBA PNG, linear and sRGB") {
    TempDir dir;
    std::vector<uint8_t> v;
    for (int i = 0; i < 3 * 2 * 4; ++i) v.push_back(uint8_t(i * 11));
    writeImage(dir.file("rgba.png"), 3, 2, 4, v);

    const Texture lin = readTexture(dir.file("rgba.png"), TextureEncoding::Linear);
    REQUIRE(lin.width() == 3);
    REQUIRE(lin.height() == 2);
    for (int i = 0; i < 6; ++i)
        for (int c = 0; c < 4; ++c)
            CHECK(lin.levels[0].texels[i][c] == float(v[i * 4 + c]) / 255.0f);
    // Row 0 of the file is row 0 of the texture (v = 0 at the top).
    CHECK(lin.levels[0].at(0, 1).r == float(v[12]) / 255.0f);

    const Texture srgb = readTexture(dir.file("rgba.png"), TextureEncoding::Srgb);
    for (int i = 0; i < 6; ++i) {
        for (int c = 0; c < 3; ++c)
            CHECK(srgb.levels[0].texels[i][c] == srgbToLinear(float(v[i * 4 + c]) / 255.0f));
        CHECK(srgb.levels[0].texels[i].a == float(v[i * 4 + 3]) / 255.0f);  // alpha stays linear
    }
}

TEST_CASE("texture io: grey and RGB images fill RGBA -- 16-bit keeps its precision") {
    TempDir dir;
    writeImage(dir.file("grey.png"), 2, 1, 1, std::vector<uint8_t>{0, 200});
    const Texture grey = readTexture(dir.file("grey.png"), TextureEncoding::Linear);
    CHECK(grey.levels[0].at(1, 0) == glm::vec4(200.0f / 255, 200.0f / 255, 200.0f / 255, 1.0f));

    writeImage(dir.file("rgb.png"), 1, 1, 3, std::vector<uint8_t>{10, 20, 30});
    CHECK(readTexture(dir.file("rgb.png"), TextureEncoding::Linear).levels[0].at(0, 0) ==
          glm::vec4(10.0f / 255, 20.0f / 255, 30.0f / 255, 1.0f));

    writeImage(dir.file("deep.png"), 1, 1, 3, std::vector<uint16_t>{1, 32768, 65535});
    const glm::vec4 d =
        readTexture(dir.file("deep.png"), TextureEncoding::Linear).levels[0].at(0, 0);
    CHECK(d.r == 1.0f / 65535.0f);
    CHECK(d.g == 32768.0f / 65535.0f);
    CHECK(d.b == 1.0f);
}

TEST_CASE("texture io: bytes in memory decode to the same texels as the file") {
    TempDir dir;
    std::vector<uint8_t> v;
    for (int i = 0; i < 5 * 3 * 3; ++i) v.push_back(uint8_t(i * 37));
    writeImage(dir.file("t.png"), 5, 3, 3, v);
    const std::vector<unsigned char> bytes = test::fileBytes(dir.file("t.png"));
    const Texture a = readTexture(dir.file("t.png"), TextureEncoding::Srgb);
    const Texture b =
        decodeTexture("embedded", bytes.data(), bytes.size(), ".png", TextureEncoding::Srgb);
    CHECK(b.name == "embedded");
    REQUIRE(a.levels.size() == b.levels.size());
    for (std::size_t l = 0; l < a.levels.size(); ++l)
        CHECK(a.levels[l].texels == b.levels[l].texels);
}

TEST_CASE("texture io: unreadable images give one line naming the image") {
    TempDir dir;
    const std::string missing = errorOf(dir.file("absent.png"));
    CHECK(missing.find(dir.file("absent.png")) != std::string::npos);

    writeImage(dir.file("ok.png"), 1, 1, 1, std::vector<uint8_t>{1});
    std::vector<unsigned char> bytes = test::fileBytes(dir.file("ok.png"));
    { std::ofstream(dir.file("garbage.png"), std::ios::binary) << "not a png at all"; }
    const std::string garbage = errorOf(dir.file("garbage.png"));
    CHECK(garbage.find(dir.file("garbage.png")) != std::string::npos);

    bytes.resize(bytes.size() / 2);  // truncated
    for (const std::size_t size : {bytes.size(), std::size_t(8), std::size_t(0)}) {
        CAPTURE(size);
        std::string msg;
        try {
            decodeTexture("image 7", bytes.data(), size, ".png", TextureEncoding::Linear);
        } catch (const std::runtime_error& e) {
            msg = e.what();
        }
        CHECK(msg.rfind("image 7: ", 0) == 0);
        CHECK(msg.find('\n') == std::string::npos);
    }
}
