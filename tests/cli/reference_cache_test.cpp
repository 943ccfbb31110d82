// The reference cache on a folder many writers share (a Slurm array's tasks on a shared
// file system): writers racing on one key leave one whole file, and a reader never sees a
// torn one; an entry holds its key and a checksum of its pixels, so that a truncated, bit-
// flipped, foreign or old entry is told apart from a good one (cli/reference_cache.h
// readCacheEntry; the command's warning and re-render: reference_cache_cli_test.cpp).
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <atomic>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include "cache_damage.h"
#include "cli/reference_cache.h"
#include "io/image_io.h"
#include "temp_dir.h"
#include "text_files.h"

using namespace ssrt;
using test::TempDir;

namespace {

constexpr int kWidth = 96, kHeight = 64;

ReferenceImage filled(float value) {
    ReferenceImage ref;
    for (PlaneF* p : cli::referencePlanes(ref)) {
        *p = PlaneF(kWidth, kHeight);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) p->at(x, y) = value + 1e-3f * float(x + y);
    }
    return ref;
}

// The value every plane of `ref` was filled with, or 0 when they disagree (a torn file).
float wholeValue(ReferenceImage& ref) {
    float value = 0.0f;
    for (PlaneF* p : cli::referencePlanes(ref))
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const float v = p->at(x, y) - 1e-3f * float(x + y);
                const float nearest = v < 1.5f ? 1.0f : 2.0f;
                if (!(std::abs(v - nearest) < 1e-4f)) return 0.0f;
                if (value == 0.0f) value = nearest;
                if (nearest != value) return 0.0f;
            }
    return value;
}

}  // namespace

TEST_CASE("reference cache: two writers racing on one file leave one whole file") {
    TempDir dir;
    const std::string path = dir.file("ref-00000000000000aa.exr");
    const ReferenceImage one = filled(1.0f), two = filled(2.0f);
    std::atomic<bool> done{false};
    std::atomic<int> reads{0}, torn{0};
    std::thread reader([&] {
        while (!done) {
            if (!std::filesystem::exists(path)) continue;  // once there, it stays
            ReferenceImage got;
            ++reads;
            if (!cli::readReferenceImage(path, kWidth, kHeight, got) || wholeValue(got) == 0.0f)
                ++torn;
        }
    });
    const auto writer = [&](const ReferenceImage& ref) {
        for (int i = 0; i < 25; ++i) cli::writeReferenceImage(path, ref);
    };
    std::thread a(writer, std::cref(one)), b(writer, std::cref(two));
    a.join();
    b.join();
    done = true;
    reader.join();
    CHECK(reads > 0);
    CHECK(torn == 0);
    // One file, no temporary left behind, and it is one writer's whole reference.
    CHECK(dir.listing() == std::vector<std::string>{"ref-00000000000000aa.exr"});
    ReferenceImage last;
    REQUIRE(cli::readReferenceImage(path, kWidth, kHeight, last));
    const float v = wholeValue(last);
    CHECK((v == 1.0f || v == 2.0f));
}

TEST_CASE("reference cache: writers racing on one entry leave one that verifies") {
    TempDir dir;
    constexpr uint64_t kKey = 0xabcdef0123456789ull;
    const ReferenceImage one = filled(1.0f), two = filled(2.0f);
    const auto writer = [&](const ReferenceImage& ref) {
        for (int i = 0; i < 25; ++i) cli::writeCacheEntry(dir.path.string(), kKey, ref);
    };
    std::thread a(writer, std::cref(one)), b(writer, std::cref(two));
    a.join();
    b.join();
    CHECK(dir.listing() == std::vector<std::string>{cli::referenceCacheFileName(kKey)});
    ReferenceImage last;
    CHECK(cli::readCacheEntry(dir.file(cli::referenceCacheFileName(kKey)), kKey, kWidth, kHeight,
                              last) == std::nullopt);
    const float v = wholeValue(last);
    CHECK((v == 1.0f || v == 2.0f));
}

namespace {

constexpr uint64_t kKey = 0x00000000000000aaull;

// A good entry for kKey in `dir`; returns its path.
std::string goodEntry(const TempDir& dir) {
    return cli::writeCacheEntry(dir.path.string(), kKey, filled(1.0f));
}

// What readCacheEntry says of the file at `path` for kKey, "" when it takes it.
std::string problemOf(const std::string& path) {
    ReferenceImage ref;
    return cli::readCacheEntry(path, kKey, kWidth, kHeight, ref).value_or("");
}

// Where an EXR's header ends (single-part: the magic and version, then attributes, each a name,
// a type, a 4-byte size and a value, until an empty name): its offset table starts there.
std::size_t exrHeaderEnd(const std::string& file) {
    std::size_t at = 8;
    while (at < file.size() && file[at] != '\0') {
        at = file.find('\0', at) + 1;  // the name
        at = file.find('\0', at) + 1;  // the type
        int32_t size = 0;
        std::memcpy(&size, file.data() + at, 4);
        at += 4 + std::size_t(size);
    }
    return at + 1;
}

}  // namespace

