// The multi-bounce reference (ReferenceSettings::bounces): an emitting closed sphere seen from
// inside (every path stays in and every hit emits the same: the geometric series, exactly), one
// bounce as before, more bounces only add light; and (skipped by default) the energy each bounce
// count leaves out on cornell, which sets --reference-bounces auto with feedback.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "plane_compare.h"
#include "scenes/mesh_builders.h"
#include "tests/truth/reference_test_rig.h"
#include "truth/image_error.h"

using namespace ssrt;
using test::ReferenceRig;

namespace {

double meanOf(const PlaneF (&p)[3]) {
    double s = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < p[c].height(); ++y)
            for (int x = 0; x < p[c].width(); ++x) s += p[c].at(x, y);
    return s / (3.0 * p[0].width() * p[0].height());
}

// The inside of a closed box, double-sided, of diffuse reflectance `albedo`, emitting `emission`
// everywhere; the sun off and a black sky (a ray that escaped through a crack would show).
Scene emittingBox(glm::vec3 albedo, glm::vec3 emission) {
    Scene s;
    s.meshes.push_back(makeBox(glm::vec3(1.0f, 0.8f, 1.2f)));
    Material m;
    m.baseColor = albedo;
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    m.emissive = emission;
    m.doubleSided = true;
    s.materials.push_back(m);
    s.instances.push_back(Instance{});
    s.sky.kind = Sky::Kind::Constant;
    s.sky.zenith = glm::vec3(0.0f);
    s.light.intensity = 0.0f;
    s.camera.position = {0.1f, 0.2f, 0.6f};
    s.camera.target = {-0.3f, -0.1f, -1.0f};
    s.camera.fovY = 70.0f;
    s.previousCamera = s.camera;
    return s;
}

struct BoxRig {
    Scene scene;
    Renderer renderer;
    Frame frame;
    EmbreeScene embree;
    BoxRig(glm::vec3 albedo, glm::vec3 emission)
        : scene(emittingBox(albedo, emission)),
          renderer(test::referenceRigSettings(64, 40, 2, true, 64)),
          frame(renderer.renderWithoutHistory(scene)),
          embree(scene) {}
    ReferenceImage reference(int bounces, int spp = 4) const {
        ReferenceSettings s;
        s.spp = spp;
        s.bounces = bounces;
        s.maxDistance = 100.0f;
        return renderReference(embree, renderer, frame, s);
    }
};

}  // namespace

TEST_CASE("reference bounces: an emitting closed box converges to the geometric series") {
    // Every path stays inside and every hit sends E back, so a path of N hits brings
    //   L_N = E (1 + a + a^2 + ... + a^(N-1)) = E (1 - a^N) / (1 - a)
    // whatever its directions: each pixel's SSGI is that, up to float rounding, and the
    // N-th bounce adds E a^(N-1). (A pixel's first ray may leak through a corner: it starts
    // epsilon off the surface and epsilon along, as it always has, and steps over a wall
    // closer than that. Such pixels are found at one bounce and left out; the further
    // bounces start at 0 and do not leak.)
    const glm::vec3 a(0.3f, 0.6f, 0.9f), e(1.0f, 0.5f, 0.25f);
    const BoxRig rig(a, e);
    const int w = rig.frame.width, h = rig.frame.height;
    std::vector<bool> leaked(std::size_t(w) * h, false);
    int leaks = 0;
    for (int n : {1, 2, 3, 8, 40}) {
        CAPTURE(n);
        const ReferenceImage ref = rig.reference(n);
        int off = 0, surface = 0;
        float worst = 0.0f;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                surface += rig.frame.gbuffer.viewZ.at(x, y) > 0.0f;
                for (int c = 0; c < 3; ++c) {
                    const double expect = e[c] * (1.0 - std::pow(double(a[c]), n)) / (1.0 - a[c]);
                    const float err = float(std::abs(ref.ssgi[c].at(x, y) - expect) / expect);
                    if (n == 1 && err > 1e-5f && !leaked[std::size_t(y) * w + x]) {
                        leaked[std::size_t(y) * w + x] = true;
                        ++leaks;
                    }
                    if (leaked[std::size_t(y) * w + x]) continue;
                    worst = std::max(worst, err);
                    off += err > 1e-5f;
                }
            }
        MESSAGE(n << " bounces: worst relative error " << worst << " over " << w * h - leaks
                  << " pixels (" << leaks << " whose first ray leaked)");
        CHECK(surface == w * h);
        CHECK(off == 0);
    }
    CHECK(leaks <= w * h / 1000);
}

