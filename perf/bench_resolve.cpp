// Pixels per second of the resolve passes on one core, scalar and each SIMD width the machine
// runs: the SSR resolve (Mip and 3x3 Reuse), the SSGI bounce and the composite, on a 640 x 360
// synthetic frame (random G-buffer, rays with pdf > 0 everywhere, 70% hits).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "core/isa.h"
#include "core/plane_view.h"
#include "core/rng.h"
#include "shading/composite.h"
#include "trace/color_pyramid.h"
#include "trace/ssgi.h"
#include "trace/ssr_resolve.h"

using namespace ssrt;

namespace {

constexpr int kW = 640, kH = 360;

PlaneF randomPlane(uint32_t dim, float lo, float hi) {
    PlaneF p(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            p.at(x, y) = lo + (hi - lo) * randomFloat(uint32_t(y * kW + x), 31, 0, dim);
    return p;
}

struct Scene {
    PlaneF viewZ = randomPlane(0, 2.0f, 6.0f);
    PlaneF normal[3] = {PlaneF(kW, kH, 0.0f), PlaneF(kW, kH, 0.0f), PlaneF(kW, kH, 1.0f)};
    PlaneF albedo[3] = {randomPlane(1, 0, 1), randomPlane(2, 0, 1), randomPlane(3, 0, 1)};
    PlaneF metallic = randomPlane(4, 0, 1), roughness = randomPlane(5, 0, 1);
    PlaneF shadow = randomPlane(6, 0, 1);
    PlaneF color[3] = {randomPlane(7, 0, 2), randomPlane(8, 0, 2), randomPlane(9, 0, 2)};
    PlaneF motion[2] = {randomPlane(10, -2, 2), randomPlane(11, -2, 2)};
    RayBatch rays;
    MarchResult march;
    ColorPyramid pyramid;
    DirectArgs light{};
    GBufferView g() const {
        return gbufferView("bench", kW, kH,
                           {{kGViewZ, &viewZ},
                            {kGNormalX, &normal[0]},
                            {kGNormalY, &normal[1]},
                            {kGNormalZ, &normal[2]},
                            {kGAlbedoR, &albedo[0]},
                            {kGAlbedoG, &albedo[1]},
                            {kGAlbedoB, &albedo[2]},
                            {kGMetallic, &metallic},
                            {kGRoughness, &roughness},
                            {kGMotionX, &motion[0]},
                            {kGMotionY, &motion[1]}});
    }
    Scene() {
        rays.ensureSize(kW, kH);
        march.ensureSize(kW, kH);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const uint32_t i = uint32_t(y * kW + x);
                const float dx = randomFloat(i, 32, 0, 0) - 0.5f,
                            dy = randomFloat(i, 32, 0, 1) - 0.5f;
                const float dz = 0.2f + randomFloat(i, 32, 0, 2);
                const float len = std::sqrt(dx * dx + dy * dy + dz * dz);
                rays.dx.at(x, y) = dx / len;
                rays.dy.at(x, y) = dy / len;
                rays.dz.at(x, y) = dz / len;
                rays.pdf.at(x, y) = 0.1f + randomFloat(i, 32, 0, 3);
                march.hit.at(x, y) = randomFloat(i, 32, 0, 4) < 0.7f ? 1.0f : 0.0f;
                march.hitX.at(x, y) = float(kW) * randomFloat(i, 32, 0, 5);
                march.hitY.at(x, y) = float(kH) * randomFloat(i, 32, 0, 6);
                march.hitZ.at(x, y) = 1.0f + randomFloat(i, 32, 0, 7);
            }
        const PlaneF* src[3] = {&color[0], &color[1], &color[2]};
        buildColorPyramid(src, pyramid, 1);
        light.toLight[1] = 1.0f;
        light.lightRadiance[0] = light.lightRadiance[1] = light.lightRadiance[2] = 3.0f;
        light.skyGradient = true;
        light.skyZenith[2] = light.skyHorizon[1] = light.skyGround[0] = 0.5f;
    }
};

Scene& scene() {
    static Scene s;
    return s;
}

void benchSsr(benchmark::State& state, Isa isa, SsrResolveMode mode) {
    if (!isaSupported(isa)) {
        state.SkipWithError("ISA not supported on this CPU");
        return;
    }
    Scene& s = scene();
    SsrResolveArgs in;
    in.camera.width = kW;
    in.camera.height = kH;
    in.g = s.g();
    for (int c = 0; c < 3; ++c) in.color[c] = viewOf(s.color[c], "color");
    in.pyramid = &s.pyramid;
    SsrResolveSettings settings;
    settings.mode = mode;
    SsrOutput out;
    for (auto _ : state) {
        resolveSsr(isa, settings, in, s.rays, s.march, out, 0, 1, 1);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kW * kH);
}

void benchSsgi(benchmark::State& state, Isa isa) {
    if (!isaSupported(isa)) {
        state.SkipWithError("ISA not supported on this CPU");
        return;
    }
    Scene& s = scene();
    SsgiArgs in;
    in.camera.width = kW;
    in.camera.height = kH;
    in.g = s.g();
    in.shadow = viewOf(s.shadow, "shadow");
    in.lighting = &s.light;
    PlaneF out[3];
    for (auto _ : state) {
        resolveSsgi(isa, in, s.rays, s.march, out, 0, 1, 1);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kW * kH);
}

void benchComposite(benchmark::State& state, Isa isa) {
    if (!isaSupported(isa)) {
        state.SkipWithError("ISA not supported on this CPU");
        return;
    }
    Scene& s = scene();
    PlaneF color[3], display[3];
    CompositeArgs in;
    for (int c = 0; c < 3; ++c) {
        in.direct[c] = in.envDiffuse[c] = in.envSpecular[c] = in.specWeight[c] =
            viewOf(s.color[c], "color");
        in.ssgi[c] = viewOf(s.albedo[c], "ssgi");
        in.ssrColor[c] = viewOf(s.albedo[c], "ssrColor");
        color[c] = PlaneF(kW, kH);
        display[c] = PlaneF(kW, kH);
        in.color[c] = outputOf(color[c], "color");
        in.display[c] = outputOf(display[c], "display");
    }
    in.g = s.g();
    in.ssrOpacity = viewOf(s.shadow, "ssrOpacity");
    for (auto _ : state) {
        composite(isa, in, 1);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * kW * kH);
}

[[maybe_unused]] const bool kRegistered = [] {
    for (Isa isa : kAllIsas) {
        if (!isaSupported(isa)) continue;
        const std::string n(isaName(isa));
        benchmark::RegisterBenchmark(("ssr_resolve_mip/" + n).c_str(), benchSsr, isa,
                                     SsrResolveMode::Mip)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("ssr_resolve_reuse/" + n).c_str(), benchSsr, isa,
                                     SsrResolveMode::Reuse)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("ssgi/" + n).c_str(), benchSsgi, isa)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("composite/" + n).c_str(), benchComposite, isa)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
