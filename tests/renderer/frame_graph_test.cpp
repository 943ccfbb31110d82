// The frame graph (renderer/frame_graph.h): compiled from the declarations, its outputs are a
// rendered frame's layers, name for name, over presets, switches, layouts and scenes; culling
// removes what the settings turn off; transient memory is shared only between lifetimes that
// do not overlap.
#include "renderer/frame_graph.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "core/pixel_formats.h"
#include "material_maps.h"
#include "plane_compare.h"
#include "renderer/quality.h"
#include "renderer/renderer.h"
#include "renderer/trace_pass.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

std::vector<std::string> frameLayerNames(const Frame& f) {
    std::vector<std::string> out;
    for (const PlaneRef& p : f.layers()) out.emplace_back(p.name);
    return out;
}

RenderSettings small(Quality q) {
    RenderSettings s;
    applyQuality(q, s);
    s.width = 36;
    s.height = 20;
    s.shadowMapSize = 64;
    s.threads = 1;
    return s;
}

// Every pixel of every layer a number: the planes are NaN before the render below.
bool allFinite(const Frame& f) {
    for (const PlaneRef& p : f.layers())
        for (int y = 0; y < p.plane->height(); ++y)
            for (int x = 0; x < p.plane->width(); ++x)
                if (!std::isfinite(p.plane->at(x, y))) {
                    MESSAGE("layer " << p.name << " not written at " << x << ", " << y);
                    return false;
                }
    return true;
}

// The denoiser's passes the graph runs, as `--stats` names them: the half frame's under the
// full one's name, the upsample inside the composite as its own line.
std::set<std::string> denoiserPasses(const CompiledGraph& g) {
    std::set<std::string> out;
    for (const GraphPass& p : g.passes) {
        std::string name(p.decl->name);
        if (name.rfind("denoise ", 0) != 0) continue;
        const std::size_t half = name.find(" (half)");
        if (half != std::string::npos) name.erase(half);
        out.insert(name);
    }
    if (g.runs(pass::kComposite) && g.find(Res::HalfDenoised) &&
        g.find(Res::HalfDenoised)->last == int(g.passes.size()) - 1)
        out.insert("denoise upsample");
    return out;
}

// The denoiser's passes a frame timed.
std::set<std::string> timedDenoiserPasses(const FrameStats& stats) {
    std::set<std::string> out;
    for (const PassTime& p : stats.passes)
        if (p.name.rfind("denoise ", 0) == 0) out.insert(p.name);
    return out;
}

// How a frame meets its history: none (a single image), the first of a sequence (nothing to
// read, its own kept), a middle one (read and kept), the last one (read, not replaced).
struct HistoryCase {
    bool read, keep;
};
constexpr HistoryCase kHistoryCases[] = {
    {false, false}, {false, true}, {true, true}, {true, false}};

// Renders a frame as `hc` says and checks that the graph's outputs are its layers; then
// renders it again into the same Frame, its planes kept (Frame reuses them) but filled with
// NaN first, and checks that every pixel of every layer was written: the graph makes no
// plane that no pass fills, and no pass reads a plane of the frame before a pass writes it.
void checkLayers(const RenderSettings& s, const Scene& scene, HistoryCase hc) {
    const CompiledGraph g = compileFrameGraph({s, SceneFacts::of(scene), hc.read, hc.keep});
    Frame frame;
    const Renderer renderer(s);
    FrameHistory h;
    const auto render = [&](uint32_t index) {
        if (!hc.read && !hc.keep) {
            renderer.renderWithoutHistory(scene, FrameInput::still(scene, index), frame);
            return;
        }
        if (hc.read) {  // a first frame to read
            FrameInput first = FrameInput::still(scene, index + 100);
            renderer.render(scene, first, h, frame);
        }
        FrameInput in = FrameInput::still(scene, index);
        in.replaceHistory = hc.keep;
        renderer.render(scene, in, h, frame);
    };
    render(0);
    CHECK(g.layerNames() == frameLayerNames(frame));
    CHECK(denoiserPasses(g) == timedDenoiserPasses(frame.stats));
    for (const PlaneRef& p : frame.layers())
        const_cast<PlaneF*>(p.plane)->fill(std::numeric_limits<float>::quiet_NaN());
    frame.direct.forEachPlane([](std::string_view, PlaneU16& p) {
        if (!p.empty()) p.fill(encodeF16(std::numeric_limits<float>::quiet_NaN()));
    });
    h = FrameHistory();
    render(1);
    CHECK(allFinite(frame));
}

