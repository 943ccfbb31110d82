// The denoiser in the renderer, along sequences: a camera path renders the same bits on every
// ISA and thread count and keeps its golden hashes; a mirror stays sharp on a moving camera
// (virtual motion); a camera cut resets the history.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <string>

#include "core/pixel_formats.h"
#include "frame_hash.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "thread_counts.h"

using namespace ssrt;

namespace {

// The scene's camera turned about its target by `degrees` around the up axis.
Camera orbit(const Camera& c, float degrees) {
    Camera out = c;
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), c.up);
    out.position = c.target + glm::vec3(turn * glm::vec4(c.position - c.target, 0.0f));
    return out;
}

RenderSettings small(Isa isa, int threads) {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 90;
    rs.shadowMapSize = 512;
    rs.isa = isa;
    rs.threads = threads;
    return rs;
}

using test::frameHash;

// Renders frames 0..count-1 along an orbit of `degreesPerFrame`, calling fn(i, frame) after
// each.
template <class Fn>
void renderOrbit(const Scene& scene, const RenderSettings& rs, int count, float degreesPerFrame,
                 Fn&& fn) {
    const Renderer renderer(rs);
    Frame frame;
    FrameHistory history;
    FrameInput input;
    for (int i = 0; i < count; ++i) {
        input.previousCamera = i > 0 ? input.camera : orbit(scene.camera, 0.0f);
        input.camera = orbit(scene.camera, degreesPerFrame * float(i));
        input.frameIndex = uint32_t(i);
        renderer.render(scene, input, history, frame);
        fn(i, frame);
    }
}

uint64_t sequenceHash(const std::string& name, Isa isa, int threads) {
    uint64_t h = 0;
    renderOrbit(makeBuiltinScene(name), small(isa, threads), 8, 1.5f, [&](int i, const Frame& f) {
        if (i == 7) h = frameHash(f);
    });
    return h;
}

// Recorded from this build (GCC 12, Debian 12); re-record with SSRT_PRINT_GOLDEN=1 and say
// why in the commit.
// clang-format off
const std::map<std::string, uint64_t> kGolden = {
    {"cornell", 0x0a5e9f06dfd965f9ull},
    {"spheres", 0xdf4dc6dbfc29e7e3ull},
};
// clang-format on

// Mean relative squared error of the denoised incoming specular against a reference, over
// the pixels with a specular signal (the mirror and the smooth surfaces).
double specularError(const Frame& f, const Frame& ref) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            if (!(f.gbuffer.viewZ.at(x, y) > 0.0f) || !(f.gbuffer.roughness.at(x, y) < 0.3f))
                continue;
            for (int c = 0; c < 3; ++c) {
                const double r =
                    ref.rgb(Res::Ssr)[c].at(x, y) * ref.plane(Res::SsrOpacity).at(x, y) +
                    decodeF16(ref.direct.envSpecular[c].at(x, y)) *
                        (1.0 - ref.plane(Res::SsrOpacity).at(x, y));
                const double d = f.rgb(Res::DenoisedSpecular)[c].at(x, y) - r;
                sum += d * d / (r * r + 0.01);
            }
            ++n;
        }
    return n ? sum / (3.0 * n) : 0.0;
}

}  // namespace

TEST_CASE("denoise sequence: a camera path renders the same bits on every ISA and thread count") {
    for (const char* name : {"cornell", "spheres"}) {
        CAPTURE(std::string(name));
        const uint64_t ref = sequenceHash(name, Isa::Scalar, 1);
        for (Isa isa : supportedIsas())
            for (int threads : testThreadCounts({1, 2, 8})) {
                CAPTURE(std::string(isaName(isa)));
                CAPTURE(threads);
                CHECK(sequenceHash(name, isa, threads) == ref);
            }
    }
}

TEST_CASE("denoise sequence: camera paths keep their golden hashes") {
    const bool print = std::getenv("SSRT_PRINT_GOLDEN") != nullptr;
    for (const auto& entry : kGolden) {
        const std::string& name = entry.first;
        CAPTURE(name);
        const uint64_t h = sequenceHash(name, Isa::Scalar, 2);
        if (print)
            std::printf("    {\"%s\", 0x%016llxull},\n", name.c_str(), (unsigned long long)h);
        CHECK(h == entry.second);
        // The best ISA too, on 1 thread (built-in scenes' golden test says why).
        const std::string best(isaName(supportedIsas().back()));
        CAPTURE(best);
        CHECK(sequenceHash(name, supportedIsas().back(), 1) == entry.second);
    }
}

