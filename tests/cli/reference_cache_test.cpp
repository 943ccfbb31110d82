// The reference cache on a folder many writers share (a Slurm array's tasks on a shared
// file system): writers racing on one key leave one whole file, and a reader never sees a
// torn one.
#include <doctest/doctest.h>

#ifdef SSRT_CLI_LIB

#include <atomic>
#include <filesystem>
#include <string>
#include <thread>

#include "cli/reference_cache.h"
#include "temp_dir.h"

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

#endif  // SSRT_CLI_LIB