TEST_CASE("reference bounces: converged is the whole series, but for a negligible tail") {
    // The path ends once its throughput is at most kNegligibleThroughput: the box's bluest
    // reflectance 0.9 gets there after 66 hits (0.9^66 = 9.6e-4), so a pixel holds the whole
    // series E / (1 - a) less a tail below that fraction of it, and more than 40 bounces do.
    const glm::vec3 a(0.3f, 0.6f, 0.9f), e(1.0f, 0.5f, 0.25f);
    const BoxRig rig(a, e);
    const ReferenceImage ref = rig.reference(ReferenceSettings::kConverged);
    const int w = rig.frame.width, h = rig.frame.height;
    int off = 0, blueShort = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool pixelOff = false;
            for (int c = 0; c < 3; ++c) {
                const double all = e[c] / (1.0 - a[c]);
                const double forty = e[c] * (1.0 - std::pow(double(a[c]), 40)) / (1.0 - a[c]);
                const double v = ref.ssgi[c].at(x, y);
                const double tail = (all - v) / all;
                pixelOff |= !(tail > -1e-5 && tail < 1.0e-3 + 1e-5);
                if (c == 2) blueShort += tail > 1e-4 && v > forty;
            }
            off += pixelOff;
        }
    MESSAGE(off << " pixels off the series, " << blueShort << " blue values cut in the tail");
    // (A pixel whose first ray leaks through a corner is off: at most one in a thousand.)
    CHECK(off <= w * h / 1000);
    // The cut is there (a fixed 256 bounces would hold the series to float rounding) and
    // beyond 40 bounces.
    CHECK(blueShort > w * h / 2);
    // The count is validated: kConverged passes, negative ones do not.
    ReferenceSettings s;
    s.bounces = ReferenceSettings::kConverged;
    CHECK_NOTHROW(s.validate());
    s.bounces = -1;
    CHECK_THROWS_AS(s.validate(), std::invalid_argument);
}

TEST_CASE("reference bounces: converged cornell holds 64 bounces' light to 0.1 %") {
    const ReferenceRig rig("cornell", 96, 54, 2);
    ReferenceSettings s;
    s.spp = 4;
    s.maxDistance = 1e4f;
    s.bounces = 64;
    const ReferenceImage many = renderReference(rig.embree, rig.renderer, rig.frame, s);
    s.bounces = ReferenceSettings::kConverged;
    const ReferenceImage all = renderReference(rig.embree, rig.renderer, rig.frame, s);
    s.bounces = 1;
    const ReferenceImage one = renderReference(rig.embree, rig.renderer, rig.frame, s);
    const double dMany = meanOf(many.diffuse), dAll = meanOf(all.diffuse),
                 dOne = meanOf(one.diffuse);
    MESSAGE("mean diffuse part: one bounce " << dOne << ", converged " << dAll << ", 64 bounces "
                                             << dMany);
    CHECK(std::abs(dAll - dMany) <= 1e-3 * dMany);
    CHECK(dAll > 1.2 * dOne);  // (28 % of cornell's diffuse light is past the first bounce)
}

TEST_CASE("reference bounces: more bounces only add diffuse light -- the rest keeps its bits") {
    const ReferenceRig rig("cornell", 96, 54, 2);
    ReferenceSettings s;
    s.spp = 4;
    s.maxDistance = 1e4f;
    const ReferenceImage one = renderReference(rig.embree, rig.renderer, rig.frame, s);
    s.bounces = 3;
    const ReferenceImage three = renderReference(rig.embree, rig.renderer, rig.frame, s);
    // Samples 0..spp-1 draw the same first rays, and each further hit adds light >= 0.
    int less = 0, more = 0, surface = 0;
    for (int y = 0; y < rig.frame.height; ++y)
        for (int x = 0; x < rig.frame.width; ++x) {
            if (!(rig.frame.gbuffer.viewZ.at(x, y) > 0.0f)) continue;
            ++surface;
            for (int c = 0; c < 3; ++c) {
                less += three.ssgi[c].at(x, y) < one.ssgi[c].at(x, y);
                more += three.ssgi[c].at(x, y) > one.ssgi[c].at(x, y);
            }
        }
    MESSAGE(more << " of " << 3 * surface << " surface values raised, " << less << " lowered");
    CHECK(less == 0);
    CHECK(more > 2 * surface);
    // The direct and specular parts do not depend on the bounce count.
    for (int c = 0; c < 3; ++c) {
        CHECK(test::sameBits(one.direct[c], three.direct[c]));
        CHECK(test::sameBits(one.ssr[c], three.ssr[c]));
    }
    // A bounce count out of range is refused.
    s.bounces = -1;
    CHECK_THROWS_AS(renderReference(rig.embree, rig.renderer, rig.frame, s), std::invalid_argument);
    s.bounces = ReferenceSettings::kMaxBounces + 1;
    CHECK_THROWS_AS(renderReference(rig.embree, rig.renderer, rig.frame, s), std::invalid_argument);
}

