// The denoiser on synthetic planes, where the right answer is known: a constant stays
// constant, a still camera averages its frames, a cut forgets, a NaN never enters the
// history, a revealed background restarts without a ghost, every input stays finite, and
// every ISA and thread count gives the same bits.
#include "denoise/denoise.h"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/pixel_formats.h"
#include "core/rng.h"
#include "denoise/denoise_fields.h"
#include "thread_counts.h"

using namespace ssrt;

namespace {

// A frame of guides and signals: by default a wall facing the camera at depth 2, grey,
// roughness 0.3, still (motion 0).
struct Synthetic {
    int w, h;
    TraceCamera camera;
    PlaneF viewZ, normal[3], roughness, albedo[3], metallic, motion[2];
    PlaneF diffuse[3], diffuseHit, ssr[3], opacity, env[3], specHit;

    Synthetic(int width, int height) : w(width), h(height) {
        camera.width = w;
        camera.height = h;
        camera.tanHalfY = 0.5f;
        camera.tanHalfX = 0.5f * float(w) / float(h);
        camera.sceneDiagonal = 10.0f;
        for (PlaneF* p : all()) *p = PlaneF(w, h, 0.0f);
        viewZ.fill(2.0f);
        normal[2].fill(1.0f);  // toward the camera (it looks down -z, view = world)
        roughness.fill(0.3f);
        for (PlaneF& a : albedo) a.fill(0.8f);
        for (PlaneF& d : diffuse) d.fill(0.5f);
        diffuseHit.fill(1.0f);
        for (PlaneF& s : ssr) s.fill(0.25f);
        opacity.fill(1.0f);
        for (PlaneF& e : env) e.fill(0.1f);
        specHit.fill(1.5f);
    }
    std::vector<PlaneF*> all() {
        return {&viewZ,      &normal[0],  &normal[1],  &normal[2], &roughness, &albedo[0],
                &albedo[1],  &albedo[2],  &metallic,   &motion[0], &motion[1], &diffuse[0],
                &diffuse[1], &diffuse[2], &diffuseHit, &ssr[0],    &ssr[1],    &ssr[2],
                &opacity,    &env[0],     &env[1],     &env[2],    &specHit};
    }
    DenoiseCall inputs(uint32_t frame) const {
        DenoiseCall in;
        in.camera = camera;
        in.frameIndex = frame;
        in.g = gbufferView("the test's guides", w, h,
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
        // (a view keeps its name as a string_view: literals)
        const char* const diffuseNames[3] = {"diffuse.R", "diffuse.G", "diffuse.B"};
        const char* const ssrNames[3] = {"ssr.R", "ssr.G", "ssr.B"};
        const char* const envNames[3] = {"envSpecular.R", "envSpecular.G", "envSpecular.B"};
        for (int i = 0; i < 3; ++i) {
            in.diffuse[i] = viewOf(diffuse[i], diffuseNames[i]);
            in.ssr[i] = viewOf(ssr[i], ssrNames[i]);
            in.envSpecular[i] = viewOf(env[i], envNames[i]);
        }
        in.diffuseHitDistance = viewOf(diffuseHit, "diffuseHitDistance");
        in.ssrOpacity = viewOf(opacity, "ssrOpacity");
        in.specularHitDistance = viewOf(specHit, "specularHitDistance");
        in.specularMaxRoughness = 0.7f;
        return in;
    }
};

// The planes the denoiser writes (a frame's are its outputs: renderer/plane_store.h).
struct Outputs {
    PlaneF diffuse[3], specular[3], diffuseFrames, specularFrames;

    // `in`, writing into these (sized to its camera) for the signals it has, history lengths
    // with them.
    DenoiseCall into(DenoiseCall in) {
        const int w = in.camera.width, h = in.camera.height;
        const auto out = [&](PlaneF& p, const char* name) {
            p.ensureSize(w, h);
            return outputOf(p, name);
        };
        const char* const names[2][3] = {
            {"denoisedDiffuse.R", "denoisedDiffuse.G", "denoisedDiffuse.B"},
            {"denoisedSpecular.R", "denoisedSpecular.G", "denoisedSpecular.B"}};
        if (in.hasDiffuse()) {
            for (int c = 0; c < 3; ++c) in.denoisedDiffuse[c] = out(diffuse[c], names[0][c]);
            in.diffuseFrames = out(diffuseFrames, "diffuseFrames");
        }
        if (in.hasSpecular()) {
            for (int c = 0; c < 3; ++c) in.denoisedSpecular[c] = out(specular[c], names[1][c]);
            in.specularFrames = out(specularFrames, "specularFrames");
        }
        return in;
    }
};

// Runs one frame.
struct Denoiser {
    DenoiseSettings settings;
    DenoiseHistory history;
    DenoiseScratch scratch;
    Outputs out;
    Isa isa = defaultIsa();
    int threads = 2;

