// Writing the 1920x1080 frame of the default preset (cornell, every layer) to a file, alone:
// the EXR per compression and thread count, and the PNG preview. The frame is rendered once;
// each iteration writes the same file under the system's temporary directory (replaced by
// rename, as `ssrt render` does). Counters: the file's size in MB and its share of the raw
// float bytes. CPU time is the whole process's (every compressing thread): on a shared
// machine it says more than the wall time, which waits for the other loads and the disk.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "io/image_io.h"
#include "renderer/layer_groups.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;
namespace fs = std::filesystem;

namespace {

const Frame& frame1080() {
    static const Frame frame = [] {
        const Scene scene = makeBuiltinScene("cornell");
        RenderSettings rs;
        rs.width = 1920;
        rs.height = 1080;
        Frame f;
        Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), f);
        return f;
    }();
    return frame;
}

std::string benchPath(const char* ext) {
    return (fs::temp_directory_path() / ("ssrt_bench_io" + std::string(ext))).string();
}

// Args: compression (ExrCompression's value), threads.
void BM_WriteExr(benchmark::State& state) {
    const Frame& frame = frame1080();
    WriteOptions options;
    options.compression = ExrCompression(state.range(0));
    options.threads = int(state.range(1));
    const std::string path = benchPath(".exr");
    for (auto _ : state) writeImage(path, frameLayers(frame), options);
    const double raw = double(frame.layers().size()) * frame.width * frame.height * sizeof(float);
    const double bytes = double(fs::file_size(path));
    state.counters["MB"] = bytes / 1e6;
    state.counters["of_raw"] = bytes / raw;
    state.SetLabel(std::string(exrCompressionName(options.compression)) + ", " +
                   std::to_string(frame.layers().size()) + " layers");
    fs::remove(path);
}

void BM_WritePng(benchmark::State& state) {
    const Frame& frame = frame1080();
    const std::string path = benchPath(".png");
    for (auto _ : state) writeImage(path, frameLayers(frame));
    state.counters["MB"] = double(fs::file_size(path)) / 1e6;
    fs::remove(path);
}

}  // namespace

BENCHMARK(BM_WriteExr)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {1, 2}})
    ->ArgNames({"compression", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_WritePng)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