TEST_CASE("reference bounces: the count is in the cache key, 1 keeps the key it had") {
    const Scene scene = makeBuiltinScene("cornell");
    const RenderSettings rs;
    ReferenceSettings s;
    const uint64_t one = referenceKey(scene, scene.camera, 0, rs, s);
    CHECK(one == 2469946427571681638ull);  // tests/renderer/settings_key_pin_test.cpp's
    s.bounces = 2;
    const uint64_t two = referenceKey(scene, scene.camera, 0, rs, s);
    s.bounces = 8;
    const uint64_t eight = referenceKey(scene, scene.camera, 0, rs, s);
    CHECK(two != one);
    CHECK(eight != two);
    CHECK(eight != one);
}

namespace {

ImageError errorOf(const PlaneF (&image)[3], const PlaneF (&ref)[3]) {
    const PlaneF* i[3] = {&image[0], &image[1], &image[2]};
    const PlaneF* r[3] = {&ref[0], &ref[1], &ref[2]};
    return imageError(i, r);
}

double colourRelMse(const Frame& f, const ReferenceImage& ref) {
    const auto iRgb = f.rgb(Res::Color);
    const PlaneF* i[3] = {&iRgb[0], &iRgb[1], &iRgb[2]};
    const PlaneF* r[3] = {&ref.color[0], &ref.color[1], &ref.color[2]};
    return imageError(i, r).relMse;
}

}  // namespace

TEST_CASE("reference bounces: SSGI feedback on a still camera converges to the matching one") {
    // Cornell, the frame's own model, the reference with 1 and with kBounces bounces: frame 0
    // (one bounce) is nearer the first, and after 10 frames of feedback (10 bounces, the
    // later ones all but nothing) nearer the second. (Screen space gets about half of the
    // further bounces' light: the diffuse part goes 0.102 -> 0.119 where the references'
    // go 0.096 -> 0.133; what lies off the screen it cannot see.)
    constexpr int kBounces = 8;
    const ReferenceRig rig("cornell", 160, 90, 2);
    ReferenceSettings s;
    s.spp = 32;
    s.maxDistance = 1e4f;
    const ReferenceImage one = renderReference(rig.embree, rig.renderer, rig.frame, s);
    s.bounces = kBounces;
    const ReferenceImage many = renderReference(rig.embree, rig.renderer, rig.frame, s);
    RenderSettings rs = rig.renderer.settings();
    rs.trace.ssgiFeedback = true;
    // 16 rays: relMSE (I - R)^2 / (R^2 + 0.01) of a 1-ray frame is mostly noise, and noise
    // weighs less against the brighter reference whatever the bias.
    rs.trace.ssgiSpp = 16;
    const Renderer fed(rs);
    FrameInput input = FrameInput::still(rig.scene);
    FrameHistory history;
    Frame f;
    std::vector<double> toOne, toMany, diffuse;
    for (int k = 0; k < 10; ++k) {
        input.frameIndex = uint32_t(k);
        fed.render(rig.scene, input, history, f);
        toOne.push_back(colourRelMse(f, one));
        toMany.push_back(colourRelMse(f, many));
        diffuse.push_back(meanOf(frameParts(f).diffuse));
        MESSAGE("frame " << k << ": colour relMSE " << toOne.back() << " against 1 bounce, "
                         << toMany.back() << " against " << kBounces << "; mean diffuse part "
                         << diffuse.back() << " (references " << meanOf(one.diffuse) << ", "
                         << meanOf(many.diffuse) << ")");
    }
    CHECK(diffuse[9] > 1.1 * diffuse[0]);
    CHECK(toOne[0] < toMany[0]);
    CHECK(toMany[9] < toOne[9]);
    CHECK(toMany[9] < toMany[0]);
}