    void run(const Synthetic& s, uint32_t frame, bool reset = false) {
        run(s.inputs(frame), reset);
    }
    void run(const DenoiseCall& in, bool reset = false) {
        denoise(isa, settings, out.into(in), &history, reset, scratch, threads);
    }
};

// Per-pixel noise in [0.5, 1.5) for frame f, channel c.
float noise(int x, int y, uint32_t f, uint32_t c) {
    return 0.5f + randomFloat(uint32_t(y * 1000 + x), f, 7, c);
}

// (The denoiser's f16 planes through the library's decoder.)
bool allFinite(const PlaneU16& p) {
    for (int y = 0; y < p.height(); ++y)
        for (int x = 0; x < p.width(); ++x)
            if (!std::isfinite(decodeF16(p.at(x, y)))) return false;
    return true;
}

bool allFinite(const PlaneU64& p) {
    for (int c = 0; c < 4; ++c)
        if (!allFinite(f16x4Channel(p, c))) return false;
    return true;
}

bool allFinite(const PlaneF& p) {
    for (int y = 0; y < p.height(); ++y)
        for (int x = 0; x < p.width(); ++x)
            if (!std::isfinite(p.at(x, y))) return false;
    return true;
}

uint64_t outputHash(const Denoiser& d) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (int c = 0; c < 3; ++c) {
        h = hashPlane(d.out.diffuse[c], h);
        h = hashPlane(d.out.specular[c], h);
        h = hashPlane(f16x4Channel(d.history.diffuse, c), h);
        h = hashPlane(f16x4Channel(d.history.specular, c), h);
    }
    h = hashPlane(d.out.diffuseFrames, h);
    return hashPlane(d.out.specularFrames, h);
}

// The default settings with NRD's pre-blur (the default preset has none), so that every pass
// runs, the blur's skip of older pixels included.
DenoiseSettings everyPass() {
    DenoiseSettings s;
    s.diffusePrepassRadius = 30.0f;
    s.specularPrepassRadius = 50.0f;
    return s;
}

// Settings that keep only the temporal accumulation: no spatial radius, no history fix, no
// fast-history clamp.
DenoiseSettings accumulationOnly() {
    DenoiseSettings s;
    s.diffusePrepassRadius = s.specularPrepassRadius = 0.0f;
    s.minBlurRadius = s.maxBlurRadius = 0.0f;
    s.historyFixFrames = 0;
    s.maxFastAccumulatedFrames = s.maxAccumulatedFrames;
    return s;
}

}  // namespace

TEST_CASE("denoise: a constant signal stays constant through every pass, frame after frame") {
    Synthetic s(96, 64);
    Denoiser d;
    d.settings = everyPass();
    for (uint32_t f = 0; f < 6; ++f) {
        CAPTURE(f);
        d.run(s, f);
        double worstDiffuse = 0.0, worstSpecular = 0.0;
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) {
                worstDiffuse =
                    std::max(worstDiffuse, std::abs(d.out.diffuse[1].at(x, y) - 0.5) / 0.5);
                worstSpecular =
                    std::max(worstSpecular, std::abs(d.out.specular[0].at(x, y) - 0.25) / 0.25);
            }
        CHECK(worstDiffuse < 1e-5);
        CHECK(worstSpecular < 1e-5);
        CHECK(d.out.diffuseFrames.at(40, 30) == float(f));
    }
}

