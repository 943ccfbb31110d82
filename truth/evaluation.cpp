#include "truth/evaluation.h"

#include <algorithm>
#include <chrono>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace ssrt {

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Median per pass name over the repeats, in the order of the first repeat's passes.
std::vector<PassTime> medianPasses(const std::vector<std::vector<PassTime>>& runs,
                                   double& frameMs) {
    std::vector<PassTime> out;
    std::vector<double> sums;
    for (const auto& run : runs) {
        double sum = 0.0;
        for (const PassTime& p : run) sum += p.ms;
        sums.push_back(sum);
    }
    frameMs = median(sums);
    for (const PassTime& p : runs.front()) {
        std::vector<double> ms;
        for (const auto& run : runs)
            for (const PassTime& q : run)
                if (q.name == p.name) ms.push_back(q.ms);
        out.push_back({p.name, median(ms)});
    }
    return out;
}

double passMs(const std::vector<PassTime>& passes, const std::string& name) {
    for (const PassTime& p : passes)
        if (p.name == name) return p.ms;
    return 0.0;
}

ImageError planesError(std::span<const PlaneF, 3> a, std::span<const PlaneF, 3> b) {
    const PlaneF* pa[3] = {&a[0], &a[1], &a[2]};
    const PlaneF* pb[3] = {&b[0], &b[1], &b[2]};
    return imageError(pa, pb);
}

}  // namespace

ErrorTable imageErrors(const Frame& frame, const ReferenceImage& ref) {
    ErrorTable t;
    t.color = planesError(frame.rgb(Res::Color), ref.color);
    // With both passes off the direct pass hands out no parts: the colour error alone.
    if (frame.direct.direct[0].empty()) return t;
    t.parts = true;
    const FrameParts parts = frameParts(frame);
    t.direct = planesError(parts.direct, ref.direct);
    t.specular = planesError(parts.specular, ref.specular);
    t.diffuse = planesError(parts.diffuse, ref.diffuse);
    return t;
}

ErrorTable referenceErrors(const ReferenceImage& image, const ReferenceImage& ref) {
    ErrorTable t;
    t.color = planesError(image.color, ref.color);
    t.parts = true;
    t.direct = planesError(image.direct, ref.direct);
    t.specular = planesError(image.specular, ref.specular);
    t.diffuse = planesError(image.diffuse, ref.diffuse);
    return t;
}

void EvaluationSettings::validate() const {
    if (repeats < 1 || repeats > 1000)
        throw std::invalid_argument("repeats must be between 1 and 1000");
    if (!(check.pixelTolerance > 0.0f) || !(check.pixelTolerance < 1e6f))
        throw std::invalid_argument("pixel tolerance must be finite and > 0");
    if (!(check.depthTolerance > 0.0f) || !(check.depthTolerance < 1.0f))
        throw std::invalid_argument("depth tolerance must be in (0, 1)");
}

namespace {

// The checked render, with `history` or without one (null), and everything measured from it.
// The pass times are the median over `runs`, the checked render's own joining them when
// `timeItToo` (the observer's time is in no pass).
Evaluation checkedRender(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                         const RenderSettings& settings, const ReferenceImage& reference,
                         const EvaluationSettings& es, std::vector<std::vector<PassTime>> runs,
                         bool timeItToo, FrameHistory* history, Frame& frame) {
    const Renderer renderer(settings);
    Evaluation ev;
    ev.ssr = settings.trace.ssr;
    ev.ssgi = settings.trace.ssgi;

    // Embree sees each sample's rays as they were marched; a pass that does not run this time
    // leaves no check planes of an earlier frame behind.
    for (Res id : {Res::SsrCheck, Res::SsgiCheck})
        for (int ch = 0; ch < kCheckChannels; ++ch) frame.outputs.plane(id, ch) = PlaneF();
    RayCheckSettings check = es.check;
    const PlaneF* viewZ = nullptr;
    const TraceObserver observer = [&](TracePass pass, int sample, const RayBatch& rays,
                                       const MarchResult& march, const HalfFrame* half) {
        const bool ssr = pass == TracePass::Ssr;
        PlaneF* planes = es.planes && sample == 0
                             ? frame.outputs.planes(ssr ? Res::SsrCheck : Res::SsgiCheck)
                             : nullptr;
        // The G-buffer is complete before the trace passes run; the frame's camera too.
        if (!viewZ) {
            viewZ = &frame.gbuffer.viewZ;
            check.maxDistance =
                marchLengths(settings.trace.march, frame.camera.sceneDiagonal).maxDistance;
        }
        const RayCheckTable t = checkRays(embree, frame.camera, *viewZ, rays, march, check, planes,
                                          settings.threads, half);
        (ssr ? ev.ssrCheck : ev.ssgiCheck).add(t);
    };
    if (history) renderer.render(scene, input, *history, frame, &observer);
    else renderer.renderWithoutHistory(scene, input, frame, &observer);
    ev.stats = frame.stats;
    ev.ssrCheck.finish();
    ev.ssgiCheck.finish();
    if (timeItToo) runs.push_back(frame.stats.passes);
    ev.passes = medianPasses(runs, ev.frameMs);

    const double marchMs = passMs(ev.passes, "ssr march") + passMs(ev.passes, "ssgi march");
    const double rays = double(ev.stats.ssr.march.rays + ev.stats.ssgi.march.rays);
    if (marchMs > 0.0) ev.marchMraysPerSecond = rays * 1e-3 / marchMs;
    const double embreeSeconds = ev.ssrCheck.embreeSeconds + ev.ssgiCheck.embreeSeconds;
    const double checked = double(ev.ssrCheck.rays + ev.ssgiCheck.rays);
    if (embreeSeconds > 0.0) ev.embreeMraysPerSecond = checked * 1e-6 / embreeSeconds;

    ev.error = imageErrors(frame, reference);
    return ev;
}

}  // namespace

