// The frame's name tables (renderer/frame.h): the layers a render hands out, in file order,
// found by name; groups the settings leave out are no layers; a reused Frame follows the
// settings it is rendered with.
#include "renderer/frame.h"

#include <doctest/doctest.h>

#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "plane_compare.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

RenderSettings tiny() {
    RenderSettings rs;
    rs.width = 24;
    rs.height = 16;
    rs.shadowMapSize = 32;
    return rs;
}

std::vector<std::string> layerNames(const Frame& f) {
    std::vector<std::string> names;
    for (const PlaneRef& p : f.layers()) names.emplace_back(p.name);
    return names;
}

}  // namespace

TEST_CASE("frame: the layers are the groups' tables in file order, each found by name") {
    const Scene scene = makeBuiltinScene("cornell");
    const Frame f = Renderer(tiny()).renderWithoutHistory(scene);
    // The EXR channel order ssrt has always written (golden files depend on it).
    const std::vector<std::string> want = {"color.R",
                                           "color.G",
                                           "color.B",
                                           "display.R",
                                           "display.G",
                                           "display.B",
                                           "shadow",
                                           "viewZ",
                                           "normal.X",
                                           "normal.Y",
                                           "normal.Z",
                                           "albedo.R",
                                           "albedo.G",
                                           "albedo.B",
                                           "metallic",
                                           "roughness",
                                           "materialId",
                                           "motion.X",
                                           "motion.Y",
                                           "instanceId",
                                           "triangleId",
                                           "ssr.R",
                                           "ssr.G",
                                           "ssr.B",
                                           "ssrOpacity",
                                           "ssrHit",
                                           "ssrHitDistance",
                                           "ssrSteps",
                                           "ssgi.R",
                                           "ssgi.G",
                                           "ssgi.B",
                                           "ssgiHit",
                                           "ssgiHitDistance",
                                           "ssgiSteps",
                                           "denoisedDiffuse.R",
                                           "denoisedDiffuse.G",
                                           "denoisedDiffuse.B",
                                           "denoisedSpecular.R",
                                           "denoisedSpecular.G",
                                           "denoisedSpecular.B",
                                           "diffuseFrames",
                                           "specularFrames"};
    CHECK(layerNames(f) == want);
    // plane(name) is the member the table names.
    CHECK(&f.plane("viewZ") == &f.gbuffer.viewZ);
    CHECK(&f.plane("normal.Z") == &f.gbuffer.normal[2]);
    CHECK(&f.plane("display.B") == &f.rgb(Res::Display)[2]);
    CHECK(&f.plane("ssrHitDistance") == &f.plane(Res::SsrHitDistance));
    CHECK(&f.plane("ssgiSteps") == &f.plane(Res::SsgiSteps));
    CHECK(&f.plane("triangleId") == &f.gbuffer.triangleId);
    for (const PlaneRef& p : f.layers()) {
        CAPTURE(std::string(p.name));
        CHECK(p.plane->width() == f.width);
        CHECK(&f.plane(p.name) == p.plane);
    }
    CHECK_THROWS_AS(f.plane("nope"), std::out_of_range);
    // The direct parts are no layers.
    CHECK_FALSE(f.has("direct.R"));
    CHECK(f.direct.direct[0].width() == f.width);
}

TEST_CASE("frame: groups the settings leave out are empty, also in a reused frame") {
    const Scene scene = makeBuiltinScene("cornell");
    Frame f = Renderer(tiny()).renderWithoutHistory(scene);
    REQUIRE(f.has("ssr.R"));
    RenderSettings less = tiny();
    less.trace.ssr = false;
    less.idPlanes = false;
    Renderer(less).renderWithoutHistory(scene, FrameInput::still(scene), f);
    CHECK_FALSE(f.has("ssr.R"));
    CHECK_FALSE(f.has("instanceId"));
    CHECK(f.has("ssgi.R"));
    CHECK(f.rgb(Res::Ssr)[0].empty());
    CHECK(f.direct.hitLight[0].width() == f.width);  // SSGI still reads it
    less.trace.ssgi = false;
    Renderer(less).renderWithoutHistory(scene, FrameInput::still(scene), f);
    CHECK(layerNames(f).size() == 19);  // image and G-buffer alone
    CHECK(f.direct.direct[0].empty());
    // Names are unique across every table, the history's and the parts' included.
    std::set<std::string> names;
    int count = 0;
    const auto add = [&](std::string_view n, const auto&) {
        names.emplace(n);
        ++count;
    };
    f.forEachPlane(add);
    FrameHistory().forEachPlane(add);
    CHECK(int(names.size()) == count);
}