TEST_CASE("denoise: a history keeps only its frame's signals, and one it lacks starts afresh") {
    Synthetic s(48, 32);
    Denoiser d;
    // Both signals for three frames, then the diffuse alone (as when SSR is turned off).
    for (uint32_t f = 0; f < 3; ++f) d.run(s, f);
    REQUIRE(d.out.specularFrames.at(20, 10) > 1.0f);
    DenoiseCall diffuseOnly = s.inputs(3);
    for (auto& p : diffuseOnly.ssr) p = {};
    d.run(diffuseOnly);
    CHECK(d.history.hasSignal(false));
    CHECK_FALSE(d.history.hasSignal(true));
    CHECK(d.history.specular.empty());
    CHECK(d.history.guide.roughness.empty());  // it guides the specular alone
    CHECK(d.scratch.frames[1].empty());
    CHECK(d.out.diffuseFrames.at(20, 10) == 3.0f);
    // The specular comes back: the diffuse goes on, the specular has no frame behind it,
    // whatever its planes, sized anew, hold (freed planes of the scene's roughness, which the
    // allocator is likely to hand back to them, would pass for a history: seen to fail so).
    {
        std::vector<PlaneF> stale;
        for (int i = 0; i < 40; ++i) stale.emplace_back(s.w, s.h, 0.3f);
    }
    d.run(s, 4);
    CHECK(d.out.diffuseFrames.at(20, 10) == 4.0f);
    CHECK(d.out.specularFrames.at(20, 10) == 0.0f);
    CHECK(d.history.hasSignal(true));
}

TEST_CASE(
    "denoise: a still camera's accumulation is the mean of its frames, then a 31-frame window") {
    Synthetic s(64, 48);
    Denoiser d;
    d.settings = accumulationOnly();
    std::vector<double> sum(std::size_t(s.w * s.h), 0.0);
    std::vector<float> previous(sum.size(), 0.0f);
    // The signal and the history are kept in f16 (denoise/denoise.h): each frame blends the
    // f16 of its sample into the f16 of the last frame's result, and its result passes through
    // an f16 plane (the ping-pong) before the output.
    const auto f16 = [](double v) { return double(decodeF16(encodeF16(float(v)))); };
    for (uint32_t f = 0; f <= 33; ++f) {
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) s.diffuse[0].at(x, y) = noise(x, y, f, 0);
        d.run(s, f);
        double worst = 0.0, worstMean = 0.0;
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) {
                const std::size_t i = std::size_t(y * s.w + x);
                const double v = s.diffuse[0].at(x, y);
                sum[i] += v;
                // Up to frame 30 (30 frames of history): each frame weighs 1 / (f + 1), the
                // plain mean; then 1/31 against the history.
                const double weight = f <= 30 ? 1.0 / double(f + 1) : 1.0 / 31.0;
                const double history = f16(previous[i]);
                const double expected = f16(history + (f16(v) - history) * weight);
                const float got = d.out.diffuse[0].at(x, y);
                worst = std::max(worst, std::abs(got - expected) / expected);
                // Against the exact mean: within a few of f16's relative steps (2^-11), the
                // roundings of up to 30 frames adding up (measured: at most 6).
                if (f <= 30)
                    worstMean = std::max(worstMean, std::abs(got - sum[i] / double(f + 1)) /
                                                        (sum[i] / double(f + 1)));
                previous[i] = got;
            }
        CAPTURE(f);
        CHECK(worst < 2e-5);
        CHECK(worstMean < 8.0 / 2048.0);
    }
    CHECK(d.out.diffuseFrames.at(10, 10) == 30.0f);
}

TEST_CASE("denoise: pixels with a long history skip the blur, younger ones keep both passes") {
    Synthetic s(64, 48);
    Denoiser both, skip;
    both.settings.blurMaxFrames = kMaxDenoiseFrames + 1;
    skip.settings.blurMaxFrames = 3;
    for (uint32_t f = 0; f < 5; ++f) {
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) s.diffuse[0].at(x, y) = noise(x, y, f, 0);
        both.run(s, f);
        skip.run(s, f);
        CAPTURE(f);
        // Frame f has f frames of history: the blur is skipped from frame 3 on.
        if (f < 3) CHECK(outputHash(both) == outputHash(skip));
        else CHECK(outputHash(both) != outputHash(skip));
    }
}

