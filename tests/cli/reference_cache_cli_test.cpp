// `ssrt reference` over a damaged cache entry (issue 47): a truncated, bit-flipped, foreign or
// old entry is warned about in one line naming the file and what was wrong, the reference is
// rendered again, the output is the one a clean run writes, byte for byte, and the entry is
// replaced by one that verifies, nothing else left in the cache. (Racing processes:
// tests/cli/check_reference_cache_race.sh.)
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cache_damage.h"
#include "cli/reference_cache.h"
#include "cli_run.h"
#include "temp_dir.h"

using namespace ssrt;
using test::contains;
using test::runSsrt;
using test::TempDir;

namespace {

constexpr int kWidth = 32, kHeight = 18;

// A small reference of the cornell scene with `spp` samples, cached in `cache`, written to `out`.
test::CliResult reference(const std::string& cache, const std::string& out, const char* spp = "2") {
    return runSsrt({"reference", "--scene", "cornell", "--width", "32", "--height", "18",
                    "--reference-spp", spp, "--shadow-map-size", "128", "-j", "2", "--cache-dir",
                    cache, "-o", out});
}

// The one entry of a cache folder (a temporary left beside it would be a second).
std::string onlyEntry(const TempDir& dir, const std::string& cache) {
    std::vector<std::string> paths;
    for (const auto& e : std::filesystem::directory_iterator(dir.file(cache)))
        paths.push_back(e.path().string());
    REQUIRE(paths.size() == 1);
    return paths[0];
}

uint64_t keyOf(const std::string& entry) {
    return cli::referenceKeyOfCacheFileName(std::filesystem::path(entry).filename().string());
}

}  // namespace

TEST_CASE("reference cache: a damaged entry is warned about, rendered again and replaced") {
    TempDir dir;
    const test::CliResult first = reference(dir.file("cache"), dir.file("clean.exr"));
    REQUIRE(first.code == 0);
    REQUIRE(contains(first.err, "reference: rendered"));
    const std::string entry = onlyEntry(dir, "cache");
    const std::string clean = test::readFile(dir.file("clean.exr"));

    const auto damagedRun = [&](const std::function<void()>& damage, const std::string& what) {
        damage();
        const test::CliResult r = reference(dir.file("cache"), dir.file("again.exr"));
        CHECK(r.code == 0);
        // One warning line, naming the entry and what was wrong; then a fresh render.
        CHECK(contains(r.err, "ssrt: warning: reference cache: '" + entry + "' " + what));
        CHECK(contains(r.err, ": rendering it again\n"));
        int warnings = 0;
        for (const std::string& line : test::textLines(r.err))
            warnings += line.rfind("ssrt: warning: ", 0) == 0;
        CHECK(warnings == 1);
        CHECK(contains(r.err, "reference: rendered"));
        CHECK(test::readFile(dir.file("again.exr")) == clean);
        // The entry replaced by one that verifies, and nothing else in the cache.
        CHECK(onlyEntry(dir, "cache") == entry);
        ReferenceImage ref;
        CHECK(cli::readCacheEntry(entry, keyOf(entry), kWidth, kHeight, ref) == std::nullopt);
    };
    SUBCASE("truncated") {
        damagedRun(
            [&] {
                const std::string bytes = test::readFile(entry);
                test::writeFile(entry, bytes.substr(0, bytes.size() * 2 / 3));
            },
            "cannot be read (");
    }
    SUBCASE("one bit of one value flipped") {
        damagedRun([&] { REQUIRE(test::flipPixelKeepHeader(entry, kWidth, kHeight, 0, 5, 5, 3)); },
                   "its pixels do not match their checksum (damaged)");
    }
    SUBCASE("another request's entry under its name") {
        REQUIRE(reference(dir.file("other"), dir.file("other.exr"), "1").code == 0);
        const std::string other = onlyEntry(dir, "other");
        REQUIRE(keyOf(other) != keyOf(entry));
        damagedRun(
            [&] {
                std::filesystem::copy_file(other, entry,
                                           std::filesystem::copy_options::overwrite_existing);
            },
            "is the entry of key ");
    }
    SUBCASE("an older ssrt's entry, without key or checksum") {
        damagedRun(
            [&] {
                ReferenceImage ref;
                REQUIRE(cli::readReferenceImage(entry, kWidth, kHeight, ref));
                cli::writeReferenceImage(entry, ref);
            },
            "holds no key or checksum (an older ssrt's entry)");
    }
    // Whole again: taken from the cache without a word.
    const test::CliResult last = reference(dir.file("cache"), dir.file("last.exr"));
    CHECK(last.code == 0);
    CHECK(contains(last.err, "reference: from the cache"));
    CHECK(!contains(last.err, "warning"));
    CHECK(test::readFile(dir.file("last.exr")) == clean);
}

#endif  // SSRT_CLI_LIB
