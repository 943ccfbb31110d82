// Marcher benchmarks: each marcher alone on fixed G-buffers (corridor and cornell rendered
// once at 1920x1080), mirror rays from every surface pixel, threads 1 (per core) and 2;
// counters rays/s, steps/s, lane utilisation, mean steps and hits. Also the Hi-Z build.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "tests/trace/march_fixture.h"

using namespace ssrt;
using namespace ssrt::test;

namespace {

struct Workload {
    GBuf g;
    RayBatch rays;
    HiZPyramid hiz;
};

// Rendered once per scene and kept for every benchmark.
const Workload& workload(const std::string& scene) {
    static std::map<std::string, std::unique_ptr<Workload>> cache;
    auto& w = cache[scene];
    if (!w) {
        w = std::make_unique<Workload>();
        w->g = renderGBuffer(scene, 1920, 1080);
        w->rays = mirrorRays(w->g);
        buildHiZ(w->g.viewZ, w->hiz, 0);
    }
    return *w;
}

void marchBench(benchmark::State& state, std::string scene, Marcher marcher) {
    const Isa isa = defaultIsa();
    const int threads = int(state.range(0));
    const Workload& w = workload(scene);
    const MarchSettings settings;
    MarchResult result;
    MarchStats stats;
    for (auto _ : state) {
        stats = marchRays(isa, marcher, settings, w.g.camera, w.g.view(),
                          marcher == Marcher::HiZ ? &w.hiz : nullptr, w.rays, result, threads);
        benchmark::DoNotOptimize(result.hit.row(0));
    }
    const double iters = double(state.iterations());
    using C = benchmark::Counter;
    state.counters["rays/s"] = C(double(stats.rays) * iters, C::kIsRate);
    state.counters["steps/s"] = C(double(stats.steps) * iters, C::kIsRate);
    state.counters["steps/ray"] = stats.meanSteps();
    state.counters["p95steps"] = stats.stepsPercentile(0.95);
    state.counters["lane_util"] = stats.laneUtilisation();
    state.counters["hit_share"] = double(stats.ends[0]) / double(stats.rays);
    state.counters["cap_share"] = double(stats.ends[int(MarchEnd::StepCap)]) / double(stats.rays);
    state.SetLabel(std::string(isaName(isa)));
}

void hizBuild(benchmark::State& state) {
    const int threads = int(state.range(0));
    const Workload& w = workload("corridor");
    HiZPyramid hiz;
    for (auto _ : state) {
        buildHiZ(w.g.viewZ, hiz, threads);
        benchmark::DoNotOptimize(hiz.minZ.back().row(0));
    }
    state.counters["pixels/s"] = benchmark::Counter(1920.0 * 1080.0 * double(state.iterations()),
                                                    benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_CAPTURE(marchBench, corridor_linear, "corridor", Marcher::Linear)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_dda, "corridor", Marcher::Dda)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_hiz, "corridor", Marcher::HiZ)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_linear, "cornell", Marcher::Linear)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_dda, "cornell", Marcher::Dda)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_hiz, "cornell", Marcher::HiZ)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(hizBuild)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