// The relative spread of a plane's values (their standard deviation over their mean): what a
// blur lowers.
double relativeSpread(const PlaneF& p) {
    double m1 = 0.0, m2 = 0.0;
    const double n = double(p.width()) * double(p.height());
    for (int y = 0; y < p.height(); ++y)
        for (int x = 0; x < p.width(); ++x) {
            m1 += p.at(x, y);
            m2 += double(p.at(x, y)) * p.at(x, y);
        }
    m1 /= n;
    return std::sqrt(std::max(0.0, m2 / n - m1 * m1)) / m1;
}

TEST_CASE("denoise: a long and steady history skips the post-blur, a changed signal does not") {
    // A pattern that stays put for 8 frames, then jumps 20-fold (a light switched on): the
    // fast history (2 frames) runs ahead of the slow one, so the pixels are not steady.
    Synthetic s(64, 48);
    Denoiser keep, skip;
    for (Denoiser* d : {&keep, &skip}) {
        d->settings.blurMaxFrames = 3;
        d->settings.maxFastAccumulatedFrames = 2;
    }
    skip.settings.postBlurMaxFrames = 5;
    for (uint32_t f = 0; f < 9; ++f) {
        const float scale = f < 8 ? 1.0f : 20.0f;
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x)
                for (PlaneF& c : s.diffuse) c.at(x, y) = scale * noise(x, y, 0, 0);
        keep.run(s, f);
        skip.run(s, f);
        CAPTURE(f);
        const double kept = relativeSpread(keep.out.diffuse[0]);
        const double skipped = relativeSpread(skip.out.diffuse[0]);
        if (f < 5) {
            CHECK(outputHash(keep) == outputHash(skip));
        } else if (f < 8) {
            // Steady: the new frames come back unblurred into the skipping history (measured:
            // 1.8-4.2x the spread), where they are steady.
            CHECK(skipped > 1.5 * kept);
        } else {
            // Changed: post-blurred again (measured 2.0x; 4.3x with the steady test left out).
            CHECK(skipped < 3.0 * kept);
        }
    }
}

TEST_CASE("denoise: a frame without history skips the temporal pass, to the same bits") {
    // Noise on two surfaces (an edge for the history fix and the blurs to stop at), a few
    // fireflies for the fast history's clamp.
    Synthetic s(64, 48);
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) {
            if (x >= 40) s.viewZ.at(x, y) = 5.0f;
            const float spike = (x * 7 + y * 3) % 53 == 0 ? 40.0f : 1.0f;
            for (int c = 0; c < 3; ++c) {
                s.diffuse[c].at(x, y) = noise(x, y, 3, uint32_t(c)) * spike;
                s.ssr[c].at(x, y) = 0.5f * noise(x, y, 3, uint32_t(c + 3));
            }
            s.diffuseHit.at(x, y) = noise(x, y, 3, 6);
            s.specHit.at(x, y) = noise(x, y, 3, 7);
        }
    const auto timed = [](const std::vector<DenoisePassTime>& times, const char* name) {
        for (const DenoisePassTime& t : times)
            if (t.name == name) return true;
        return false;
    };
    for (const DenoiseSettings& settings : {DenoiseSettings(), everyPass()}) {
        DenoiseCall in = s.inputs(5);
        DenoiseScratch scratch[2];
        Outputs out[2];
        std::vector<DenoisePassTime> times[2];
        for (int k = 0; k < 2; ++k) {
            in.temporal = k == 0;
            denoise(defaultIsa(), settings, out[k].into(in), nullptr, false, scratch[k], 2,
                    &times[k]);
        }
        CHECK(timed(times[0], "denoise temporal"));
        CHECK_FALSE(timed(times[1], "denoise temporal"));
        for (int c = 0; c < 3; ++c) {
            CHECK(hashPlane(out[0].diffuse[c]) == hashPlane(out[1].diffuse[c]));
            CHECK(hashPlane(out[0].specular[c]) == hashPlane(out[1].specular[c]));
        }
        CHECK(hashPlane(out[0].diffuseFrames) == hashPlane(out[1].diffuseFrames));
        CHECK(hashPlane(out[0].specularFrames) == hashPlane(out[1].specularFrames));
    }
    // A history to read or to keep needs the pass.
    DenoiseCall in = s.inputs(5);
    in.temporal = false;
    DenoiseHistory history;
    DenoiseScratch scratch;
    Outputs out;
    CHECK_THROWS_AS(
        denoise(defaultIsa(), DenoiseSettings(), out.into(in), &history, false, scratch, 2),
        std::logic_error);
}