// The figures for the report (run with --no-skip): the mean diffuse part and colour of
// cornell's reference for each bounce count, against 64 bounces.
TEST_CASE("reference bounces: measure the energy left out on cornell" * doctest::skip()) {
    const ReferenceRig rig("cornell", 160, 90, 2, true, 0);
    std::vector<int> counts = {1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 24, 32, 64};
    std::vector<double> diffuse, color, sec;
    for (int n : counts) {
        ReferenceSettings s;
        s.spp = 32;
        s.bounces = n;
        s.maxDistance = 1e4f;
        const auto t0 = std::chrono::steady_clock::now();
        const ReferenceImage ref = renderReference(rig.embree, rig.renderer, rig.frame, s);
        sec.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        diffuse.push_back(meanOf(ref.diffuse));
        color.push_back(meanOf(ref.color));
    }
    for (std::size_t i = 0; i < counts.size(); ++i)
        std::printf(
            "bounces %2d: mean diffuse %.5f (%.2f %% missing), colour %.5f (%.2f %% "
            "missing), %.1f s\n",
            counts[i], diffuse[i], 100.0 * (1.0 - diffuse[i] / diffuse.back()), color[i],
            100.0 * (1.0 - color[i] / color.back()), sec[i]);
}

// The figures for the report (run with --no-skip): cornell at 640x360 (2 threads), a still
// camera, colour relMSE against the 64-spp reference with 1 and with 8 bounces, one bounce
// and feedback, on the 1st, 10th and 30th frame of a sequence, 1 and 16 SSGI rays.
TEST_CASE("reference bounces: measure feedback's convergence on cornell 640x360" *
          doctest::skip()) {
    const ReferenceRig rig("cornell", 640, 360, 2, true, 0);
    ReferenceSettings s;
    s.spp = 64;
    s.maxDistance =
        marchLengths(rig.renderer.settings().trace.march, rig.scene.diagonal()).maxDistance;
    const auto timed = [&](int bounces) {
        s.bounces = bounces;
        const auto t0 = std::chrono::steady_clock::now();
        ReferenceImage r = renderReference(rig.embree, rig.renderer, rig.frame, s);
        std::printf("reference, %d bounces: %.1f s\n", bounces,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        return r;
    };
    const ReferenceImage one = timed(1), many = timed(8);
    for (int spp : {1, 16})
        for (bool feedback : {false, true}) {
            RenderSettings rs = rig.renderer.settings();
            rs.trace.ssgiFeedback = feedback;
            rs.trace.ssgiSpp = spp;
            const Renderer r(rs);
            FrameInput input = FrameInput::still(rig.scene);
            FrameHistory history;
            Frame f;
            double resolveMs = 0.0;
            for (int k = 0; k < 30; ++k) {
                input.frameIndex = uint32_t(k);
                r.render(rig.scene, input, history, f);
                for (const PassTime& p : f.stats.passes)
                    if (p.name == "ssgi resolve" && k > 0) resolveMs += p.ms;
                if (k != 0 && k != 9 && k != 29) continue;
                const FrameParts parts = frameParts(f);
                std::printf(
                    "ssgi x%-2d %-9s frame %2d: colour relMSE %.4f (1 bounce) %.4f (8 "
                    "bounces); diffuse part relMSE %.4f %.4f, mean %.4f (refs %.4f %.4f)\n",
                    spp, feedback ? "feedback" : "1 bounce", k + 1, colourRelMse(f, one),
                    colourRelMse(f, many), errorOf(parts.diffuse, one.diffuse).relMse,
                    errorOf(parts.diffuse, many.diffuse).relMse, meanOf(parts.diffuse),
                    meanOf(one.diffuse), meanOf(many.diffuse));
            }
            std::printf("ssgi x%-2d %-9s: ssgi resolve %.2f ms per frame (frames 2-30)\n", spp,
                        feedback ? "feedback" : "1 bounce", resolveMs / 29.0);
        }
}
