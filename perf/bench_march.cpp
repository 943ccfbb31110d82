// Marcher benchmarks: each marcher alone on fixed G-buffers (corridor and cornell rendered
// once at 1920x1080), threads 1 (per core) and 2; rays from every surface pixel: mirror
// (coherent), and as the renderer traces them (frame 0, sample 0): VNDF-bounded GGX (`_vndf`)
// and cosine-weighted diffuse (`_cosine`), both incoherent. Counters rays/s, steps/s, lane
// utilisation, mean steps and hits. Also the Hi-Z build.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "tests/trace/march_fixture.h"
#include "trace/ray_gen.h"

using namespace ssrt;
using namespace ssrt::test;

namespace {

enum class Rays { Mirror, Vndf, Cosine };

struct Workload {
    GBuf g;
    PlaneF roughness;
    RayBatch rays[3];  // by Rays
    HiZPyramid hiz;
};

// Rendered once per scene and kept for every benchmark.
const Workload& workload(const std::string& scene) {
    static std::map<std::string, std::unique_ptr<Workload>> cache;
    auto& w = cache[scene];
    if (!w) {
        w = std::make_unique<Workload>();
        w->g = renderGBuffer(scene, 1920, 1080, &w->roughness);
        w->rays[int(Rays::Mirror)] = mirrorRays(w->g);
        const GBufferView rg = w->g.view(&w->roughness);
        generateSpecularRays(defaultIsa(), SsrMethod::VndfBounded, 0, 0, w->g.camera, rg,
                             w->rays[int(Rays::Vndf)], 0);
        generateDiffuseRays(defaultIsa(), 0, 0, w->g.camera, rg, w->rays[int(Rays::Cosine)], 0);
        buildHiZ(w->g.viewZ, w->hiz, 0);
    }
    return *w;
}

void marchBench(benchmark::State& state, std::string scene, Marcher marcher,
                Rays kind = Rays::Mirror) {
    const Isa isa = defaultIsa();
    const int threads = int(state.range(0));
    const Workload& w = workload(scene);
    const MarchSettings settings;
    MarchResult result;
    MarchStats stats;
    for (auto _ : state) {
        stats = marchRays(isa, marcher, settings, {}, w.g.camera, w.g.view(), nullptr,
                          marcher == Marcher::HiZ ? &w.hiz : nullptr, w.rays[int(kind)], result,
                          threads);
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
BENCHMARK_CAPTURE(marchBench, corridor_linear_vndf, "corridor", Marcher::Linear, Rays::Vndf)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_linear_cosine, "corridor", Marcher::Linear, Rays::Cosine)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_dda_vndf, "corridor", Marcher::Dda, Rays::Vndf)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_dda_cosine, "corridor", Marcher::Dda, Rays::Cosine)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_hiz_vndf, "corridor", Marcher::HiZ, Rays::Vndf)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, corridor_hiz_cosine, "corridor", Marcher::HiZ, Rays::Cosine)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_linear_vndf, "cornell", Marcher::Linear, Rays::Vndf)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_linear_cosine, "cornell", Marcher::Linear, Rays::Cosine)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_dda_vndf, "cornell", Marcher::Dda, Rays::Vndf)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_dda_cosine, "cornell", Marcher::Dda, Rays::Cosine)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_hiz_vndf, "cornell", Marcher::HiZ, Rays::Vndf)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(marchBench, cornell_hiz_cosine, "cornell", Marcher::HiZ, Rays::Cosine)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(hizBuild)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
