// The --stats memory table (renderer/memory_use.h): every group that holds memory, with the
// bytes its planes hold, and nothing a frame does not hold.
#include "renderer/memory_use.h"

#include <doctest/doctest.h>

#include <map>
#include <string>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

std::map<std::string, std::size_t> byName(const std::vector<MemoryUse>& rows) {
    std::map<std::string, std::size_t> m;
    for (const MemoryUse& r : rows) {
        CHECK(m.count(r.name) == 0);  // each group once
        CHECK(r.bytes > 0);           // empty groups are left out
        m[r.name] = r.bytes;
    }
    return m;
}

}  // namespace

TEST_CASE("memory use: each group's planes, the denoiser's shared ping-pong scratch") {
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
    CHECK(m.at("image") == 7 * plane);
    CHECK(m.at("gbuffer") == 12 * plane);
    CHECK(m.at("ssr") == 7 * plane);
    // direct, sky specular and its weight, SSGI's hit light: no sky diffuse (SSGI's light
    // replaces it), no emission (nothing in cornell emits).
    CHECK(m.at("direct parts") == 12 * plane);
    CHECK(m.at("denoised") == 8 * plane);
    // Between frames the pool holds the scratch that passes hand on: the SSR resolve's 9 (hit
    // radiance 3, fade, target 3, and the pdf and hits its tile chain copies out of the tiles'
    // batches: trace/tile_chain.h; no frame of rays or march results), whose blocks the
    // full-resolution denoiser's scratch takes (the specular signal's alone: noisy 4, ping 4,
    // pong 4 and fast in f16, signalZ and frames in f32 = 15, not a group per pass; an f16
    // plane takes a whole f32 block where one is free, else half of one: core/plane_pool.h),
    // and the half-resolution denoiser's 15 (the diffuse's, on the half frame: SSGI's half
    // layout; a 20x12 plane is 32 elements a row).
    const std::size_t halfPlane = 32 * 12 * sizeof(float);
    const std::size_t plane16 = plane / 2, halfPlane16 = halfPlane / 2;
    REQUIRE(PlaneU16(40, 24).bytes() == plane16);
    const std::size_t slack = 64;  // a 16-bit plane's block (core/image.cpp)
    CHECK(frame.scratch.pool.size() == 30);
    CHECK(m.at("pooled scratch") >=
          13 * (plane16 + slack) + 2 * plane + 13 * (halfPlane16 + slack) + 2 * halfPlane);
    CHECK(m.at("pooled scratch") <= 15 * plane + 15 * halfPlane);
    for (const char* pooled :
         {"rays", "march", "ssr resolve", "denoise scratch", "half denoise scratch"})
        CHECK(m.count(pooled) == 0);
    // The denoiser's history: the guides (viewZ, normal 3, roughness) and frames in f32, the
    // signal 4 and fast in f16.
    CHECK(m.at("denoise history") == 6 * plane + 5 * plane16);
    CHECK(m.count("half denoise history") == 1);
    CHECK(m.at("shadow map") == 64 * 64 * sizeof(float));
    // (The colour history only where a setting reads it: not by default.)
    CHECK(m.count("history") == 0);
    // SSR off: the full-resolution denoiser has no signal and does not run; the diffuse is
    // denoised on the half frame and still reaches the frame.
    {
        RenderSettings d = rs;
        d.trace.ssr = false;
        Frame diffuseOnly;
        FrameHistory h;
        Renderer(d).render(scene, FrameInput::still(scene), h, diffuseOnly);
        const auto dm = byName(diffuseOnly.stats.memory);
        CHECK(dm.count("denoise scratch") == 0);
        // The half denoiser's alone.
        CHECK(diffuseOnly.scratch.pool.size() == 15);
        CHECK(dm.at("pooled scratch") >= 13 * (halfPlane16 + slack) + 2 * halfPlane);
        CHECK(dm.at("pooled scratch") <= 15 * halfPlane);
        CHECK(dm.at("denoised") == 4 * plane);  // diffuse RGB and its history length
        CHECK(diffuseOnly.trace.denoise.out.specular[0].empty());
    }
    // Without a history, and without the trace, those groups are gone.
    Frame still;
    rs.trace.ssr = rs.trace.ssgi = false;
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), still);
    const auto n = byName(still.stats.memory);
    CHECK(n.count("denoise history") == 0);
    CHECK(n.count("denoise scratch") == 0);
    CHECK(n.count("ssr") == 0);
    CHECK(n.at("gbuffer") == 12 * plane);
}

TEST_CASE("memory use: a sequence's pooled scratch is allocated in its first frame only") {
    RenderSettings rs;
    rs.width = 40;
    rs.height = 24;
    rs.shadowMapSize = 64;
    rs.trace.ssgiLayout = TraceLayout::Full;  // SSGI takes the rays and march results too
    const Scene scene = makeBuiltinScene("cornell");
    FrameHistory history;
    Frame frame;
    std::size_t first = 0, firstBytes = 0;
    for (uint32_t i = 0; i < 4; ++i) {
        Renderer(rs).render(scene, FrameInput::still(scene, i), history, frame);
        // (The pool frees nothing at one size: a plane allocated later would grow it. Its
        // blocks change hands between f32 and f16 planes without being freed; which of its f16
        // planes hold f32 blocks settles after the first frame, the one without a history.)
        if (i == 0) first = frame.scratch.pool.size();
        if (i == 1) firstBytes = frame.scratch.pool.bytes();
        CHECK(frame.scratch.pool.size() == first);
        if (i > 1) CHECK(frame.scratch.pool.bytes() == firstBytes);
    }
    CHECK(first > 0);
    // (Both signals at full resolution: the denoiser's 22 planes, 18 of them f16, in the
    // blocks of SSR's 20 and new ones.)
    CHECK(first == 22);
    // Another size frees the pooled planes of the old one.
    rs.width = 32;
    Renderer(rs).render(scene, FrameInput::still(scene, 4), history, frame);
    CHECK(frame.scratch.pool.size() == first);
    CHECK(frame.scratch.pool.bytes() >=
          18 * (PlaneU16(32, 24).bytes() + 64) + 4 * PlaneF(32, 24).bytes());
    CHECK(frame.scratch.pool.bytes() <= first * PlaneF(32, 24).bytes());
}
