// Ray generation at 1920x1080 on the spheres scene's G-buffer (trace/ray_gen.h): rays/s per
// method (rays = pixels of the frame, background and rejected included; "traced/s" counts
// only the rays written with pdf > 0), on 1 and 2 threads, scalar and the best ISA.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "core/isa.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "trace/ray_gen.h"

using namespace ssrt;

namespace {

constexpr int kW = 1920, kH = 1080;

struct GBuffer {
    Frame frame;
    TraceCamera camera;
    GBuffer() {
        const Scene scene = makeBuiltinScene("spheres");
        RenderSettings rs;
        rs.width = kW;
        rs.height = kH;
        rs.threads = 2;
        rs.shadowMapSize = 512;
        frame = Renderer(rs).renderWithoutHistory(scene);
        camera.width = kW;
        camera.height = kH;
        camera.tanHalfY = std::tan(glm::radians(scene.camera.fovY) * 0.5f);
        camera.tanHalfX = camera.tanHalfY * (float(kW) / float(kH));
        const glm::mat3 viewToWorld = glm::mat3(glm::inverse(scene.camera.view()));
        std::copy_n(glm::value_ptr(viewToWorld), 9, camera.viewToWorld);
    }
    GBufferView g() const { return frame.gbuffer.view(); }
};

const GBuffer& gbuffer() {
    static const GBuffer g;
    return g;
}

// method: 0..4 an SsrMethod, 5 diffuse.
void benchRayGen(benchmark::State& state, int method, Isa isa, int threads) {
    if (!isaSupported(isa)) {
        state.SkipWithError("ISA not supported on this CPU");
        return;
    }
    const GBuffer& gb = gbuffer();
    RayBatch rays;
    RayGenStats stats;
    uint32_t sample = 0;
    for (auto _ : state) {
        stats = method < 5
                    ? generateSpecularRays(isa, SsrMethod(method), 0, sample++, gb.camera, gb.g(),
                                           rays, threads)
                    : generateDiffuseRays(isa, 0, sample++, gb.camera, gb.g(), rays, threads);
        benchmark::DoNotOptimize(rays.pdf.row(0));
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kW * kH);
    state.counters["traced/s"] =
        benchmark::Counter(double(stats.rays), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["surface"] = double(stats.pixels) / double(kW * kH);
}

[[maybe_unused]] const bool kRegistered = [] {
    const Isa best = supportedIsas().back();
    for (int method = 0; method <= 5; ++method) {
        const std::string name =
            method < 5 ? std::string(ssrMethodName(SsrMethod(method))) : std::string("diffuse");
        for (Isa isa : {Isa::Scalar, best}) {
            for (int threads : {1, 2}) {
                const std::string full = "RayGen/" + name + "/" + std::string(isaName(isa)) +
                                         "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(full.c_str(), benchRayGen, method, isa, threads)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
            }
            if (isa == best) break;
        }
    }
    return true;
}();

}  // namespace