namespace {

using test::sameBits;

// The layers of `without` are those of `with` but `debug`, with the same bits.
void checkWithoutDebugPlanes(const Frame& with, const Frame& without,
                             const std::set<std::string>& debug) {
    std::set<std::string> missing;
    for (const PlaneRef& p : with.layers()) {
        CAPTURE(std::string(p.name));
        if (!without.has(p.name)) missing.emplace(p.name);
        else CHECK(sameBits(*p.plane, without.plane(p.name)));
    }
    CHECK(missing == debug);
    CHECK(without.layers().size() + debug.size() == with.layers().size());
}

}  // namespace

TEST_CASE("frame: without the debug planes the others keep their bits, along a sequence") {
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings plain = tiny();
    plain.debugPlanes = false;
    FrameHistory h1, h2;
    Frame with, without;
    // The default preset: SSGI at half resolution, denoised there; SSR in a checkerboard.
    REQUIRE(plain.trace.ssgiLayout == TraceLayout::Half);
    for (uint32_t i = 0; i < 3; ++i) {
        Renderer(tiny()).render(scene, FrameInput::still(scene, i), h1, with);
        Renderer(plain).render(scene, FrameInput::still(scene, i), h2, without);
        // (The denoised diffuse at full resolution too: without a file to show it, the
        // composite upsamples the half frame's tile by tile, diffuseUpsampledInComposite; and
        // SSR's planes, pooled once the denoiser has read them, tracedSignalsPooled.)
        checkWithoutDebugPlanes(
            with, without,
            {"ssgi.R", "ssgi.G", "ssgi.B", "ssgiHit", "ssgiHitDistance", "ssgiSteps", "ssrSteps",
             "diffuseFrames", "specularFrames", "denoisedDiffuse.R", "denoisedDiffuse.G",
             "denoisedDiffuse.B", "ssr.R", "ssr.G", "ssr.B", "ssrOpacity", "ssrHit",
             "ssrHitDistance"});
    }
}

TEST_CASE("frame: without the denoiser the full-resolution SSGI is no debug plane") {
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings rs = tiny();
    rs.trace.denoise.enabled = false;
    RenderSettings plain = rs;
    plain.debugPlanes = false;
    const Frame with = Renderer(rs).renderWithoutHistory(scene);
    const Frame without = Renderer(plain).renderWithoutHistory(scene);
    checkWithoutDebugPlanes(with, without, {"ssrSteps", "ssgiSteps"});
}

TEST_CASE("frame: extra layers follow the renderer's") {
    const Scene scene = makeBuiltinScene("cornell");
    Frame f = Renderer(tiny()).renderWithoutHistory(scene);
    const std::size_t n = f.layers().size();
    f.extraLayers.push_back({"ref.color.R", PlaneF(f.width, f.height, 0.5f)});
    const std::vector<PlaneRef> layers = f.layers();
    REQUIRE(layers.size() == n + 1);
    CHECK(layers.back().name == "ref.color.R");
    CHECK(f.plane("ref.color.R").at(0, 0) == 0.5f);
}

TEST_CASE("frame: the G-buffer's plane names are its resources' channels, one for one") {
    // core/gbuffer_view.h names the planes; the resource table names the G-buffer's layers and
    // the groups of G-buffer planes the half frame and the denoiser's history hold. Each plane
    // is one channel of a G-buffer layer, and every channel of those layers is a plane.
    std::set<std::string> planes, channels;
    for (int i = 0; i < kGBufferPlaneCount; ++i) {
        const std::string name(gbufferPlaneName(GBufferPlane(1u << i)));
        CAPTURE(name);
        const Res res = resourceOfChannel(name);
        REQUIRE(res != Res::Count);
        CHECK(resourceDecl(res).group == LayerGroup::GBuffer);
        planes.insert(name);
    }
    for (int r = 0; r < kResourceCount; ++r)
        if (resourceDecl(Res(r)).lifetime == Lifetime::Output &&
            resourceDecl(Res(r)).group == LayerGroup::GBuffer)
            for (const std::string& c : resourceDecl(Res(r)).channelNames()) {
                // (a layer's channels are its name, or its name and a suffix)
                const std::string layer(resourceDecl(Res(r)).name);
                CHECK((c == layer || c.starts_with(layer + ".")));
                channels.insert(c);
            }
    CHECK(planes == channels);
    // A group's channels are its name and its planes' names, in the G-buffer's order.
    CHECK(resourceDecl(Res::HalfGuides).channelNames() ==
          std::vector<std::string>{"half.guide.viewZ", "half.guide.normal.X", "half.guide.normal.Y",
                                   "half.guide.normal.Z", "half.guide.motion.X",
                                   "half.guide.motion.Y"});
    CHECK(resourceDecl(Res::DenoiseHistoryGuides).channelCount() == 5);
}
