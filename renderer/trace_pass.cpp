#include "renderer/trace_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/tiles.h"
#include "shading/composite.h"
#include "trace/hit_stats.h"
#include "trace/ssgi.h"

namespace ssrt {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

PlaneF& planeOf(Frame& f, std::string_view name) {
    for (NamedPlane& p : f.planes)
        if (p.name == name) return p.plane;
    throw std::logic_error("frame has no plane '" + std::string(name) + "'");
}

// The frame's SSR colour and opacity planes, lent to the resolve's output while it runs.
const char* const kSsrOutputNames[4] = {"ssr.R", "ssr.G", "ssr.B", "ssrOpacity"};

void swapSsrOutput(Frame& frame, SsrOutput& out) {
    for (int c = 0; c < 3; ++c) std::swap(out.color[c], planeOf(frame, kSsrOutputNames[c]));
    std::swap(out.opacity, planeOf(frame, kSsrOutputNames[3]));
}

}  // namespace

std::vector<const char*> tracePlaneNames(const TraceSettings& s) {
    std::vector<const char*> names;
    if (s.ssr)
        names.insert(names.end(), {"ssr.R", "ssr.G", "ssr.B", "ssrOpacity", "ssrHit",
                                   "ssrHitDistance", "ssrSteps"});
    if (s.ssgi) names.insert(names.end(), {"ssgi.R", "ssgi.G", "ssgi.B", "ssgiHit", "ssgiSteps"});
    return names;
}

