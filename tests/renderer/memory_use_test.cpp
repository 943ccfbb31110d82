// The --stats memory table (renderer/memory_use.h): every resource that holds memory, named as
// the resource table names it, with the bytes its planes hold, and nothing a frame does not hold.
#include "renderer/memory_use.h"

#include <doctest/doctest.h>

#include <initializer_list>
#include <map>
#include <string>

#include "core/plane_memory.h"
#include "plane_compare.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

std::map<std::string, std::size_t> byName(const std::vector<MemoryUse>& rows) {
    std::map<std::string, std::size_t> m;
    for (const MemoryUse& r : rows) {
        CHECK(m.count(r.name) == 0);  // each resource once
        CHECK(r.bytes > 0);           // empty ones are left out
        m[r.name] = r.bytes;
    }
    return m;
}

// The bytes of the rows named (0 for those not there).
std::size_t sum(const std::map<std::string, std::size_t>& m,
                std::initializer_list<const char*> names) {
    std::size_t n = 0;
    for (const char* name : names) n += m.count(name) ? m.at(name) : 0;
    return n;
}

// The G-buffer's resources, and the rows of scratch that no pass hands on.
const std::initializer_list<const char*> kGBuffer = {
    "viewZ", "normal", "albedo", "metallic", "roughness", "materialId", "motion"};
const std::initializer_list<const char*> kPassScratch = {"ray.pdf",
                                                         "rays",
                                                         "march.hit",
                                                         "march",
                                                         "resolve.hitRadiance",
                                                         "resolve.hitTarget",
                                                         "ssr resolve",
                                                         "noisy.diffuse",
                                                         "noisy.specular",
                                                         "preBlurred.diffuse",
                                                         "preBlurred.specular",
                                                         "temporal.diffuse",
                                                         "temporal.specular",
                                                         "fixed.diffuse",
                                                         "fixed.specular",
                                                         "blurred.diffuse",
                                                         "blurred.specular",
                                                         "state.diffuse",
                                                         "state.specular",
                                                         "fast.diffuse",
                                                         "fast.specular",
                                                         "half.noisy.diffuse",
                                                         "half.preBlurred.diffuse",
                                                         "half.temporal.diffuse",
                                                         "half.fixed.diffuse",
                                                         "half.blurred.diffuse",
                                                         "half.state.diffuse",
                                                         "half.fast.diffuse"};

}  // namespace

TEST_CASE("memory use: each resource's planes, named from the resource table") {
    RenderSettings rs;
    rs.width = 40;
    rs.height = 24;
    rs.shadowMapSize = 64;
    rs.trace.ssr = true;
    rs.trace.ssgi = true;
    rs.trace.denoise.enabled = true;
    const Scene scene = makeBuiltinScene("cornell");
    FrameHistory history;
    Frame frame;
    Renderer(rs).render(scene, FrameInput::still(scene), history, frame);
    const auto m = byName(frame.stats.memory);
    CHECK(m == byName(memoryUse(frame, &history)));
    // A plane of the frame: 40 floats padded to 48 (64-byte rows), 24 rows.
    const std::size_t plane = 48 * 24 * sizeof(float);
    REQUIRE(frame.gbuffer.viewZ.bytes() == plane);
    CHECK(m.at("color") == 3 * plane);
    CHECK(m.at("display") == 3 * plane);
    CHECK(m.at("shadow") == plane);
    CHECK(m.at("normal") == 3 * plane);
    CHECK(sum(m, kGBuffer) == 12 * plane);
    CHECK(m.at("ssr") == 3 * plane);
    CHECK(sum(m, {"ssrOpacity", "ssrHit", "ssrHitDistance", "ssrSteps"}) == 4 * plane);
    // direct, sky specular and its weight, SSGI's hit light: no sky diffuse (SSGI's light
    // replaces it), no emission (nothing in cornell emits); f16, half a float plane each.
    for (const char* part : {"direct", "envSpecular", "specWeight", "hitLight"})
        CHECK_MESSAGE(m.at(part) == 3 * plane / 2, part);
    CHECK(m.count("envDiffuse") == 0);
    CHECK(m.count("emission") == 0);
    CHECK(sum(m, {"denoisedDiffuse", "denoisedSpecular", "diffuseFrames", "specularFrames"}) ==
          8 * plane);
    // Between frames no scratch that passes hand on is held: its planes went back to the
    // planes' range after their last pass (renderer/frame_memory.h), whose pages stay the
    // process's; the table says how much of them no plane uses.
    const std::size_t plane16 = PlaneU16(40, 24).bytes();
    REQUIRE(plane16 == plane / 2);
    if (planeMemoryUse().fromRange) CHECK(m.at("free plane memory") > 0);
    for (const char* pooled : kPassScratch) CHECK_MESSAGE(m.count(pooled) == 0, pooled);
    // The denoiser's history (the specular's: the diffuse is denoised on the half frame): the
    // guides (viewZ, normal 3, roughness) and frames in f32, the signal's four channels packed
    // in f16 (f16x4) and its fast luma in f16.
    CHECK(m.at("history.denoise.guide") == 5 * plane);
    CHECK(m.at("history.denoise.specularFrames") == plane);
    CHECK(m.at("history.denoise.specular") == PlaneU64(40, 24).bytes());
    CHECK(m.at("history.denoise.specularFast") == plane16);
    CHECK(m.count("history.denoise.diffuse") == 0);
    CHECK(m.count("half denoise history") == 1);
    CHECK(m.at("shadowMap") == 64 * 64 * sizeof(float));
    // (The colour history only where a setting reads it: not by default.)
    CHECK(m.count("history.color") == 0);
    // SSR off: the full-resolution denoiser has no signal and does not run; the diffuse is
    // denoised on the half frame and still reaches the frame.
    {
        RenderSettings d = rs;
        d.trace.ssr = false;
        Frame diffuseOnly;
        FrameHistory h;
        Renderer(d).render(scene, FrameInput::still(scene), h, diffuseOnly);
        const auto dm = byName(diffuseOnly.stats.memory);
        CHECK(dm.count("noisy.specular") == 0);
        CHECK(dm.count("blurred.specular") == 0);
        // diffuse RGB and its history length
        CHECK(dm.at("denoisedDiffuse") + dm.at("diffuseFrames") == 4 * plane);
        CHECK(diffuseOnly.rgb(Res::DenoisedSpecular)[0].empty());
    }
    // Without a history, and without the trace, those groups are gone.
    Frame still;
    rs.trace.ssr = rs.trace.ssgi = false;
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), still);
    const auto n = byName(still.stats.memory);
    CHECK(n.count("history.denoise.guide") == 0);
    CHECK(n.count("blurred.diffuse") == 0);
    CHECK(n.count("ssr") == 0);
    CHECK(sum(n, kGBuffer) == 12 * plane);
}

