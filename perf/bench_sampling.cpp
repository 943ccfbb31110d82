// Samples per second for every sampler, scalar and each SIMD width the machine runs
// (items_per_second = directions per second on one core). The "_pdf" variants also
// evaluate the PDF of each sample, as a renderer that weights its samples must.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/isa.h"
#include "core/rng.h"
#include "shading/sampling_kernels.h"

using namespace ssrt;

namespace {

constexpr std::size_t kN = 4096;

struct Inputs {
    std::vector<float> wiX, wiY, wiZ, ax, ay, u1, u2, ox, oy, oz, pdf;
    Inputs() {
        for (auto* v : {&wiX, &wiY, &wiZ, &ax, &ay, &u1, &u2, &ox, &oy, &oz, &pdf}) v->resize(kN);
        for (std::size_t i = 0; i < kN; ++i) {
            // Views over the upper hemisphere (cosine-ish spread), roughness in [0.05, 1].
            const float ct = 0.05f + 0.95f * randomFloat(uint32_t(i), 7, 0, 0);
            const float phi = 6.2831853f * randomFloat(uint32_t(i), 7, 0, 1);
            const float st = std::sqrt(1.0f - ct * ct);
            wiX[i] = st * std::cos(phi);
            wiY[i] = st * std::sin(phi);
            wiZ[i] = ct;
            const float r = 0.2f + 0.8f * randomFloat(uint32_t(i), 7, 0, 2);
            ax[i] = ay[i] = r * r;
            u1[i] = randomFloat(uint32_t(i), 7, 1, 0);
            u2[i] = randomFloat(uint32_t(i), 7, 1, 1);
        }
    }
};

void benchSampler(benchmark::State& state, Isa isa, Sampler s, bool withPdf) {
    if (!isaSupported(isa)) {
        state.SkipWithError("ISA not supported on this CPU");
        return;
    }
    static Inputs in;
    const SampleBatch a{.wiX = in.wiX.data(),
                        .wiY = in.wiY.data(),
                        .wiZ = in.wiZ.data(),
                        .alphaX = in.ax.data(),
                        .alphaY = in.ay.data(),
                        .u1 = in.u1.data(),
                        .u2 = in.u2.data(),
                        .outX = in.ox.data(),
                        .outY = in.oy.data(),
                        .outZ = in.oz.data(),
                        .outPdf = withPdf ? in.pdf.data() : nullptr};
    for (auto _ : state) {
        sampleDirections(isa, s, a, kN);
        benchmark::DoNotOptimize(in.ox.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kN));
}

[[maybe_unused]] const bool kRegistered = [] {
    for (Sampler s : kAllSamplers)
        for (Isa isa : kAllIsas)
            for (bool withPdf : {false, true}) {
                if (!isaSupported(isa)) continue;
                const std::string name = "sample/" + std::string(samplerName(s)) +
                                         (withPdf ? "_pdf/" : "/") + std::string(isaName(isa));
                benchmark::RegisterBenchmark(name.c_str(), benchSampler, isa, s, withPdf);
            }
    return true;
}();

}  // namespace
