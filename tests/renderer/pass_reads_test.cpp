// A pass's inputs as the frame graph declares them (renderer/pass_reads.h): a declared read
// comes back checked, an undeclared one absent; and the last frame's parts the graph declares
// are the ones the history holds.
#include "renderer/pass_reads.h"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

#include "frame_hash.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

RenderSettings small() {
    RenderSettings s;
    s.width = 96;
    s.height = 64;
    s.shadowMapSize = 256;
    s.threads = 1;
    // (The direct pass's parts stay to the frame's end, as the truth reads them.)
    s.tracePlanes = true;
    return s;
}

// A rendered single image and its graph, compiled as the renderer compiles it.
struct Rendered {
    Scene scene = makeBuiltinScene("cornell");
    RenderSettings settings = small();
    CompiledGraph graph;
    Frame frame;
    Rendered() {
        graph = compileFrameGraph({settings, SceneFacts::of(scene), false, false});
        Renderer(settings).renderWithoutHistory(scene, FrameInput::still(scene), frame);
    }
};

std::string refusal(const Frame& frame, const CompiledGraph& g, std::string_view pass) {
    try {
        const PassReads r(g, frame, pass);
    } catch (const std::logic_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("pass reads: what a pass declares comes back, what it does not is absent") {
    const Rendered r;
    REQUIRE(r.graph.runs(pass::kComposite));
    const PassReads composite(r.graph, r.frame, pass::kComposite);
    // The direct pass's parts (f16) and the denoised specular (f32), declared.
    CHECK(composite.has(Res::Direct));
    CHECK(composite.value(Res::Direct, 1).f16.data == r.frame.direct.direct[1].row(0));
    CHECK(composite.view(Res::DenoisedSpecular, 2).data ==
          r.frame.plane(Res::DenoisedSpecular, 2).row(0));
    // SSR's own signal is a layer of this frame, but the composite reads the denoiser's.
    REQUIRE_FALSE(r.frame.plane(Res::Ssr).empty());
    CHECK_FALSE(composite.has(Res::Ssr));
    CHECK_FALSE(composite.view(Res::Ssr));
    CHECK(composite.view(Res::Ssr).name == "ssr.R");
    // The G-buffer: albedo for SSGI's light, no roughness.
    const GBufferView g = composite.gbuffer();
    CHECK(g.albedo[0] == r.frame.gbuffer.albedo[0].row(0));
    CHECK(g.roughness == nullptr);
    CHECK(g.width == 96);
    // SSR reads roughness.
    CHECK(PassReads(r.graph, r.frame, pass::kSsr).gbuffer().roughness != nullptr);
    // An f16 plane is no f32 view.
    CHECK_THROWS_WITH_AS(composite.view(Res::Direct),
                         "pass 'composite' reads 'direct.R' as f32; it is f16", std::logic_error);
}

TEST_CASE("pass reads: a declared read that is missing or mis-sized is refused, naming it") {
    Rendered r;
    CHECK(refusal(r.frame, r.graph, pass::kComposite).empty());
    PlaneU16 kept = std::move(r.frame.direct.specWeight[2]);
    r.frame.direct.specWeight[2] = PlaneU16();
    CHECK(refusal(r.frame, r.graph, pass::kComposite) ==
          "pass 'composite' reads 'specWeight.B', which is missing");
    r.frame.direct.specWeight[2] = PlaneU16(48, 64);
    CHECK(refusal(r.frame, r.graph, pass::kComposite) ==
          "pass 'composite' reads 'specWeight.B', which is 48x64, not 96x64");
    r.frame.direct.specWeight[2] = std::move(kept);
    // A plane the pass does not read may be anything.
    r.frame.gbuffer.roughness = PlaneF();
    CHECK(refusal(r.frame, r.graph, pass::kComposite).empty());
    CHECK(refusal(r.frame, r.graph, pass::kSsr) ==
          "pass 'ssr' reads 'roughness', which is missing");
    // A pass the graph does not run.
    CHECK(refusal(r.frame, r.graph, "ssgi reconstruct") ==
          "pass reads: the frame graph does not run 'ssgi reconstruct'");
}

TEST_CASE("pass reads: a history holding the denoiser's part alone is not reprojected") {
    // The default preset keeps the denoiser's history and not the colour (its SSR lights hits
    // with this frame's light); a renderer that reprojects, handed that history, has no last
    // colour: its graph reads this frame's, and its image is the current radiance's.
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings current = small();
    current.tracePlanes = false;
    REQUIRE(current.trace.resolve.radiance == HitRadiance::Current);
    RenderSettings reprojected = current;
    reprojected.trace.resolve.radiance = HitRadiance::Reprojected;
    FrameHistory a, b;
    Frame fa, fb;
    FrameInput input = FrameInput::still(scene);
    Renderer(current).render(scene, input, a, fa);
    Renderer(current).render(scene, input, b, fb);
    REQUIRE_FALSE(a.usableAt(96, 64));
    REQUIRE(a.readableAt(96, 64));
    input.frameIndex = 1;
    Renderer(reprojected).render(scene, input, a, fa);
    Renderer(current).render(scene, input, b, fb);
    CHECK(test::frameHash(fa) == test::frameHash(fb));
    // Its next frame has the colour.
    CHECK(a.usableAt(96, 64));
    // SSR's reads: this frame's colour without the last one, the last one with it.
    const auto ssrReads = [&](bool lastColor, Res id) {
        GraphKey key{reprojected, SceneFacts::of(scene), true, true};
        key.lastColor = lastColor;
        const CompiledGraph g = compileFrameGraph(key);
        for (const GraphPass& p : g.passes)
            for (const Access& x : p.reads)
                if (p.decl->name == pass::kSsr && x.res == id) return true;
        return false;
    };
    CHECK(ssrReads(false, Res::Color));
    CHECK_FALSE(ssrReads(false, Res::HistoryColor));
    CHECK_FALSE(ssrReads(true, Res::Color));
    CHECK(ssrReads(true, Res::HistoryColor));
}

TEST_CASE("pass reads: SSR's mixed tracing reads the visibility ids, checked as the planes are") {
    Rendered r;
    RenderSettings mixed = r.settings;
    mixed.trace.ssrTrace = TraceMode::Mixed;
    const CompiledGraph g = compileFrameGraph({mixed, SceneFacts::of(r.scene), false, false});
    // On screen SSR has no ids to read; mixed, it has them, the frame's own.
    CHECK_FALSE(PassReads(r.graph, r.frame, pass::kSsr).ids(Res::VisibilityIds));
    r.frame.scratch.visibility.ids = PlaneU32();
    CHECK(refusal(r.frame, g, pass::kSsr) == "pass 'ssr' reads 'visibility.ids', which is missing");
    r.frame.scratch.visibility.ids = PlaneU32(96, 32);
    CHECK(refusal(r.frame, g, pass::kSsr) ==
          "pass 'ssr' reads 'visibility.ids', which is 96x32, not 96x64");
    r.frame.scratch.visibility.ids = PlaneU32(96, 64);
    const ViewU32 ids = PassReads(g, r.frame, pass::kSsr).ids(Res::VisibilityIds);
    CHECK(ids.data == r.frame.scratch.visibility.ids.row(0));
    CHECK(ids.name == "visibility.ids");
}
