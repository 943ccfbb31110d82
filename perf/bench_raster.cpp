// Rasterizer and pass benchmarks: small and large triangles (triangles/s, pixels/s), and the
// whole G-buffer and shadow passes on the benchmark scenes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/rng.h"
#include "raster/raster.h"
#include "raster/shadow_map.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

// A screen-space soup of `count` triangles about `size` pixels across, at random depths.
Scene triangleSoup(int count, float size, int w, int h) {
    Scene s;
    Mesh m;
    for (int i = 0; i < count; ++i) {
        auto rnd = [&](uint32_t d) { return randomFloat(uint32_t(i), 11, 0, d); };
        const glm::vec2 c(rnd(0) * w, rnd(1) * h);
        const float z = rnd(2) * 2.0f - 1.0f;
        for (int k = 0; k < 3; ++k) {
            const float a = 6.2831853f * (float(k) / 3.0f + rnd(3) * 0.2f);
            const glm::vec2 p = c + 0.5f * size * glm::vec2(std::cos(a), std::sin(a));
            m.positions.push_back({2.0f * p.x / w - 1.0f, 1.0f - 2.0f * p.y / h, z});
            m.normals.push_back({0, 0, 1});
            m.indices.push_back(uint32_t(m.indices.size()));
        }
    }
    s.meshes.push_back(std::move(m));
    Material mat;
    mat.doubleSided = true;
    s.materials.push_back(mat);
    s.instances.push_back(Instance{});
    return s;
}

void rasterSoup(benchmark::State& state, Isa isa) {
    if (!isaSupported(isa)) {
        state.SkipWithError("ISA not supported by this CPU");
        return;
    }
    const int w = 1920, h = 1080;
    const int count = int(state.range(0));
    const float size = float(state.range(1));
    const Scene scene = triangleSoup(count, size, w, h);
    RasterView view;
    view.width = w;
    view.height = h;
    view.perspective = false;
    RasterOptions o;
    o.isa = isa;
    o.threads = 1;
    const TransformedVertices tv = transformVertices(scene, view, 1);
    RasterStats stats;
    for (auto _ : state) {
        stats = RasterStats{};
        benchmark::DoNotOptimize(rasterize(scene, tv, view, o, stats).depth.row(0));
    }
    state.counters["tris/s"] =
        benchmark::Counter(double(count), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["px/s"] = benchmark::Counter(double(stats.pixelsCovered),
                                                benchmark::Counter::kIsIterationInvariantRate);
}

// Small (4 px) and large (200 px) triangles, one thread, per ISA.
void BM_RasterSmall(benchmark::State& s) { rasterSoup(s, Isa(s.range(2))); }
void BM_RasterLarge(benchmark::State& s) { rasterSoup(s, Isa(s.range(2))); }
BENCHMARK(BM_RasterSmall)
    ->ArgsProduct({{100000}, {4}, {0, 1, 2, 3, 4}})
    ->ArgNames({"tris", "px", "isa"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RasterLarge)
    ->ArgsProduct({{2000}, {200}, {0, 1, 2, 3, 4}})
    ->ArgNames({"tris", "px", "isa"})
    ->Unit(benchmark::kMillisecond);

// Whole passes at 1920x1080 on the benchmark scenes (2 threads, best ISA).
void passBench(benchmark::State& state, const char* passName) {
    const Scene scene = makeKnotScene(int(state.range(0)));
    RenderSettings rs;
    rs.width = 1920;
    rs.height = 1080;
    rs.threads = 2;
    rs.shadowMapSize = 2048;
    const Renderer r(rs);
    Frame f;  // rendered into again and again: no allocation after the first frame
    r.renderWithoutHistory(scene, FrameInput::still(scene), f);
    for (auto _ : state) {
        r.renderWithoutHistory(scene, FrameInput::still(scene), f);
        double ms = 0.0;
        for (const PassTime& p : f.stats.passes) {
            const std::string n = p.name;
            if (std::string(passName) == "gbuffer"
                    ? (n == "geometry" || n == "visibility" || n == "resolve")
                    : n == passName)
                ms += p.ms;
        }
        state.SetIterationTime(ms / 1000.0);
    }
    state.counters["tris"] = double(scene.triangleCount());
}
void BM_GBufferPass(benchmark::State& s) { passBench(s, "gbuffer"); }
void BM_ShadowPass(benchmark::State& s) { passBench(s, "shadow"); }
void BM_ShadingPass(benchmark::State& s) { passBench(s, "shading"); }
BENCHMARK(BM_GBufferPass)
    ->Arg(3700)
    ->Arg(121000)
    ->ArgName("tris")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShadowPass)
    ->Arg(3700)
    ->Arg(121000)
    ->ArgName("tris")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShadingPass)
    ->Arg(3700)
    ->ArgName("tris")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