TEST_CASE("memory use: a sequence takes no new memory after its second frame") {
    if (!planeMemoryUse().fromRange) return;  // (malloc's: a sanitizer's build)
    RenderSettings rs;
    rs.width = 40;
    rs.height = 24;
    rs.shadowMapSize = 64;
    rs.trace.ssgiLayout = TraceLayout::Full;  // SSGI takes the rays and march results too
    const Scene scene = makeBuiltinScene("cornell");
    FrameHistory history;
    Frame frame;
    std::size_t touched = 0;
    for (uint32_t i = 0; i < 5; ++i) {
        Renderer(rs).render(scene, FrameInput::still(scene, i), history, frame);
        // (The first frame has no history to read; from the second on, every frame frees and
        // takes the same planes in the same order, so the range's best fit gives them the
        // same blocks.)
        if (i == 1) touched = planeMemoryUse().bytesTouched;
        if (i > 1) CHECK(planeMemoryUse().bytesTouched == touched);
    }
}

TEST_CASE("memory use: a frame that shows no trace planes keeps no scratch past its last pass") {
    RenderSettings rs;
    rs.width = 40;
    rs.height = 24;
    rs.shadowMapSize = 64;
    // (As for a PNG: renderer/settings.h.)
    rs.gbufferPlanes = false;
    rs.tracePlanes = false;
    const Scene scene = makeBuiltinScene("cornell");
    Frame frame;
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), frame);
    const auto m = byName(frame.stats.memory);
    for (const char* freed : {"visibility.depth", "visibility.ids", "back.depth", "back.ids",
                              "backZ", "shadowMap", "hiz.minZ", "half.gbuffer", "half.hitLight",
                              "half.guide", "half.hiz", "half.ray.pdf", "half rays", "half march"})
        CHECK_MESSAGE(m.count(freed) == 0, freed);
    for (const char* freed : kPassScratch) CHECK_MESSAGE(m.count(freed) == 0, freed);
    CHECK(m.count("color") == 1);
}

// What a PNG frees early (its scratch after the last pass, the half frame's denoiser first) no
// later frame reads: a sequence that shows no planes keeps the image of one that shows them,
// frame after frame, at a height where the SSR resolve's ring of tile rows wraps.
TEST_CASE("memory use: a sequence that shows no planes keeps the image of one that shows them") {
    RenderSettings shown;
    shown.width = 96;
    shown.height = 300;
    shown.shadowMapSize = 128;
    RenderSettings freed = shown;
    freed.gbufferPlanes = freed.tracePlanes = freed.debugPlanes = freed.idPlanes = false;
    const Scene scene = makeBuiltinScene("cornell");
    FrameHistory ha, hb;
    Frame a, b;
    for (uint32_t i = 0; i < 3; ++i) {
        Renderer(shown).render(scene, FrameInput::still(scene, i), ha, a);
        Renderer(freed).render(scene, FrameInput::still(scene, i), hb, b);
        CAPTURE(i);
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(test::sameBits(a.rgb(Res::Color)[ch], b.rgb(Res::Color)[ch]));
            CHECK(test::sameBits(a.rgb(Res::Display)[ch], b.rgb(Res::Display)[ch]));
        }
    }
}
