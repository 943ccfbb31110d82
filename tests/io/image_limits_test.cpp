// Image sizes over io/image_limits.h's limits are refused from the header, before a pixel is
// allocated, in every format ssrt reads (issue 33): PNG, JPEG, Radiance HDR and EXR through
// io/'s own decoders, BMP through OpenImageIO's module. The files in tests/io/data/oversized/
// are small valid images whose headers were changed to claim 60000 x 60000 (JPEG: 65000 x
// 65000); each must give one line naming the file, its size and the limit, as an environment
// image and as a texture, from a file and from bytes.
#include "io/image_limits.h"

#include <doctest/doctest.h>
#include <sys/resource.h>
#include <zlib.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "image_files.h"
#include "io/image_io.h"
#include "io/texture_io.h"
#include "png_files.h"
#include "temp_dir.h"

using namespace ssrt;

namespace {

const std::string kOversized = SSRT_SOURCE_DIR "/tests/io/data/oversized/";

std::string thrownBy(const auto& read) {
    try {
        read();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(nothing thrown)";
}

std::string bytesOf(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void checkRefusal(const std::string& message, const std::string& name, const std::string& side) {
    INFO(message);
    CHECK(message.find(name) != std::string::npos);
    CHECK(message.find(side + " x " + side + " pixels") != std::string::npos);
    CHECK(message.find("over the limit of 134217728 pixels") != std::string::npos);
    CHECK(std::count(message.begin(), message.end(), '\n') == 0);
}

}  // namespace

TEST_CASE("image limits: the limits and their message") {
    CHECK(!imageSizeProblem(16384, 8192, 4));
    CHECK(!imageSizeProblem(65536, 2048, 3));
    CHECK(!imageSizeProblem(1, 1, 64));
    CHECK(imageSizeProblem(16384, 8193, 3) ==
          "the image is 16384 x 8193 pixels, over the limit of 134217728 pixels (16384 x 8192) "
          "and 65536 a side");
    CHECK(imageSizeProblem(65537, 1, 3));  // a side too long
    CHECK(imageSizeProblem(0, 5, 3) == "the image is 0 x 5 pixels: empty");
    CHECK(imageSizeProblem(-4294967296, 1, 3));  // a corrupt window, in 64 bits
    CHECK(imageSizeProblem(4, 4, 65) == "the image has 65 channels, over the limit of 64");
}

TEST_CASE("image limits: an oversized header is refused in every format, file and bytes") {
    for (const char* file : {"big.png", "big.jpg", "big.hdr", "big.exr", "big.bmp"}) {
        const std::string path = kOversized + file;
        const std::string side = std::string(file) == "big.jpg" ? "65000" : "60000";
        CAPTURE(file);
        checkRefusal(thrownBy([&] { readSkyImage(path); }), path, side);
        checkRefusal(thrownBy([&] { readTextureImage(path, TextureEncoding::Srgb); }), path, side);
        const std::string bytes = bytesOf(path);
        REQUIRE(bytes.size() < 2000);  // a small file claiming a huge image
        checkRefusal(thrownBy([&] {
                         decodeTextureImage("embedded image 3", bytes.data(), bytes.size(), file,
                                            TextureEncoding::Linear);
                     }),
                     "embedded image 3", side);
    }
}

TEST_CASE("image limits: EXR channel names and attributes check the header too") {
    const std::string path = kOversized + std::string("big.exr");
    checkRefusal(thrownBy([&] { readChannelNames(path); }), path, "60000");
    checkRefusal(thrownBy([&] { readExrStringAttributes(path); }), path, "60000");
}

TEST_CASE("image limits: an EXR header OpenEXR's core library refuses is refused at once") {
    // The sky-image fuzzer's input (667 bytes): a string attribute's size beyond the file and a
    // channel sampled every 1.7e9 rows, which OpenEXR's InputFile read for 15 s (40 s under
    // ASan) and gigabytes before failing; now one line from the header.
    const std::string path = SSRT_SOURCE_DIR "/tests/io/data/damaged_header.exr";
    const std::string message = thrownBy([&] { readSkyImage(path); });
    INFO(message);
    CHECK(message == "cannot read '" + path +
                         "': the header is damaged: Attribute 'Exif:ImageHistory', type "
                         "'string': Invalid size 1835622262");
}

namespace {

// The pages this process has faulted in so far (each first touch of a page is one).
long pagesTouched() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt + usage.ru_majflt;
}

// `bytes` written to `path` and read as a sky: what was thrown, and the pages touched doing it.
std::pair<std::string, long> readSkyCounting(const std::string& path,
                                             const std::vector<unsigned char>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    const long before = pagesTouched();
    const std::string message = thrownBy([&] { readSkyImage(path); });
    return {message, pagesTouched() - before};
}

void putBigEndian(std::vector<unsigned char>& bytes, std::size_t at, uint32_t value) {
    for (int i = 0; i < 4; ++i) bytes[at + std::size_t(i)] = uint8_t(value >> (24 - 8 * i));
}

// A 64 x 64 PNG whose header claims 16384 x 8192 (its CRC made right again), its data cut
// to what a 64 x 64 image held.
std::vector<unsigned char> pngClaimingLarge(test::TempDir& dir) {
    test::writePng(dir.file("small.png"), {64, 64, PNG_COLOR_TYPE_RGB, 8});
    std::vector<unsigned char> bytes = test::fileBytes(dir.file("small.png"));
    putBigEndian(bytes, 16, 16384);  // IHDR: width, height, then the chunk's CRC
    putBigEndian(bytes, 20, 8192);
    putBigEndian(bytes, 29, uint32_t(crc32(0, bytes.data() + 12, 17)));
    return bytes;
}

// A 64 x 64 JPEG whose frame header (SOF0) claims 16384 x 8192.
std::vector<unsigned char> jpegClaimingLarge(test::TempDir& dir) {
    test::writeImage(dir.file("small.jpg"), 64, 64, 3, std::vector<uint8_t>(64 * 64 * 3, 90));
    std::vector<unsigned char> bytes = test::fileBytes(dir.file("small.jpg"));
    for (std::size_t i = 2; i + 9 < bytes.size(); ++i)
        if (bytes[i] == 0xff && bytes[i + 1] == 0xc0) {  // SOF0: length, precision, height, width
            bytes[i + 5] = 8192 >> 8, bytes[i + 6] = 0;
            bytes[i + 7] = 16384 >> 8, bytes[i + 8] = 0;
            return bytes;
        }
    FAIL("no SOF0 in the test's JPEG");
    return {};
}

// A Radiance file claiming 16384 x 8192 with 64 bytes of flat (not run-length) pixels: stb_image
// reads the rest as zeros.
std::vector<unsigned char> hdrClaimingLarge() {
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n";
    std::vector<unsigned char> bytes(header.begin(), header.end());
    bytes.insert(bytes.end(), 64, 0x80);
    return bytes;
}

// The sky fuzzer's inputs, which OpenImageIO's lenient Radiance reader read, allocating the
// 60000 rows of 2000 pixels claimed ("-Y 60000 +X 2000rgbe") and trying them row by row
// (5-8 s under ASan): regression_hdr_lenient_header.bin (68 bytes) has a first line stb_image
// refuses ("#?RAD2-bitE"), regression_hdr_no_magic.bin (61) no "#?" at all.
std::vector<unsigned char> skySeed(const std::string& name) {
    return test::fileBytes(SSRT_SOURCE_DIR "/tests/fuzz/seeds/sky_image/" + name);
}

}  // namespace

TEST_CASE("image limits: a small file claiming a large image is refused having touched little") {
    // 16384 x 8192 is within the limits; each file holds a few of those pixels. Each is refused
    // as damaged (cut short), without its decoder first touching the claimed pixels: 128 Mi
    // of them, 384 MiB as 8-bit RGB, 1.5 GiB as float, some 100 k pages or more. Zeroing the
    // samples before decoding, or decoding the missing rows as grey (JPEG) or zeros (HDR),
    // touches them all.
    test::TempDir dir;
    const std::vector<std::pair<std::string, std::vector<unsigned char>>> files = {
        {"claims.png", pngClaimingLarge(dir)},
        {"claims.jpg", jpegClaimingLarge(dir)},
        {"claims.hdr", hdrClaimingLarge()},
        {"claims_lenient.hdr", skySeed("regression_hdr_lenient_header.bin")},
        {"claims_no_magic.hdr", skySeed("regression_hdr_no_magic.bin")}};
    for (const auto& file : files) {
        // (Named variables, not a structured binding: clang 14's lambdas, in CAPTURE, cannot
        // capture one.)
        const std::string& name = file.first;
        const std::vector<unsigned char>& bytes = file.second;
        CAPTURE(name);
        const std::string path = dir.file(name);
        const std::pair<std::string, long> read = readSkyCounting(path, bytes);
        const std::string& message = read.first;
        const long touched = read.second;
        INFO(message);
        CHECK(message.rfind("cannot read '" + path + "': ", 0) == 0);
        CHECK(std::count(message.begin(), message.end(), '\n') == 0);
        // 160 MB of 4 KB pages, under half of the 384 MiB the claimed 8-bit RGB takes: a few
        // of its rows, libpng's and libjpeg's own buffers and, under ASan, the shadow of the
        // claim (an eighth of it: 24.6 k pages in all there, under 20 k without).
        CHECK(touched < 40000);
        // A Radiance file is refused from its header by ssrt, not by the library reading it
        // (OpenImageIO allocates the claim first, and under ASan poisons and frees all of it).
        if (name.ends_with(".hdr")) CHECK(message.find("is cut short") != std::string::npos);
        const std::string asTexture = thrownBy([&] {
            decodeTextureImage("embedded image 1", bytes.data(), bytes.size(), name,
                               TextureEncoding::Srgb);
        });
        CHECK(asTexture.rfind("embedded image 1: cannot decode the image: ", 0) == 0);
    }
}

TEST_CASE("image limits: a PNG chunk longer than the file is refused before its buffer") {
    // The texture fuzzer's input (tests/fuzz/seeds/texture/regression_chunk_too_large.png): a
    // text chunk claiming 1.8 GB in a 607-byte PNG (after the fuzz input's first byte).
    // libpng 1.6.39 only warns that the chunk is too long, then allocates and zeroes 1.8 GB for it
    // (8.5 s under ASan) before the file runs out.
    test::TempDir dir;
    test::writePng(dir.file("small.png"), {4, 4, PNG_COLOR_TYPE_RGB, 8});
    const std::vector<unsigned char> png = test::fileBytes(dir.file("small.png"));
    std::vector<unsigned char> bytes(png.begin(), png.begin() + 33);  // signature and IHDR
    const unsigned char chunk[] = {0x70, 0x60, 0x00, 0x00, 't', 'E', 'X', 't', 'k', 'e', 'y', 0};
    bytes.insert(bytes.end(), std::begin(chunk), std::end(chunk));
    bytes.insert(bytes.end(), png.begin() + 33, png.end());  // the rest, inside the "text"
    const std::string path = dir.file("long_chunk.png");
    const std::pair<std::string, long> read = readSkyCounting(path, bytes);
    const std::string& message = read.first;
    const long touched = read.second;
    INFO(message);
    CHECK(message ==
          "cannot read '" + path + "': tEXt: chunk data is too large: longer than the file");
    CHECK(touched < 40000);  // as above; with the chunk's buffer zeroed, 460 k
}

TEST_CASE("image limits: an EXR whose chunks the file does not hold is refused at once") {
    // The texture fuzzer's input (279 bytes after its first byte; sky_image's and merge's were
    // alike): a header without its end, whose chunk table OpenEXR's core library finds out of
    // range. OpenEXR's InputFile read the same header as a 4005380 x 4 image, sized its
    // decompression buffers by that and took 13.8 s under ASan; the core library, which reads
    // the pixels now, refuses the first chunk.
    const std::string committed = SSRT_SOURCE_DIR "/tests/io/data/damaged_chunk_table.exr";
    test::TempDir dir;
    const std::string path = dir.file("damaged_chunk_table.exr");
    const std::string expected =
        "chunk 0 of 4 cannot be read: Invalid chunk size "
        "reconstructing chunk table: found out of range 7827300";
    const std::pair<std::string, long> read = readSkyCounting(path, test::fileBytes(committed));
    INFO(read.first);
    CHECK(read.first == "cannot read '" + path + "': " + expected);
    CHECK(read.second < 2000);  // 8 MB of pages; InputFile's buffers alone were 230 MB
    const std::string bytes = bytesOf(committed);
    CHECK(thrownBy([&] {
              decodeTextureImage("embedded image 2", bytes.data(), bytes.size(), "x.exr",
                                 TextureEncoding::Linear);
          }) == "embedded image 2: cannot decode the image: " + expected);
}