Evaluation evaluate(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                    const RenderSettings& settings, const ReferenceImage& reference,
                    const EvaluationSettings& es, Frame& frame) {
    es.validate();
    const Renderer renderer(settings);
    // Timed renders: nothing else runs inside them.
    std::vector<std::vector<PassTime>> runs;
    for (int i = 0; i < es.repeats; ++i) {
        renderer.renderWithoutHistory(scene, input, frame);
        runs.push_back(frame.stats.passes);
    }
    return checkedRender(embree, scene, input, settings, reference, es, std::move(runs), false,
                         nullptr, frame);
}

Evaluation evaluateSequenceFrame(const EmbreeScene& embree, const Scene& scene,
                                 const FrameInput& input, const RenderSettings& settings,
                                 const ReferenceImage& reference, const EvaluationSettings& es,
                                 const std::vector<std::vector<PassTime>>& earlierRuns,
                                 FrameHistory& history, Frame& frame) {
    es.validate();
    return checkedRender(embree, scene, input, settings, reference, es, earlierRuns, true, &history,
                         frame);
}

Evaluation evaluateEmbreeMethod(const EmbreeScene& embree, const Scene& scene,
                                const FrameInput& input, const RenderSettings& settings,
                                const ReferenceSettings& world, const ReferenceImage& reference,
                                const EvaluationSettings& es) {
    es.validate();
    world.validate();
    // What stays of the frame: raster, G-buffer, direct light (no trace, no denoiser).
    RenderSettings direct = settings;
    direct.trace.ssr = direct.trace.ssgi = false;
    const Renderer directRenderer(direct);
    Frame frame;
    std::vector<std::vector<PassTime>> runs;
    for (int i = 0; i < es.repeats; ++i) {
        directRenderer.renderWithoutHistory(scene, input, frame);
        runs.push_back(frame.stats.passes);
    }
    Evaluation ev;
    ev.passes = medianPasses(runs, ev.frameMs);
    // The frame Embree traces from (renderReference reads its G-buffer, direct parts and
    // samplers' inputs; both trace passes on, as it requires), untimed.
    RenderSettings traced = settings;
    traced.trace.ssr = traced.trace.ssgi = true;
    const Renderer renderer(traced);
    renderer.renderWithoutHistory(scene, input, frame);
    ev.stats = frame.stats;
    std::vector<double> ms;
    ReferenceImage image;
    for (int i = 0; i < es.repeats; ++i) {
        const auto start = std::chrono::steady_clock::now();
        image = renderReference(embree, renderer, frame, world);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
    }
    const double traceMs = median(ms);
    ev.passes.push_back({kEmbreeTracePass, traceMs});
    ev.frameMs += traceMs;
    ev.error.color = planesError(image.color, reference.color);
    ev.error.parts = true;
    ev.error.direct = planesError(image.direct, reference.direct);
    ev.error.specular = planesError(image.specular, reference.specular);
    ev.error.diffuse = planesError(image.diffuse, reference.diffuse);
    return ev;
}

}  // namespace ssrt
