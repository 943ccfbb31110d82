// ssrt_soak: a long sequence through the library, frame after frame in one process, for
// perf/soak.sh (issue 33), not the unit suite. The cornell scene at 320x180 along a camera
// path with two cuts, its mirror sphere moving on a circle (rigid motion: motion vectors), one
// history carried from frame to frame as `ssrt render` carries it. Per frame it writes a CSV
// row: the frame, a hash of every layer (tests/frame_hash.h's), the layers' non-finite values,
// the wall and CPU time, the resident memory and the open file descriptors after the frame.
//
// --write-every N --out DIR writes every N-th frame (i % N == 0) as `ssrt render` writes a
// frame (cli/options.h writeFrame: every layer, an EXR), DIR/frame_NNNNN.exr: what a long
// run's file output leaks or leaves behind (descriptors, temporaries) shows in the
// descriptor count and in DIR's listing.
//
// --nan-frame F corrupts the input of frame F: before it renders, one pixel of every plane of
// the history (the caller's FrameHistory, which the frame reads) is set to NaN, as a corrupt
// or uninitialised history handed in by a caller would be. No output may then hold a NaN.
// --shard K/N renders frames [k F / N, (k + 1) F / N) as `ssrt render --shard` does: replayed
// from the last history restart (frame 0 or a cut) at or before the block, rows written for
// the block only, so the shards' rows put together are the whole run's.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>

#include "cli/options.h"
#include "cli/shard.h"
#include "core/pixel_formats.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "scenes/camera_path.h"

using namespace ssrt;

namespace {

struct Options {
    int frames = 2000;
    int width = 320, height = 180;
    int nanFrame = -1;  // none
    cli::Shard shard;
    std::string csv = "soak.csv";
    int writeEvery = 0;  // 0: no frame written
    std::string out;     // the folder frames are written to
};

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr,
                 "ssrt_soak: %s\nusage: ssrt_soak [--frames N] [--width W] [--height H] "
                 "[--nan-frame F] [--shard K/N] [--csv FILE] [--write-every N --out DIR]\n",
                 problem.c_str());
    std::exit(2);
}

int intArg(const std::string& flag, const char* text, int lo, int hi) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (*text == '\0' || *end != '\0' || v < lo || v > hi)
        usage(flag + ": invalid value '" + text + "' (expected an integer from " +
              std::to_string(lo) + " to " + std::to_string(hi) + ")");
    return int(v);
}

Options parseOptions(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc) usage(flag + ": needs a value");
        const char* value = argv[++i];
        if (flag == "--frames") o.frames = intArg(flag, value, 1, 1000000);
        else if (flag == "--width") o.width = intArg(flag, value, 8, 8192);
        else if (flag == "--height") o.height = intArg(flag, value, 8, 8192);
        else if (flag == "--nan-frame") o.nanFrame = intArg(flag, value, 0, 1000000);
        else if (flag == "--shard") o.shard = cli::parseShard("--shard", value);
        else if (flag == "--csv") o.csv = value;
        else if (flag == "--write-every") o.writeEvery = intArg(flag, value, 1, 1000000);
        else if (flag == "--out") o.out = value;
        else usage("unknown option '" + flag + "'");
    }
    if ((o.writeEvery > 0) != !o.out.empty()) usage("--write-every and --out go together");
    return o;
}

// Before the box's open front, two cuts: three shots of the same scene, each a small sway,
// framed alike so that every frame costs about the same: the time bar is about the run, not
// about what each shot shows (a sway of 1.2 units made the CPU time per frame swing from 12.5
// to 18.4 ms with the camera's side, the same at the same place early and late).
CameraPath soakPath() {
    CameraPath path;
    path.interpolation = PathInterpolation::CatmullRom;
    const glm::vec3 target{0.0f, 1.0f, 0.0f};
    path.keys = {{0.0, {-0.1f, 1.3f, 4.5f}, target, 45.0f, false},
                 {1.0, {0.1f, 1.35f, 4.45f}, target, 45.0f, false},
                 {2.0, {0.08f, 1.25f, 4.5f}, target, 44.5f, true},
                 {3.0, {-0.08f, 1.35f, 4.45f}, target, 45.5f, false},
                 {4.0, {-0.1f, 1.3f, 4.55f}, target, 45.0f, true},
                 {5.0, {0.1f, 1.3f, 4.45f}, target, 45.0f, false}};
    path.validate();
    return path;
}

// The moving instance's transform at frame i: its own, moved on a circle of 0.3 units.
glm::mat4 movedAt(const glm::mat4& base, int i) {
    const double a = 2.0 * 3.14159265358979 * double(i) / 250.0;
    return glm::translate(glm::mat4(1.0f),
                          glm::vec3(float(0.3 * std::sin(a)), 0.0f, float(0.3 * std::cos(a)))) *
           base;
}

uint64_t frameHash(const Frame& f) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const PlaneRef& p : f.layers()) {
        for (char c : p.name) h = (h ^ uint8_t(c)) * 0x100000001b3ull;
        h = hashPlane(*p.plane, h);
    }
    return h;
}