TEST_CASE("denoise sequence: a mirror stays sharp on a moving camera (virtual motion)") {
    // Cornell's mirror sphere, still and on an orbit of 0.75 degrees a frame; each frame's
    // denoised specular against the same camera's undenoised 32-ray SSR (the screen-space
    // answer the denoiser converges to, so this measures the denoiser, not the tracer).
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings rs = small(defaultIsa(), 2);
    RenderSettings refSettings = rs;
    refSettings.trace.ssrSpp = 32;
    refSettings.trace.ssgi = false;
    refSettings.trace.denoise.enabled = false;
    const Renderer reference(refSettings);
    const auto run = [&](float degrees, bool virtualMotion, int first, int last) {
        RenderSettings s = rs;
        s.trace.denoise.virtualMotion = virtualMotion;
        double sum = 0.0;
        int n = 0;
        renderOrbit(scene, s, last + 1, degrees, [&](int i, const Frame& f) {
            if (i < first || (i - first) % 4) return;
            FrameInput in;
            in.camera = in.previousCamera = orbit(scene.camera, degrees * float(i));
            in.frameIndex = 1000u + uint32_t(i);
            sum += specularError(f, reference.renderWithoutHistory(scene, in));
            ++n;
        });
        return sum / n;
    };
    const double still = run(0.0f, true, 30, 30);
    const double moving = run(0.75f, true, 10, 46);
    const double surfaceOnly = run(0.75f, false, 10, 46);
    MESSAGE("specular relMSE: still frame 30 " << still << ", orbit frames 10-46 " << moving
                                               << ", orbit without virtual motion " << surfaceOnly);
    // Measured: 0.0156 still, 0.0424 on the orbit, 0.244 following the surface alone. (Before
    // issue 44 sharpened the mirror, 0.0251, 0.0469 and 0.234: the still frame gained more than
    // the orbit, whose error is the motion's, so the orbit is bounded by its own level, not by
    // a multiple of the still frame's.)
    CHECK(moving < 0.05);
    CHECK(moving < 0.5 * surfaceOnly);
}

TEST_CASE("denoise sequence: a camera cut renders as a fresh history would") {
    const Scene scene = makeBuiltinScene("spheres");
    const RenderSettings rs = small(defaultIsa(), 2);
    const Renderer renderer(rs);
    Frame a, b;
    FrameHistory history, fresh;
    FrameInput input = FrameInput::still(scene);
    for (uint32_t i = 0; i < 4; ++i) {
        input.frameIndex = i;
        renderer.render(scene, input, history, a);
    }
    input.camera = input.previousCamera = orbit(scene.camera, 30.0f);
    input.frameIndex = 4;
    input.resetHistory = true;
    renderer.render(scene, input, history, a);
    input.resetHistory = false;
    renderer.render(scene, input, fresh, b);
    CHECK(frameHash(a) == frameHash(b));
    CHECK(a.plane(Res::DiffuseFrames).at(80, 45) == 0.0f);
}