bool anyNamed(const CompiledGraph& g, const std::string& part) {
    const auto lower = [](std::string s) {
        for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    for (const GraphResource& r : g.resources)
        if (lower(std::string(resourceDecl(r.id).name)).find(part) != std::string::npos)
            return true;
    for (const GraphPass& p : g.passes)
        if (lower(std::string(p.decl->name)).find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("frame graph: the resource table is in Res order, with channel names") {
    for (int r = 0; r < kResourceCount; ++r) CHECK(int(resourceDecl(Res(r)).id) == r);
    CHECK(resourceDecl(Res::Normal).channelNames() ==
          std::vector<std::string>{"normal.X", "normal.Y", "normal.Z"});
    CHECK(resourceDecl(Res::ViewZ).channelNames() == std::vector<std::string>{"viewZ"});
}

TEST_CASE("frame graph: the frame's plane groups are named from the resource table") {
    Frame f;
    FrameHistory h;
    int planes = 0;
    const auto known = [&](std::string_view name, const auto&) {
        ++planes;
        CHECK(resourceOfChannel(name) != Res::Count);
    };
    f.forEachPlane(known);
    h.forEachPlane(known);
    CHECK(planes == 7 + 12 + 4 + 2 + 18 + 7 + 6 + 8 + 6);
    CHECK(channelName(Res::Normal, 2) == "normal.Z");
    PlaneF two[2];
    const auto none = [](std::string_view, PlaneF&) {};
    CHECK_THROWS_AS(forEachChannel(Res::Normal, two, none), std::logic_error);
}

TEST_CASE("frame graph: its outputs are the rendered frame's layers") {
    Scene cornell = makeBuiltinScene("cornell");
    Scene textured = makeBuiltinScene("cornell");
    test::addMaterialMaps(textured);
    Scene emissive = makeBuiltinScene("cornell");
    emissive.materials[0].emissive = glm::vec3(2.0f);
    const Scene* scenes[] = {&cornell, &textured, &emissive};
    for (int q = 0; q < kQualityCount; ++q)
        for (const Scene* scene : scenes)
            for (int variant = 0; variant < 12; ++variant) {
                RenderSettings s = small(Quality(q));
                switch (variant) {
                    case 1: s.debugPlanes = false; break;
                    case 2: s.idPlanes = false, s.debugPlanes = false; break;
                    case 3: s.trace.ssr = false; break;
                    case 4: s.trace.ssgi = false, s.debugPlanes = false; break;
                    case 5: s.trace.ssr = s.trace.ssgi = false; break;
                    case 6: s.trace.denoise.enabled = false, s.debugPlanes = false; break;
                    case 7:
                        s.trace.ssgiLayout = TraceLayout::Checkerboard;
                        s.trace.ssrLayout = TraceLayout::Full;
                        s.debugPlanes = false;
                        break;
                    case 8:
                        s.trace.ssgiFeedback = !s.trace.ssgiFeedback;
                        s.trace.resolve.mode = SsrResolveMode::Reuse;
                        break;
                    case 9:
                        s.trace.ssgiLayout = TraceLayout::Full;
                        s.trace.marcher = Marcher::Linear;
                        s.trace.march.backFaces = !s.trace.march.backFaces;
                        s.debugPlanes = false;
                        break;
                    case 10: s.gbufferPlanes = false; break;  // a PNG's frame
                    case 11:
                        s.tracePlanes = s.debugPlanes = s.idPlanes = s.gbufferPlanes = false;
                        break;
                    default: break;
                }
                for (const HistoryCase hc : kHistoryCases) {
                    CAPTURE(q);
                    CAPTURE(variant);
                    CAPTURE(hc.read);
                    CAPTURE(hc.keep);
                    CAPTURE(scene == &textured);
                    checkLayers(s, *scene, hc);
                }
            }
}

TEST_CASE("frame graph: a pass the settings turn off takes its resources with it") {
    const SceneFacts facts = SceneFacts::of(makeBuiltinScene("cornell"));
    RenderSettings s = small(Quality::Medium);
    REQUIRE(anyNamed(compileFrameGraph({s, facts, true}), "ssr"));
    s.trace.ssr = false;
    const CompiledGraph noSsr = compileFrameGraph({s, facts, true});
    CHECK_FALSE(anyNamed(noSsr, "ssr"));
    CHECK_FALSE(noSsr.has(Res::DenoisedSpecular));
    CHECK(noSsr.has(Res::DenoisedDiffuse) != diffuseUpsampledInComposite(s));
    // Planes only looked at: made when asked for, culled otherwise; the traced signals the
    // denoiser reads stay, as transients.
    s = small(Quality::Medium);
    s.trace.ssgiLayout = TraceLayout::Full;
    CHECK(compileFrameGraph({s, facts, true}).has(Res::SsrSteps));
    s.debugPlanes = false;
    const CompiledGraph lean = compileFrameGraph({s, facts, true});
    CHECK_FALSE(lean.has(Res::SsrSteps));
    CHECK_FALSE(lean.has(Res::SpecularFrames));
    REQUIRE(lean.has(Res::Ssr));
    CHECK(lean.find(Res::Ssr)->lifetime == Lifetime::Transient);
    // A single image has no history: nothing of it, and no commit.
    const CompiledGraph single = compileFrameGraph({s, facts, false, false});
    CHECK(single.historyBytes == 0);
    // The last frame of a sequence reads the history and keeps none: no commit.
    CHECK_FALSE(compileFrameGraph({s, facts, true, false}).runs("history commit"));
    for (const GraphResource& r : single.resources) CHECK(r.lifetime != Lifetime::History);
    CHECK_FALSE(anyNamed(single, "history commit"));
    s.trace.ssgiFeedback = true;  // (the next frame reads this one's diffuse light)
    CHECK(anyNamed(compileFrameGraph({s, facts, true}), "history commit"));
    CHECK(compileFrameGraph({s, facts, true}).has(Res::HistoryDiffuse));
}

TEST_CASE("frame graph: a frame without history runs no temporal pass, one with either does") {
    const Scene scene = makeBuiltinScene("cornell");
    const SceneFacts facts = SceneFacts::of(scene);
    for (const TraceLayout layout : {TraceLayout::Half, TraceLayout::Full}) {
        CAPTURE(int(layout));
        RenderSettings s = small(Quality::Medium);
        s.trace.ssgiLayout = layout;
        const bool half = layout == TraceLayout::Half;
        for (const HistoryCase hc : kHistoryCases) {
            CAPTURE(hc.read);
            CAPTURE(hc.keep);
            const CompiledGraph g = compileFrameGraph({s, facts, hc.read, hc.keep});
            const bool history = hc.read || hc.keep;
            CHECK(g.runs(pass::kDenoiseTemporal) == history);
            CHECK(g.runs(pass::kDenoiseTemporalHalf) == (history && half));
        }
        // The renderer obeys: a single image times no temporal pass, while a sequence's last
        // frame, which reads the denoiser's history (the preset keeps no colour), does.
        const Renderer renderer(s);
        Frame single;
        renderer.renderWithoutHistory(scene, FrameInput::still(scene, 0), single);
        CHECK_FALSE(timedDenoiserPasses(single.stats).count("denoise temporal"));
        FrameHistory h;
        Frame frame;
        renderer.render(scene, FrameInput::still(scene, 0), h, frame);
        FrameInput last = FrameInput::still(scene, 1);
        last.replaceHistory = false;
        renderer.render(scene, last, h, frame);
        CHECK(timedDenoiserPasses(frame.stats).count("denoise temporal"));
    }
}

TEST_CASE("frame graph: the pre-blur runs where a prepass radius asks for it") {
    const SceneFacts facts = SceneFacts::of(makeBuiltinScene("cornell"));
    RenderSettings s = small(Quality::Medium);
    s.trace.ssgiLayout = TraceLayout::Full;
    const CompiledGraph medium = compileFrameGraph({s, facts, true});
    CHECK_FALSE(medium.runs("denoise pre-blur"));
    // The front end then hands its output straight to the temporal pass, at the pixel: one chain.
    REQUIRE(medium.runs("denoise temporal"));
    const auto chainOf = [](const CompiledGraph& g, std::string_view name) {
        for (const GraphPass& p : g.passes)
            if (p.decl->name == name) return p.chain;
        return -1;
    };
    CHECK(chainOf(medium, "denoise front end") == chainOf(medium, "denoise temporal"));
    s.trace.denoise.specularPrepassRadius = 50.0f;
    const CompiledGraph specular = compileFrameGraph({s, facts, true});
    CHECK(specular.runs("denoise pre-blur"));
    CHECK(chainOf(specular, "denoise front end") != chainOf(specular, "denoise temporal"));
}

TEST_CASE("frame graph: transients share memory only where their lifetimes do not overlap") {
    const SceneFacts facts = SceneFacts::of(makeBuiltinScene("cornell"));
    for (int q = 0; q < kQualityCount; ++q) {
        const CompiledGraph g = compileFrameGraph({small(Quality(q)), facts, true});
        std::size_t sum = 0, highest = 0;
        for (const GraphResource& a : g.resources) {
            if (a.lifetime != Lifetime::Transient) {
                CHECK(a.offsets.empty());
                continue;
            }
            sum += a.bytes;
            REQUIRE(a.offsets.size() == std::size_t(resourceDecl(a.id).channelCount()));
            const std::size_t aPlane = a.bytes / a.offsets.size();
            for (std::size_t at : a.offsets) highest = std::max(highest, at + aPlane);
            for (const GraphResource& b : g.resources) {
                if (&a == &b || b.offsets.empty()) continue;
                const std::size_t bPlane = b.bytes / b.offsets.size();
                for (std::size_t x : a.offsets)
                    for (std::size_t y : b.offsets)
                        if (x < y + bPlane && y < x + aPlane) {  // their bytes overlap
                            CAPTURE(resourceDecl(a.id).name);
                            CAPTURE(resourceDecl(b.id).name);
                            CHECK((a.last < b.first || b.last < a.first));
                        }
            }
            // (A resource's own planes never overlap.)
            for (std::size_t i = 0; i < a.offsets.size(); ++i)
                for (std::size_t j = i + 1; j < a.offsets.size(); ++j)
                    CHECK((a.offsets[i] + aPlane <= a.offsets[j] ||
                           a.offsets[j] + aPlane <= a.offsets[i]));
        }
        CHECK(g.transientBytes == highest);
        CHECK(g.transientBytes < sum);  // some memory is shared
        CHECK(g.totalBytes() == g.transientBytes + g.outputBytes + g.historyBytes);
    }
}

TEST_CASE(
    "frame graph: a pass joins a chain only when it reads the chain's resources at its pixel") {
    const SceneFacts facts = SceneFacts::of(makeBuiltinScene("cornell"));
    const CompiledGraph g = compileFrameGraph({small(Quality::Medium), facts, true});
    for (std::size_t i = 1; i < g.passes.size(); ++i) {
        if (g.passes[i].chain != g.passes[i - 1].chain) continue;
        // Everything it reads that its chain wrote, it reads at its own pixel.
        for (const Access& r : g.passes[i].reads)
            for (std::size_t j = i; j-- > 0 && g.passes[j].chain == g.passes[i].chain;)
                for (const Access& w : g.passes[j].writes)
                    if (w.res == r.res) CHECK(r.footprint == Footprint::Pixel);
    }
    // No pass joins a chain that read around its pixel what the pass writes: SSR reads the
    // colour anywhere, which the composite overwrites (here in what would be one chain).
    RenderSettings s = small(Quality::Medium);
    s.trace.denoise.enabled = false;
    s.trace.ssgi = false;
    s.trace.ssrLayout = TraceLayout::Full;
    const CompiledGraph raw = compileFrameGraph({s, facts, false, false});
    const auto chainOf = [](const CompiledGraph& cg, std::string_view name) {
        for (const GraphPass& p : cg.passes)
            if (p.decl->name == name) return p.chain;
        return -1;
    };
    REQUIRE(raw.runs("ssr"));
    CHECK(chainOf(raw, "ssr") != chainOf(raw, "composite"));
    for (std::size_t i = 1; i < raw.passes.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) {
            if (raw.passes[j].chain != raw.passes[i].chain) continue;
            for (const Access& r : raw.passes[j].reads)
                if (r.footprint != Footprint::Pixel)
                    for (const Access& w : raw.passes[i].writes) CHECK(w.res != r.res);
        }
    // The denoiser's spatial passes read their neighbours: each runs in a loop after the one of
    // the pass that made what it reads.
    const auto chainOfPass = [&](std::string_view name) {
        for (const GraphPass& p : g.passes)
            if (p.decl->name == name) return p.chain;
        return -1;
    };
    REQUIRE(chainOfPass("denoise blur") >= 0);
    CHECK(chainOfPass("denoise blur") != chainOfPass("denoise history fix"));
    CHECK(chainOfPass("denoise post-blur") != chainOfPass("denoise blur"));
}

TEST_CASE("frame graph: DOT output names every pass and resource") {
    const CompiledGraph g = compileFrameGraph(
        {small(Quality::Medium), SceneFacts::of(makeBuiltinScene("cornell")), true});
    const std::string dot = frameGraphDot(g);
    CHECK(dot.rfind("digraph frame {", 0) == 0);
    for (const GraphPass& p : g.passes)
        CHECK(dot.find(std::string(p.decl->name)) != std::string::npos);
    for (const GraphResource& r : g.resources)
        CHECK(dot.find("\"" + std::string(resourceDecl(r.id).name) + "\\n") != std::string::npos);
}

// The frame's memory follows the graph's lifetimes (renderer/frame_memory.h): with every plane
// that goes back to the pool filled with NaN, no pass reads one after its last declared pass
// or before its first, and the image keeps its bits.
TEST_CASE("frame graph: no pass reads a plane outside the lifetime the graph gives it") {
    const Scene scene = makeBuiltinScene("cornell");
    for (int q = 0; q < kQualityCount; ++q)
        for (int variant = 0; variant < 3; ++variant) {
            RenderSettings s = small(Quality(q));
            if (variant >= 1) s.gbufferPlanes = s.tracePlanes = s.debugPlanes = s.idPlanes = false;
            if (variant == 2) s.trace.ssgiLayout = TraceLayout::Full;
            CAPTURE(q);
            CAPTURE(variant);
            const Renderer renderer(s);
            Frame plain, poisoned;
            FrameHistory hp, hq;
            poisoned.scratch.pool.poison(std::numeric_limits<float>::quiet_NaN());
            for (uint32_t i = 0; i < 3; ++i) {  // a first frame, then two with history
                renderer.render(scene, FrameInput::still(scene, i), hp, plain);
                renderer.render(scene, FrameInput::still(scene, i), hq, poisoned);
                const std::vector<PlaneRef> a = plain.layers(), b = poisoned.layers();
                REQUIRE(a.size() == b.size());
                for (std::size_t k = 0; k < a.size(); ++k) {
                    CAPTURE(a[k].name);
                    CHECK(test::sameBits(*a[k].plane, *b[k].plane));
                }
            }
        }
}