TEST_CASE("denoise: a missing or mis-sized plane is an error naming it") {
    Synthetic s(64, 48);
    Denoiser d;
    const auto message = [&](const DenoiseCall& in) {
        try {
            d.run(in);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    DenoiseCall in = s.inputs(0);
    in.specularHitDistance = {};
    CHECK(message(in) == "denoise: specularHitDistance is missing");
    const PlaneF small(32, 48, 1.0f);
    in = s.inputs(0);
    in.diffuse[1] = viewOf(small, "diffuse.G");
    CHECK(message(in) == "denoise: diffuse.G is 32x48, not 64x48");
    // A guide only the missing signal reads is not needed.
    in = s.inputs(0);
    for (auto& p : in.ssr) p = {};
    in.g.roughness = nullptr;
    CHECK(message(in) == "no error");
    in.g.motion[1] = nullptr;
    CHECK(message(in) == "denoise: motion.Y is missing");
    // Where it writes is the caller's, checked as what it reads.
    DenoiseCall unwritable = d.out.into(s.inputs(0));
    unwritable.denoisedSpecular[1] = {};
    CHECK_THROWS_WITH_AS(
        denoise(d.isa, d.settings, unwritable, &d.history, false, d.scratch, d.threads),
        "denoise: denoisedSpecular is missing", std::invalid_argument);
}

TEST_CASE("denoise: a camera cut gives the frame a fresh history, bit for bit") {
    Synthetic s(64, 48);
    Denoiser seq, fresh;
    for (uint32_t f = 0; f < 4; ++f) {
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) s.diffuse[0].at(x, y) = noise(x, y, f, 0);
        seq.run(s, f);
    }
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) s.diffuse[0].at(x, y) = noise(x, y, 9, 0);
    seq.run(s, 9, true);
    fresh.run(s, 9);
    CHECK(outputHash(seq) == outputHash(fresh));
    CHECK(seq.out.diffuseFrames.at(5, 5) == 0.0f);
    // Without the cut, the same frame differs (the test can fail).
    Denoiser cont;
    for (uint32_t f = 0; f < 4; ++f) cont.run(s, f);
    cont.run(s, 9);
    CHECK(outputHash(cont) != outputHash(fresh));
}

TEST_CASE("denoise: NaN and infinity never enter the history, and the pixel recovers") {
    Synthetic s(64, 48), unpoisoned(64, 48);
    Denoiser d, clean;  // the same frames, with and without the poison
    for (uint32_t f = 0; f < 12; ++f) {
        for (Synthetic* frame : {&s, &unpoisoned})
            for (int y = 0; y < s.h; ++y)
                for (int x = 0; x < s.w; ++x)
                    for (int c = 0; c < 3; ++c)
                        frame->diffuse[c].at(x, y) = noise(x, y, f, uint32_t(c));
        s.specHit.fill(1.5f);
        s.diffuseHit.fill(1.0f);
        for (PlaneF& p : s.ssr) p.fill(0.25f);
        if (f == 1) {
            s.diffuse[0].at(20, 20) = std::nanf("");
            s.diffuse[1].at(21, 20) = INFINITY;
            s.ssr[2].at(22, 20) = -INFINITY;
            s.specHit.at(23, 20) = std::nanf("");
            s.diffuseHit.at(24, 20) = INFINITY;
        }
        d.run(s, f);
        clean.run(unpoisoned, f);
        CAPTURE(f);
        for (const PlaneF* p : {&d.out.diffuse[0], &d.out.diffuse[1], &d.out.diffuse[2],
                                &d.out.specular[0], &d.out.specular[1], &d.out.specular[2]})
            CHECK(allFinite(*p));
        CHECK(allFinite(d.history.diffuse));
        CHECK(allFinite(d.history.specular));
        for (const PlaneU16* p : {&d.history.diffuseFast, &d.history.specularFast})
            CHECK(allFinite(*p));
    }
    // Ten clean frames later the poisoned pixels are within the poisoned frame's share of the
    // history (its sample became 0: 1/11 of the mean at most) of the unpoisoned run.
    for (int x = 20; x <= 24; ++x) {
        const float v = d.out.diffuse[1].at(x, 20), want = clean.out.diffuse[1].at(x, 20);
        CAPTURE(x);
        CHECK(std::abs(v - want) < want / 11.0f);
    }
}

