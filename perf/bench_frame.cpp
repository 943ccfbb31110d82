// The whole frame at 1920x1080 on 2 threads: raster, direct light, one SSR and one SSGI ray
// per pixel (Hi-Z marcher by default), resolve and composite; each pass's mean time is a
// counter beside the total, so one run gives the breakdown. `hidden:1` also traces the rays
// the composite hides (TraceSettings::traceHidden: SSR past the roughness fade, SSGI on
// metals), so every surface pixel has its two rays, as the issue defines the frame.
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

const char* const kScenes[] = {"cornell", "corridor", "spheres"};
const Marcher kMarchers[] = {Marcher::HiZ, Marcher::Dda, Marcher::Linear};

// Args: scene index, marcher index, threads, trace hidden rays (0 or 1).
void BM_Frame(benchmark::State& state) {
    const Scene scene = makeBuiltinScene(kScenes[state.range(0)]);
    RenderSettings rs;
    rs.width = 1920;
    rs.height = 1080;
    rs.threads = int(state.range(2));
    rs.trace.marcher = kMarchers[state.range(1)];
    rs.trace.traceHidden = state.range(3) != 0;
    const Renderer r(rs);
    Frame f;  // reused: no allocation after the first frame
    r.renderWithoutHistory(scene, FrameInput::still(scene), f);
    std::map<std::string, double> passMs;
    for (auto _ : state) {
        r.renderWithoutHistory(scene, FrameInput::still(scene), f);
        for (const PassTime& p : f.stats.passes) passMs[p.name] += p.ms;
    }
    for (const auto& [name, ms] : passMs)
        state.counters[name + "_ms"] = ms / double(state.iterations());
    state.counters["ssr_steps_per_ray"] = f.stats.ssr.march.meanSteps();
    state.counters["ssgi_steps_per_ray"] = f.stats.ssgi.march.meanSteps();
    state.counters["ssr_rays"] = double(f.stats.ssr.march.rays);
    state.counters["ssgi_rays"] = double(f.stats.ssgi.march.rays);
    state.SetLabel(std::string(kScenes[state.range(0)]) + " " +
                   std::string(marcherName(rs.trace.marcher)));
}

}  // namespace

BENCHMARK(BM_Frame)
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2}, {2}, {0}})
    ->Args({0, 0, 2, 1})
    ->Args({1, 0, 2, 1})
    ->Args({2, 0, 2, 1})
    ->ArgNames({"scene", "marcher", "threads", "hidden"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