TEST_CASE("denoise sequence: a camera pan reveals background that restarts its history") {
    // Cornell, panning 3 degrees a frame: a pixel whose previous position showed another
    // instance nearer the camera (the tall box against the wall behind it) is revealed and
    // must start afresh (where its whole bilinear footprint did: NRD keeps the taps that
    // still see the same surface); one that showed its own instance well inside it keeps its frames
    // (fractions of a frame may go to rounding: the bilinear weights sum to 1 within an ulp).
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings rs = small(defaultIsa(), 2);
    // The diffuse signal denoised at full resolution, so that each pixel's history length is
    // its own (at half resolution the upsample blends the half pixels' lengths).
    rs.trace.ssgiLayout = TraceLayout::Full;
    int revealed = 0, restarted = 0, kept = 0, keptFrames = 0;
    PlaneF previousIds, previousZ;
    renderOrbit(scene, rs, 8, 3.0f, [&](int i, const Frame& f) {
        if (i >= 3) {
            const PlaneF& ids = f.gbuffer.instanceId;
            for (int y = 2; y < f.height - 2; ++y)
                for (int x = 2; x < f.width - 2; ++x) {
                    if (!(f.gbuffer.viewZ.at(x, y) > 0.0f)) continue;
                    // The previous position and its bilinear footprint's corner.
                    const float qx = float(x) + 0.5f + f.gbuffer.motion[0].at(x, y);
                    const float qy = float(y) + 0.5f + f.gbuffer.motion[1].at(x, y);
                    const int px = int(std::floor(qx)), py = int(std::floor(qy));
                    const int fx = int(std::floor(qx - 0.5f)), fy = int(std::floor(qy - 0.5f));
                    if (fx < 2 || fy < 2 || fx >= f.width - 3 || fy >= f.height - 3) continue;
                    const float id = ids.at(x, y);
                    bool same = true;  // the previous 5x5 around it all this instance
                    for (int dy = -2; dy <= 2; ++dy)
                        for (int dx = -2; dx <= 2; ++dx)
                            same &= previousIds.at(px + dx, py + dy) == id;
                    const float frames = f.plane(Res::DiffuseFrames).at(x, y);
                    // Revealed: the whole footprint showed something nearer.
                    const float z = f.gbuffer.viewZ.at(x, y);
                    bool occluded = true;
                    for (int dy = 0; dy <= 1; ++dy)
                        for (int dx = 0; dx <= 1; ++dx) {
                            const float zp = previousZ.at(fx + dx, fy + dy);
                            occluded &= zp > 0.0f && zp < 0.9f * z;
                        }
                    if (occluded && f.gbuffer.metallic.at(x, y) < 1.0f) {
                        ++revealed;
                        restarted += frames < 1.0f;
                    } else if (same) {
                        ++kept;
                        keptFrames += frames >= float(i) - 0.5f;  // since frame 0
                    }
                }
        }
        previousIds = f.gbuffer.instanceId.clone();
        previousZ = f.gbuffer.viewZ.clone();
    });
    MESSAGE("revealed " << revealed << " (restarted " << restarted << "), kept " << kept
                        << " (full history " << keptFrames << ")");
    REQUIRE(revealed > 20);
    CHECK(restarted >= 0.9 * revealed);
    CHECK(keptFrames >= 0.9 * kept);
}

TEST_CASE("denoise sequence: a frame that does not replace the history renders the same bits") {
    // The last frame of a sequence reads the history and leaves it (FrameInput::replaceHistory):
    // the same image as a frame that replaces it, the history untouched, and without a
    // history to begin with no history made at all.
    const Scene scene = makeBuiltinScene("cornell");
    const RenderSettings rs = small(Isa::Scalar, 2);
    const Renderer renderer(rs);
    FrameHistory history;
    Frame frame;
    FrameInput input = FrameInput::still(scene);
    for (uint32_t i = 0; i < 3; ++i) {
        input.frameIndex = i;
        renderer.render(scene, input, history, frame);
    }
    input.frameIndex = 3;
    // (The default preset traces SSGI at half resolution: its diffuse history is the half one.)
    FrameHistory kept;
    kept.denoise.guide.viewZ = history.denoise.guide.viewZ.clone();
    kept.denoise.specular = history.denoise.specular.clone();
    kept.denoise.specularFrames = history.denoise.specularFrames.clone();
    kept.denoiseHalf.diffuse = history.denoiseHalf.diffuse.clone();
    Frame last;
    input.replaceHistory = false;
    renderer.render(scene, input, history, last);
    CHECK(history.denoise.valid);
    CHECK(history.denoiseHalf.valid);
    CHECK(hashPlane(history.denoise.guide.viewZ) == hashPlane(kept.denoise.guide.viewZ));
    CHECK(hashPlane(history.denoise.specular) == hashPlane(kept.denoise.specular));
    CHECK(hashPlane(history.denoise.specularFrames) == hashPlane(kept.denoise.specularFrames));
    CHECK(hashPlane(history.denoiseHalf.diffuse) == hashPlane(kept.denoiseHalf.diffuse));
    input.replaceHistory = true;
    renderer.render(scene, input, history, frame);
    CHECK(frameHash(last) == frameHash(frame));
    CHECK(hashPlane(history.denoise.specular) != hashPlane(kept.denoise.specular));
    CHECK(hashPlane(history.denoiseHalf.diffuse) != hashPlane(kept.denoiseHalf.diffuse));

    FrameHistory none;
    input.replaceHistory = false;
    renderer.render(scene, input, none, last);
    CHECK(none.denoise.guide.viewZ.empty());
    CHECK(none.denoiseHalf.guide.viewZ.empty());
    CHECK_FALSE(none.denoise.valid);
}