TEST_CASE("denoise: a history handed in with NaN restarts those pixels, and nothing spreads") {
    // The caller owns the history (issue 33's soak hands one in corrupt): a NaN block in its
    // radiance must not spread (a rejected tap's weight 0 times NaN is NaN) to the output or
    // to the next history.
    Synthetic s(64, 48);
    Denoiser d;
    for (uint32_t f = 0; f < 6; ++f) {
        for (int y = 0; y < s.h; ++y)
            for (int x = 0; x < s.w; ++x) s.diffuse[0].at(x, y) = noise(x, y, f, 0);
        if (f == 4) {
            // (NaN in diffuse R and G, specular B: f16x4 channels 0, 1 and 2.)
            const uint64_t nan = encodeF16(std::nanf(""));
            for (int y = 20; y < 28; ++y)
                for (int x = 28; x < 36; ++x) {
                    uint64_t& dif = d.history.diffuse.at(x, y);
                    uint64_t& spec = d.history.specular.at(x, y);
                    dif = (dif & ~0xffffffffull) | nan | nan << 16;
                    spec = (spec & ~(0xffffull << 32)) | nan << 32;
                }
        }
        d.run(s, f);
        CAPTURE(f);
        for (const PlaneF* p : {&d.out.diffuse[0], &d.out.diffuse[1], &d.out.specular[2]})
            CHECK(allFinite(*p));
        CHECK(allFinite(d.history.diffuse));
        CHECK(allFinite(d.history.specular));
    }
}

TEST_CASE("denoise: revealed background restarts its history and carries no ghost") {
    // A red box (depth 1) over a white wall (depth 4), moving 10 pixels right at frame 8; the
    // camera is still, so the wall's motion is 0 and the box's -10 (previous minus current).
    const int w = 96, h = 64;
    Synthetic s(w, h);
    const auto place = [&](int boxX, float boxMotion, uint32_t f) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const bool box = x >= boxX && x < boxX + 20 && y >= 20 && y < 44;
                s.viewZ.at(x, y) = box ? 1.0f : 4.0f;
                s.motion[0].at(x, y) = box ? boxMotion : 0.0f;
                const float n = noise(x, y, f, 0);
                s.diffuse[0].at(x, y) = box ? 2.0f * n : n;
                s.diffuse[1].at(x, y) = box ? 0.0f : n;
                s.diffuse[2].at(x, y) = box ? 0.0f : n;
            }
    };
    const auto run = [&](DenoiseSettings settings) {
        Denoiser d;
        d.settings = settings;
        for (uint32_t f = 0; f < 8; ++f) {
            place(30, 0.0f, f);
            d.run(s, f);
        }
        place(40, -10.0f, 8);
        d.run(s, 8);
        return d;
    };
    const Denoiser d = run(DenoiseSettings{});
    DenoiseSettings spatialOnly;
    spatialOnly.maxAccumulatedFrames = 0;
    const Denoiser ref = run(spatialOnly);
    double error = 0.0, errorSpatial = 0.0;
    int revealed = 0;
    for (int y = 22; y < 42; ++y)
        for (int x = 31; x < 39; ++x) {  // were box, now wall (a pixel from the edges)
            CAPTURE(x);
            CAPTURE(y);
            CHECK(d.out.diffuseFrames.at(x, y) == 0.0f);
            const float r = d.out.diffuse[0].at(x, y), g = d.out.diffuse[1].at(x, y);
            CHECK(std::abs(r - g) <= 0.05f * g);  // no red ghost
            error += std::abs(g - 1.0f) + std::abs(r - 1.0f);
            errorSpatial += std::abs(ref.out.diffuse[1].at(x, y) - 1.0f) +
                            std::abs(ref.out.diffuse[0].at(x, y) - 1.0f);
            ++revealed;
        }
    CHECK(revealed == 160);
    CHECK(error <= 1.1 * errorSpatial + 1e-6);
    // The wall that stayed keeps its history.
    CHECK(d.out.diffuseFrames.at(80, 10) == 8.0f);
    // The box's own history follows it: its pixels were box 10 pixels left.
    // The box moved across the view at one depth: its own history follows it.
    CHECK(d.out.diffuseFrames.at(50, 30) == 8.0f);
}