long long nonFinite(const Frame& f) {
    long long n = 0;
    for (const PlaneRef& p : f.layers())
        for (int y = 0; y < p.plane->height(); ++y)
            for (int x = 0; x < p.plane->width(); ++x) n += !std::isfinite(p.plane->at(x, y));
    return n;
}

// NaN in the radiance the history carries (the colour, the denoiser's diffuse and specular
// signals) over a 16 x 16 block in the middle of the frame (a corrupt or uninitialised region);
// its depth and normals stay valid, so the reprojection accepts those pixels and reads the NaN
// (a NaN depth would be rejected as a disocclusion and test nothing).
int poisonHistory(FrameHistory& history) {
    int planes = 0;
    const auto poison = [&](PlaneF& p) {
        if (p.width() < 16 || p.height() < 16) return;
        for (int y = p.height() / 2 - 8; y < p.height() / 2 + 8; ++y)
            for (int x = p.width() / 2 - 8; x < p.width() / 2 + 8; ++x) p.at(x, y) = std::nanf("");
        ++planes;
    };
    for (PlaneF& p : history.color) poison(p);
    for (PlaneF& p : history.diffuse) poison(p);
    // (The denoiser's f16x4 signals: a NaN's bits, as encodeF16 gives them, in all four
    // channels.)
    const auto poison16x4 = [&](PlaneU64& p) {
        if (p.width() < 16 || p.height() < 16) return;
        for (int y = p.height() / 2 - 8; y < p.height() / 2 + 8; ++y)
            for (int x = p.width() / 2 - 8; x < p.width() / 2 + 8; ++x)
                p.at(x, y) = 0x0001000100010001ull * encodeF16(std::nanf(""));
        ++planes;
    };
    for (DenoiseHistory* d : {&history.denoise, &history.denoiseHalf}) {
        poison16x4(d->diffuse);
        poison16x4(d->specular);
    }
    return planes;
}

// CPU time of the whole process (every thread), in milliseconds: the renderer's own work,
// which other processes on a shared machine do not lengthen as they lengthen the wall time.
double cpuMs() {
    rusage use{};
    getrusage(RUSAGE_SELF, &use);
    const auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + t.tv_usec / 1e3; };
    return ms(use.ru_utime) + ms(use.ru_stime);
}

long residentKiB() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// The process's open file descriptors (the entries of /proc/self/fd, less the one that lists
// them): a write that leaks one shows as a count that grows.
long openDescriptors() {
    long n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd"))
        ++n;
    return n - 1;
}

// frame_00042.exr
std::string frameFileName(int i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.exr", i);
    return name;
}

}  // namespace

int main(int argc, char** argv) try {
    const Options o = parseOptions(argc, argv);
    Scene scene = makeBuiltinScene("cornell");
    const std::size_t moving = scene.instances.size() - 1;
    const glm::mat4 base = scene.instances[moving].transform;
    const CameraPath path = soakPath();
    RenderSettings settings;
    settings.width = o.width;
    settings.height = o.height;
    const Renderer renderer(settings);

    const cli::ItemRange block = cli::shardBlock(o.shard, o.frames);
    const auto timeOf = [&](int i) { return path.frameTime(i, o.frames); };
    const auto restarts = [&](int i) {
        return i == 0 || path.cutBetween(timeOf(i - 1), timeOf(i));
    };
    int start = int(block.begin);
    while (start > 0 && !restarts(start)) --start;

    std::ofstream csv(o.csv);
    csv << "frame,hash,nonfinite,ms,cpu_ms,rss_kib,fds\n";
    FrameHistory history;
    Frame frame;
    for (int i = start; i < int(block.end); ++i) {
        const bool reset = restarts(i);
        FrameInput input;
        input.frameIndex = uint32_t(i);
        input.camera = path.at(timeOf(i), scene.camera);
        input.previousCamera = reset ? input.camera : path.at(timeOf(i - 1), scene.camera);
        input.resetHistory = reset;
        scene.instances[moving].transform = movedAt(base, i);
        scene.instances[moving].previousTransform = movedAt(base, reset ? i : i - 1);
        if (i == o.nanFrame)
            std::fprintf(stderr, "ssrt_soak: frame %d: a NaN in %d history planes\n", i,
                         poisonHistory(history));
        const auto t0 = std::chrono::steady_clock::now();
        const double cpu0 = cpuMs();
        renderer.render(scene, input, history, frame);
        const double cpu = cpuMs() - cpu0;
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        if (i < block.begin) continue;  // replayed for its history only
        if (o.writeEvery > 0 && i % o.writeEvery == 0)
            cli::writeFrame((std::filesystem::path(o.out) / frameFileName(i)).string(), frame, {});
        char hash[17];
        std::snprintf(hash, sizeof hash, "%016llx", (unsigned long long)frameHash(frame));
        csv << i << "," << hash << "," << nonFinite(frame) << "," << ms << "," << cpu << ","
            << residentKiB() << "," << openDescriptors() << "\n";
    }
    if (!csv.flush()) throw std::runtime_error("cannot write '" + o.csv + "'");
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "ssrt_soak: error: %s\n", e.what());
    return 3;
}