TEST_CASE("reference cache: an entry holds its key and checksum and reads back as written") {
    TempDir dir;
    const std::string path = goodEntry(dir);
    CHECK(path == dir.file("ref-00000000000000aa.exr"));
    const auto attrs = readExrStringAttributes(path);
    CHECK(attrs.at(cli::kCacheKeyAttribute) == "00000000000000aa");
    CHECK(attrs.at(cli::kChecksumAttribute).size() == 16);
    ReferenceImage ref;
    CHECK(cli::readCacheEntry(path, kKey, kWidth, kHeight, ref) == std::nullopt);
    CHECK(wholeValue(ref) == 1.0f);
    CHECK(cli::referenceChecksum(ref) == cli::referenceChecksum(filled(1.0f)));
    CHECK(cli::referenceChecksum(ref) != cli::referenceChecksum(filled(2.0f)));
    CHECK(problemOf(dir.file("ref-00000000000000bb.exr")) == cli::kCacheEntryMissing);
    CHECK(cli::referenceKeyOfCacheFileName("ref-00000000000000aa.exr") == kKey);
    CHECK_THROWS_AS(cli::referenceKeyOfCacheFileName("ref-00000000000000ag.exr"),
                    std::runtime_error);
    CHECK_THROWS_AS(cli::referenceKeyOfCacheFileName("ref-aa.exr"), std::runtime_error);
}

TEST_CASE("reference cache: truncated, bit-flipped, foreign and old entries are each found") {
    TempDir dir;
    const std::string path = goodEntry(dir);
    const std::string good = test::readFile(path);
    SUBCASE("truncated") {
        test::writeFile(path, good.substr(0, good.size() / 2));
        CHECK(problemOf(path).rfind("cannot be read (", 0) == 0);
    }
    SUBCASE("a bit of one value flipped, the header kept") {
        // The lowest mantissa bit: 1 ulp.
        REQUIRE(test::flipPixelKeepHeader(path, kWidth, kHeight, 7, 40, 30, 0));
        CHECK(problemOf(path) == "its pixels do not match their checksum (damaged)");
    }
    SUBCASE("another key's entry under its name") {
        const std::string other = cli::writeCacheEntry(dir.file("other"), 0xbbull, filled(1.0f));
        std::filesystem::copy_file(other, path, std::filesystem::copy_options::overwrite_existing);
        CHECK(problemOf(path) ==
              "is the entry of key 00000000000000bb, not 00000000000000aa "
              "(another request's file under its name)");
    }
    SUBCASE("an older ssrt's entry: no key, no checksum") {
        cli::writeReferenceImage(path, filled(1.0f));
        CHECK(problemOf(path) == "holds no key or checksum (an older ssrt's entry)");
    }
    SUBCASE("its key, another size") {
        ReferenceImage small;
        for (PlaneF* p : cli::referencePlanes(small)) *p = PlaneF(48, 32);
        cli::writeCacheEntry(dir.path.string(), kKey, small);
        CHECK(problemOf(path) == "is 48 x 32 pixels, not 96 x 64");
    }
    SUBCASE("a folder in its place") {
        std::filesystem::remove(path);
        std::filesystem::create_directory(path);
        CHECK(problemOf(path).rfind("cannot be read (", 0) == 0);
    }
}

TEST_CASE("reference cache: 100 damaged entries, none taken") {
    // Truncated at 34 lengths, 33 single bits flipped in the chunks (their headers and pixel
    // data, past the header and the offset table), 33 other keys' entries under its name.
    TempDir dir;
    const std::string path = goodEntry(dir);
    const std::string good = test::readFile(path);
    // The offset table: 8 bytes for each of the 64 one-row chunks (RLE) after the header.
    const std::size_t headerEnd = exrHeaderEnd(good), chunksStart = headerEnd + 8 * kHeight;
    REQUIRE(headerEnd > 18 * 14);  // 18 channels named
    REQUIRE(good.size() > 40 * chunksStart);
    int damaged = 0, refused = 0;
    const auto check = [&](const std::string& bytes, const std::string& what, std::size_t at) {
        test::writeFile(path, bytes);
        const std::string problem = problemOf(path);
        CAPTURE(what);
        CAPTURE(at);
        CHECK(!problem.empty());
        ++damaged;
        refused += !problem.empty();
    };
    for (std::size_t k = 0; k < 34; ++k) {
        const std::size_t length = k * (good.size() - 1) / 33;  // 0 to one byte short
        check(good.substr(0, length), "truncated", length);
    }
    const auto flipped = [&](std::size_t at, int bit) {
        std::string bytes = good;
        bytes[at] = char(bytes[at] ^ (1 << bit));
        return bytes;
    };
    for (std::size_t k = 0; k < 33; ++k) {
        const std::size_t at = chunksStart + k * (good.size() - chunksStart - 1) / 32;
        check(flipped(at, int(k % 8)), "bit flipped", at);
    }
    for (uint64_t k = 0; k < 33; ++k) {
        const std::string other =
            cli::writeCacheEntry(dir.file("other"), 0x100 + k, filled(1.0f + 0.01f * float(k)));
        check(test::readFile(other), "another key's", std::size_t(k));
    }
    CHECK(damaged == 100);
    CHECK(refused == 100);
    // A flipped bit in the offset table is refused, or OpenEXR finds the chunks without it
    // (it rebuilds a table that does not fit the file) and the pixels are the entry's own:
    // never a wrong reference.
    for (std::size_t k = 0; k < 8; ++k) {
        const std::size_t at = headerEnd + 8 * (8 * k) + k;  // entry 8k's byte k
        test::writeFile(path, flipped(at, int(k)));
        ReferenceImage ref;
        CAPTURE(at);
        CHECK((cli::readCacheEntry(path, kKey, kWidth, kHeight, ref) ||
               cli::referenceChecksum(ref) == cli::referenceChecksum(filled(1.0f))));
    }
}

#endif  // SSRT_CLI_LIB