TEST_CASE("denoise: sky, screen edges, roughness 0 and 1 and random motion stay finite") {
    const int w = 80, h = 48;
    Synthetic s(w, h);
    Denoiser d;
    d.settings = everyPass();
    for (uint32_t f = 0; f < 8; ++f) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const uint32_t p = uint32_t(y * w + x);
                const bool sky = randomFloat(p, f, 1, 0) < 0.2f || x == 0 || y == h - 1;
                s.viewZ.at(x, y) = sky ? 0.0f : 0.1f + 20.0f * randomFloat(p, f, 1, 1);
                float n[3] = {randomFloat(p, f, 1, 2) - 0.5f, randomFloat(p, f, 1, 3) - 0.5f,
                              randomFloat(p, f, 1, 4)};
                const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) + 1e-6f;
                for (int c = 0; c < 3; ++c) s.normal[c].at(x, y) = n[c] / len;
                const float r = randomFloat(p, f, 1, 5);
                s.roughness.at(x, y) = r < 0.3f ? 0.0f : r > 0.7f ? 1.0f : r;
                s.motion[0].at(x, y) = 40.0f * (randomFloat(p, f, 1, 6) - 0.5f);
                s.motion[1].at(x, y) = 40.0f * (randomFloat(p, f, 1, 7) - 0.5f);
                s.diffuseHit.at(x, y) = randomFloat(p, f, 1, 8) < 0.3f ? 0.0f : 30.0f * r;
                s.specHit.at(x, y) = randomFloat(p, f, 1, 9) < 0.3f ? 0.0f : 0.001f * r;
                s.metallic.at(x, y) = randomFloat(p, f, 1, 10) < 0.2f ? 1.0f : 0.0f;
                s.opacity.at(x, y) = randomFloat(p, f, 1, 11);
                for (int c = 0; c < 3; ++c) {
                    s.diffuse[c].at(x, y) = 100.0f * noise(x, y, f, uint32_t(c));
                    s.ssr[c].at(x, y) = noise(x, y, f, uint32_t(c + 3));
                }
            }
        s.camera.position[0] = 0.1f * float(f);  // a moving camera
        d.run(s, f);
        CAPTURE(f);
        for (int c = 0; c < 3; ++c) {
            CHECK(allFinite(d.out.diffuse[c]));
            CHECK(allFinite(d.out.specular[c]));
        }
        CHECK(allFinite(d.history.diffuse));
        CHECK(allFinite(d.history.specular));
    }
}

TEST_CASE("denoise: every ISA and thread count gives the same bits over a moving sequence") {
    const int w = 72, h = 40;  // not a multiple of the lane width or the tile
    const auto sequence = [&](Isa isa, int threads) {
        Synthetic s(w, h);
        Denoiser d;
        d.settings = everyPass();
        d.settings.postBlurMaxFrames = 5;  // (steady pixels of frames 5-7 skip the post-blur)
        d.isa = isa;
        d.threads = threads;
        for (uint32_t f = 0; f < 8; ++f) {
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    s.viewZ.at(x, y) = 2.0f + 0.02f * float(x) + 0.5f * float((x / 9 + y / 7) % 2);
                    s.roughness.at(x, y) = float((x + y) % 10) * 0.08f;
                    s.motion[0].at(x, y) = -0.7f;
                    s.motion[1].at(x, y) = 0.3f;
                    for (int c = 0; c < 3; ++c) {
                        s.diffuse[c].at(x, y) = noise(x, y, f, uint32_t(c));
                        s.ssr[c].at(x, y) = noise(x, y, f, uint32_t(c + 3));
                    }
                    s.specHit.at(x, y) = noise(x, y, f, 9);
                }
            s.camera.position[0] = 0.05f * float(f);
            d.run(s, f);
        }
        return outputHash(d);
    };
    const uint64_t ref = sequence(Isa::Scalar, 1);
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 2, 8})) {
            CAPTURE(std::string(isaName(isa)));
            CAPTURE(threads);
            CHECK(sequence(isa, threads) == ref);
        }
}