void runTracePasses(const RenderSettings& settings, Isa isa, const TraceCamera& camera,
                    const DirectArgs& direct, Frame& frame, const TraceObserver* observer) {
    const TraceSettings& ts = settings.trace;
    const int threads = settings.threads;
    const int w = camera.width, h = camera.height;
    auto pass = [&](const char* name, Clock::time_point t0) {
        frame.stats.passes.push_back({name, msSince(t0)});
    };
    Frame::Scratch& sc = frame.scratch;
    const PlaneF& viewZ = frame.plane("viewZ");
    const PlaneF* normal[3] = {&frame.plane("normal.X"), &frame.plane("normal.Y"),
                               &frame.plane("normal.Z")};
    const PlaneF* albedo[3] = {&frame.plane("albedo.R"), &frame.plane("albedo.G"),
                               &frame.plane("albedo.B")};
    const PlaneF* color[3] = {&frame.plane("color.R"), &frame.plane("color.G"),
                              &frame.plane("color.B")};
    const PlaneF* parts = sc.directParts;  // direct, emission, envDiffuse, envSpecular, specWeight

    // Hi-Z pyramid of the depth buffer, shared by both passes.
    const HiZPyramid* hiz = nullptr;
    if (ts.marcher == Marcher::HiZ) {
        const auto t0 = Clock::now();
        buildHiZ(viewZ, sc.hiz, threads);
        hiz = &sc.hiz;
        pass("hi-z", t0);
    }
    const MarchGBuffer mg{&viewZ, {normal[0], normal[1], normal[2]}};
    // (albedo and metallic: the diffuse colour the composite multiplies SSGI by)
    const RayGenGBuffer rg{&viewZ,
                           {normal[0], normal[1], normal[2]},
                           &frame.plane("roughness"),
                           {albedo[0], albedo[1], albedo[2]},
                           &frame.plane("metallic")};
    double pyramidMs = 0.0;
    auto timed = [](double& ms, auto&& fn) {
        const auto t0 = Clock::now();
        fn();
        ms += msSince(t0);
    };
    const auto march = [&](TraceStats& st, uint32_t sample) {
        MarchSettings m = ts.march;
        m.frame = settings.frame;
        m.sample = sample;
        st.march.add(marchRays(isa, ts.marcher, m, camera, mg, hiz, sc.rays, sc.march, threads));
    };

    SsrOutput& ssrOut = sc.ssr;
    if (ts.ssr) {
        // The hit radiance: this frame's direct light, or last frame's composite (when there is
        // one) through the motion vectors.
        const bool reproject = ts.resolve.radiance == HitRadiance::Reprojected && sc.hasPrevious &&
                               sc.previousColor[0].width() == w &&
                               sc.previousColor[0].height() == h;
        SsrResolveSettings rs = ts.resolve;
        if (!reproject) rs.radiance = HitRadiance::Current;
        SsrResolveInputs in;
        in.camera = camera;
        in.viewZ = &viewZ;
        for (int c = 0; c < 3; ++c) {
            in.normal[c] = normal[c];
            in.color[c] = color[c];
            in.prevColor[c] = reproject ? &sc.previousColor[c] : nullptr;
        }
        in.motion[0] = &frame.plane("motion.X");
        in.motion[1] = &frame.plane("motion.Y");
        in.roughness = &frame.plane("roughness");
        in.radianceScale = 1.0f / settings.exposure;
        if (rs.mode == SsrResolveMode::Mip) {
            timed(pyramidMs, [&] {
                const PlaneF* src[3] = {in.color[0], in.color[1], in.color[2]};
                if (reproject)
                    for (int c = 0; c < 3; ++c) src[c] = in.prevColor[c];
                buildColorPyramid(src, sc.colorPyramid, threads);
            });
            in.pyramid = &sc.colorPyramid;
        }
        // The output planes are the frame's own, lent to the resolve.
        swapSsrOutput(frame, ssrOut);
        // Per-pixel hit fraction, mean steps and mean hit distance (trace/hit_stats.h).
        const HitStatsPlanes hp{&planeOf(frame, "ssrHit"), &planeOf(frame, "ssrSteps"),
                                &planeOf(frame, "ssrHitDistance")};
        TraceStats& st = frame.stats.ssr;
        st.ran = true;
        st.spp = ts.ssrSpp;
        double genMs = 0.0, marchMs = 0.0, resolveMs2 = pyramidMs;
        const float maxRoughness =
            ts.traceHidden ? std::numeric_limits<float>::infinity() : rs.roughnessFadeEnd;
        for (int s = 0; s < ts.ssrSpp; ++s) {
            timed(genMs, [&] {
                st.rays.add(generateSpecularRays(isa, ts.ssrMethod, settings.frame, uint32_t(s),
                                                 camera, rg, sc.rays, threads, maxRoughness));
            });
            timed(marchMs, [&] { march(st, uint32_t(s)); });
            if (observer && *observer) (*observer)(TracePass::Ssr, s, sc.rays, sc.march);
            timed(resolveMs2, [&] {
                resolveSsr(isa, rs, in, sc.rays, sc.march, ssrOut, s, ts.ssrSpp, threads);
                accumulateHitStats(isa, camera, sc.rays, sc.march, hp, s, ts.ssrSpp, threads);
            });
        }
        frame.stats.passes.push_back({"ssr rays", genMs});
        frame.stats.passes.push_back({"ssr march", marchMs});
        frame.stats.passes.push_back({"ssr resolve", resolveMs2});
    }

    PlaneF* ssgi[3] = {};
    if (ts.ssgi) {
        SsgiInputs in;
        in.camera = camera;
        in.viewZ = &viewZ;
        for (int c = 0; c < 3; ++c) {
            in.normal[c] = normal[c];
            in.albedo[c] = albedo[c];
            in.emission[c] = direct.anyEmissive ? &parts[3 + c] : nullptr;
            // The direct pass's hit light where it wrote one (then the G-buffer planes above
            // are not read), else SSGI computes it from them.
            in.hitLight[c] = direct.hitLight[0] ? &sc.hitLight[c] : nullptr;
            ssgi[c] = &planeOf(frame, c == 0 ? "ssgi.R" : c == 1 ? "ssgi.G" : "ssgi.B");
        }
        in.metallic = &frame.plane("metallic");
        in.shadow = &frame.plane("shadow");
        in.lighting = &direct;
        const HitStatsPlanes hp{&planeOf(frame, "ssgiHit"), &planeOf(frame, "ssgiSteps"), nullptr};
        TraceStats& st = frame.stats.ssgi;
        st.ran = true;
        st.spp = ts.ssgiSpp;
        double genMs = 0.0, marchMs = 0.0, resolveMs2 = 0.0;
        PlaneF out[3];
        for (int c = 0; c < 3; ++c) std::swap(out[c], *ssgi[c]);
        for (int s = 0; s < ts.ssgiSpp; ++s) {
            timed(genMs, [&] {
                st.rays.add(generateDiffuseRays(
                    isa, settings.frame, uint32_t(s), camera, rg, sc.rays, threads,
                    ts.traceHidden ? DiffuseCut::None : DiffuseCut::NoDiffuseColour));
            });
            timed(marchMs, [&] { march(st, uint32_t(s)); });
            if (observer && *observer) (*observer)(TracePass::Ssgi, s, sc.rays, sc.march);
            timed(resolveMs2, [&] {
                resolveSsgi(isa, in, sc.rays, sc.march, out, s, ts.ssgiSpp, threads);
                accumulateHitStats(isa, camera, sc.rays, sc.march, hp, s, ts.ssgiSpp, threads);
            });
        }
        for (int c = 0; c < 3; ++c) std::swap(out[c], *ssgi[c]);
        frame.stats.passes.push_back({"ssgi rays", genMs});
        frame.stats.passes.push_back({"ssgi march", marchMs});
        frame.stats.passes.push_back({"ssgi resolve", resolveMs2});
    }

    // Composite: direct + diffuse (SSGI or the sky's irradiance) + specular (SSR over the
    // environment), tone mapped; replaces the direct pass's color and display.
    const auto t0 = Clock::now();
    CompositeInputs ci;
    for (int c = 0; c < 3; ++c) {
        ci.direct[c] = &parts[c];
        ci.emission[c] = direct.anyEmissive ? &parts[3 + c] : nullptr;
        ci.envDiffuse[c] = &parts[6 + c];
        ci.envSpecular[c] = &parts[9 + c];
        ci.specWeight[c] = &parts[12 + c];
        if (ts.ssgi) {
            ci.ssgi[c] = ssgi[c];
            ci.albedo[c] = albedo[c];
        }
        if (ts.ssr) ci.ssrColor[c] = &ssrOut.color[c];
    }
    if (ts.ssgi) {
        ci.viewZ = &viewZ;
        ci.metallic = &frame.plane("metallic");
    }
    if (ts.ssr) ci.ssrOpacity = &ssrOut.opacity;
    ci.exposure = settings.exposure;
    PlaneF outColor[3], outDisplay[3];
    const char* colorNames[3] = {"color.R", "color.G", "color.B"};
    const char* displayNames[3] = {"display.R", "display.G", "display.B"};
    for (int c = 0; c < 3; ++c) {
        std::swap(outColor[c], planeOf(frame, colorNames[c]));
        std::swap(outDisplay[c], planeOf(frame, displayNames[c]));
    }
    composite(isa, ci, outColor, outDisplay, threads);
    for (int c = 0; c < 3; ++c) {
        std::swap(outColor[c], planeOf(frame, colorNames[c]));
        std::swap(outDisplay[c], planeOf(frame, displayNames[c]));
    }
    if (ts.ssr) {
        swapSsrOutput(frame, ssrOut);
    }
    pass("composite", t0);

    // Last frame's colour for reprojected hits in the next frame of a sequence.
    if (ts.ssr && ts.resolve.radiance == HitRadiance::Reprojected) {
        for (int c = 0; c < 3; ++c) {
            const PlaneF& src = frame.plane(colorNames[c]);
            PlaneF& dst = sc.previousColor[c];
            dst.ensureSize(w, h);  // kept across frames: no allocation once sized
            for (int y = 0; y < h; ++y) std::copy_n(src.row(y), w, dst.row(y));
        }
        sc.hasPrevious = true;
    }
}

}  // namespace ssrt
