#include "renderer/renderer.h"

#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/tiles.h"
#include "raster/back_depth.h"
#include "raster/raster.h"
#include "raster/resolve_kernel.h"
#include "raster/shadow_map.h"
#include "renderer/direct_lighting.h"
#include "renderer/frame_graph.h"
#include "renderer/frame_memory.h"
#include "renderer/frame_scheduler.h"
#include "renderer/memory_use.h"
#include "renderer/pass_reads.h"
#include "renderer/pass_timer.h"
#include "renderer/resolve_tables.h"
#include "renderer/sky_lighting.h"
#include "renderer/texture_pass.h"
#include "renderer/trace_pass.h"
#include "shading/direct_kernel.h"
#include "trace/trace_layout.h"

namespace ssrt {

namespace {

// What every pass of one frame shares.
struct FrameContext {
    const RenderSettings& settings;
    const CompiledGraph& graph;  // which passes run, which planes exist
    const Camera& camera;
    Isa isa;
    int threads;
    TileGrid grid;
    glm::vec3 origin;  // Scene::origin(): every world position below is measured from it
    glm::mat4 view, proj, prevViewProj;
    TraceCamera trace;  // the camera as the kernels take it (tanHalf*, near, far, rotation)

    FrameContext(const RenderSettings& s, const CompiledGraph& g, const Scene& scene,
                 const FrameInput& input)
        : settings(s),
          graph(g),
          camera(input.camera),
          isa(resolveIsa(s.isa)),
          threads(s.threads),
          grid(s.width, s.height) {
        const float aspect = float(s.width) / float(s.height);
        const Bounds bounds = scene.bounds();  // one pass over the vertices for both facts
        origin = bounds.centre();
        view = camera.viewFrom(origin);
        proj = camera.projection(aspect);
        prevViewProj =
            input.previousCamera.projection(aspect) * input.previousCamera.viewFrom(origin);
        trace.width = s.width;
        trace.height = s.height;
        trace.tanHalfY = std::tan(glm::radians(camera.fovY) * 0.5f);
        trace.tanHalfX = trace.tanHalfY * aspect;
        trace.nearZ = camera.nearZ;
        trace.farZ = camera.farZ;
        const glm::mat3 viewToWorld = glm::mat3(glm::inverse(view));
        std::copy_n(glm::value_ptr(viewToWorld), 9, trace.viewToWorld);
        const glm::vec3 position(glm::dvec3(camera.position) - glm::dvec3(origin));
        std::copy_n(glm::value_ptr(position), 3, trace.position);
        std::copy_n(glm::value_ptr(origin), 3, trace.origin);
        trace.sceneDiagonal = bounds.diagonal();
    }
    RasterOptions raster() const {
        RasterOptions ro;
        ro.isa = isa;
        ro.threads = threads;
        return ro;
    }
};

// The back-face layer's own buffers, which the frame memory does not hold: emptied when the
// graph has no back faces.
void dropBackFaces(const CompiledGraph& graph, Frame& f) {
    if (!graph.has(Res::BackZ)) f.scratch.backVisibility = {}, f.scratch.backZ = PlaneF();
}

void shadowPass(const FrameContext& c, const Scene& scene, Frame& frame) {
    const ScopedPass timer(frame.stats, "shadow");
    renderShadowMap(scene, c.settings.shadowMapSize, c.raster(), frame.scratch.shadow,
                    frame.stats.shadow);
}

// The back faces' raster over the visibility pass's vertices, resolved to the back-face depth
// layer (Frame::Scratch::backZ).
void backDepthPass(const FrameContext& c, const Scene& scene, const TransformedVertices& tv,
                   RasterView rv, const RasterOptions& ro, Frame& frame) {
    const ScopedPass timer(frame.stats, "back faces");
    rv.faces = Faces::Back;
    RasterStats stats;
    rasterize(scene, tv, rv, ro, frame.scratch.backVisibility, stats);
    resolveBackDepth(frame.scratch.visibility, frame.scratch.backVisibility, tv.triangleOffset,
                     frame.scratch.backZ, c.threads);
}

// Depth and triangle ids; "geometry" is the vertex transform and set-up around the raster.
void visibilityPass(const FrameContext& c, const Scene& scene, Frame& frame) {
    const auto t0 = PassClock::now();
    RasterView rv;
    rv.viewProj = c.proj * c.view;
    rv.origin = c.origin;
    rv.width = c.grid.width;
    rv.height = c.grid.height;
    rv.nearW = c.camera.nearZ;
    RasterOptions ro = c.raster();
    ro.clearDepth = 1.0f / c.camera.farZ;
    rv.farKey = ro.clearDepth;  // clipped at the far plane before binning as by the depth test
    const TransformedVertices tv = [&] {
        const ProfileScope slice("geometry");
        return transformVertices(scene, rv, c.threads);
    }();
    RasterTimes rt;
    rasterize(scene, tv, rv, ro, frame.scratch.visibility, frame.stats.visibility, &rt);
    frame.stats.passes.push_back({"geometry", msSince(t0) - rt.rasterMs});
    frame.stats.passes.push_back({"visibility", rt.rasterMs});
    // (The marchers' depth intervals, raster/back_depth.h, when a trace pass marches with them.)
    if (c.graph.runs(pass::kBackFaces)) backDepthPass(c, scene, tv, rv, ro, frame);
}

// The resolve's arguments: the G-buffer of the visible pixels (and their UVs and tangent
// frames for the texture pass), from the visibility buffer and the scene's tables.
ResolveArgs resolveArgs(const FrameContext& c, const ResolveTables& tables, bool textured,
                        Frame& frame) {
    GBuffer& g = frame.gbuffer;
    ResolveArgs ra{};
    ra.triangles = tables.triangles.data();
    ra.instances = tables.instances.data();
    ra.normalX = tables.nx.data();
    ra.normalY = tables.ny.data();
    ra.normalZ = tables.nz.data();
    ra.ids = frame.scratch.visibility.ids.row(0);
    ra.idStride = frame.scratch.visibility.ids.stride();
    ra.width = c.grid.width;
    ra.height = c.grid.height;
    ra.tilesX = c.grid.tilesX;
    ra.tanHalfX = c.trace.tanHalfX;
    ra.tanHalfY = c.trace.tanHalfY;
    ra.nearZ = c.trace.nearZ;
    ra.farZ = c.trace.farZ;
    // Every output with one stride.
    GBufferPlanesF::forEach(
        g, [&](GBufferPlane which, PlaneF& p) { GBufferOf<float*>::at(ra.out, which) = p.row(0); },
        kResolvedPlanes);
    ra.outStride = g.viewZ.stride();
    if (textured) {
        ra.u = tables.u.data();
        ra.v = tables.v.data();
        if (!tables.u1.empty()) {
            ra.u1 = tables.u1.data();
            ra.v1 = tables.v1.data();
        }
        for (int s = 0; s < (ra.u1 ? 2 : 1); ++s)
            for (int i = 0; i < kResolveUvOutputs; ++i) {
                PlaneF& p = frame.scratch.uv[s][i];
                p.ensureSize(c.grid.width, c.grid.height);
                ra.uv[s][i] = p.row(0);
            }
        // The tangent frame, for the normal maps.
        if (!tables.tangent[0].empty())
            for (int i = 0; i < kResolveTangentOutputs; ++i) {
                ra.tangent[i] = tables.tangent[i].data();
                PlaneF& p = frame.scratch.tangent[i];
                p.ensureSize(c.grid.width, c.grid.height);
                ra.tangentFrame[i] = p.row(0);
            }
    }
    return ra;
}

// One tile of the instance and triangle ids as float planes, from the visibility buffer.
void idTile(const TileGrid& grid, const std::vector<ResolveTriangle>& tris, Frame& frame,
            int tile) {
    const PlaneU32& ids = frame.scratch.visibility.ids;
    GBuffer& out = frame.gbuffer;
    const TileRect r = grid.rect(tile);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const uint32_t id = ids.at(x, y);
            const bool hit = id != kNoPrimitive;
            out.instanceId.at(x, y) = hit ? float(tris[id].instance) : -1.0f;
            out.triangleId.at(x, y) = hit ? float(tris[id].localTriangle) : -1.0f;
        }
}

// An equirect sky's prefiltered levels and irradiance: built on its first frame, then taken
// from the cache (renderer/sky_lighting.h). Null for the analytic skies.
std::shared_ptr<const SkyLighting> environmentPass(const FrameContext& c, const Scene& scene,
                                                   Frame& frame) {
    if (scene.sky.kind != Sky::Kind::Image) return nullptr;
    const ScopedPass timer(frame.stats, "environment");
    return cachedSkyLighting(scene.sky.image, c.threads);
}

// The direct pass's arguments: direct light, sky and tone map into the frame's image (Res::Color,
// Display, Shadow); with a trace pass on, the parts the composite rebuilds the colour from
// (frame.direct; shading/direct_kernel.h) instead of the tone map, which the composite does.
void setDirectArgs(const FrameContext& c, const Scene& scene,
                   std::shared_ptr<const SkyLighting> sky, uint32_t frameIndex,
                   const FrameHistory* previous, Frame& frame, DirectLighting& lighting) {
    setDirectLighting(scene, c.settings, frame.scratch.shadow, std::move(sky), lighting);
    DirectArgs& da = lighting.args;
    const PassReads r(c.graph, frame, pass::kShading, previous);
    // The G-buffer, and its emission and occlusion where materials have them per pixel.
    da.g = r.gbuffer();
    for (int ch = 0; ch < 3; ++ch) da.emissivePlane[ch] = da.g.emission[ch];
    da.occlusion = da.g.occlusion;
    da.width = c.grid.width;
    da.height = c.grid.height;
    da.tilesX = c.grid.tilesX;
    da.tanHalfX = c.trace.tanHalfX;
    da.tanHalfY = c.trace.tanHalfY;
    std::copy_n(c.trace.viewToWorld, 9, da.viewToWorld);
    std::copy_n(c.trace.position, 3, da.camPos);
    for (int ch = 0; ch < 3; ++ch) {
        da.color[ch] = frame.plane(Res::Color, ch).row(0);
        da.display[ch] = frame.plane(Res::Display, ch).row(0);
    }
    da.shadow = frame.plane(Res::Shadow).row(0);
    da.outStride = frame.plane(Res::Color).stride();
    if (c.settings.trace.any()) {
        // The composite overwrites the display (and the colour, which SSR reads before it).
        for (float*& p : da.display) p = nullptr;
        DirectParts& p = frame.direct;
        for (int ch = 0; ch < 3; ++ch) {
            da.direct[ch] = p.direct[ch].row(0);
            da.emission[ch] = p.emission[ch].empty() ? nullptr : p.emission[ch].row(0);
            da.envDiffuse[ch] = p.envDiffuse[ch].empty() ? nullptr : p.envDiffuse[ch].row(0);
            da.envSpecular[ch] = p.envSpecular[ch].row(0);
            da.specWeight[ch] = p.specWeight[ch].row(0);
            if (c.settings.trace.ssgi && !p.hitLight[ch].empty())
                da.hitLight[ch] = p.hitLight[ch].row(0);
        }
        // Multi-bounce diffuse (ssgiFeedback): the last frame's incoming diffuse light, where
        // the history has it at this size, reflected into the hit light (none: one bounce).
        for (int ch = 0; ch < 3; ++ch) da.prevDiffuse[ch] = r.view(Res::HistoryDiffuse, ch).data;
        if (hitLightAtHalf(c.settings)) {
            // Straight into the half frame that SSGI traces (its chosen pixels this frame).
            HalfFrame& hf = frame.scratch.half.frame;
            const TraceCamera half = halfCamera(c.trace);
            for (PlaneU16& p : hf.hitLight) p.ensureSize(half.width, half.height);
            for (int ch = 0; ch < 3; ++ch) da.hitLightHalf[ch] = hf.hitLight[ch].row(0);
            da.halfStride = hf.hitLight[0].stride();
            const PixelOffset o = halfOffset(frameIndex);
            da.halfOffsetX = o.x;
            da.halfOffsetY = o.y;
        }
    }
}

// Holds an object's InUse (renderer/in_use.h) for one render call and lets it go on every way
// out, an exception's too; refuses, naming the object, when another call holds it.
class Claim {
public:
    Claim(InUse* flag, const char* what, const char* why) : flag_(flag) {
        if (flag_ && !flag_->claim())
            throw std::logic_error(std::string("render: the ") + what +
                                   " is in use by another render call (" + why + ")");
    }
    ~Claim() {
        if (flag_) flag_->release();
    }
    Claim(const Claim&) = delete;
    Claim& operator=(const Claim&) = delete;

private:
    InUse* flag_;
};

}  // namespace

GBufferView GBuffer::view() const {
    // Of its planes' size: any still held, as the frame's memory frees each after its last
    // reader.
    int w = 0, h = 0;
    forEach(*this, [&](GBufferPlane, const PlaneF& p) {
        if (w == 0 && !p.empty()) w = p.width(), h = p.height();
    });
    return gbufferView("the G-buffer", w, h, *this);
}

std::vector<PlaneRef> Frame::layers() const {
    // The outputs' planes, each with its file part from the resource table.
    std::vector<PlaneRef> out;
    forEachPlane([&](std::string_view name, const auto& p) {
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, PlaneF>) {
            const ResourceDecl& d = resourceDecl(resourceOfChannel(name));
            if (!p.empty() && d.lifetime == Lifetime::Output) out.push_back({name, &p, d.group});
        }
    });
    for (const NamedPlane& p : extraLayers) out.push_back({p.name, &p.plane, LayerGroup::Truth});
    outputs.forEachPlane(LayerGroup::Truth, [&](std::string_view name, const PlaneF& p) {
        if (!p.empty()) out.push_back({name, &p, LayerGroup::Truth});
    });
    return out;
}

const PlaneF& Frame::plane(std::string_view name) const {
    for (const PlaneRef& p : layers())
        if (p.name == name) return *p.plane;
    throw std::out_of_range("frame has no plane '" + std::string(name) + "'");
}

bool Frame::has(std::string_view name) const {
    for (const PlaneRef& p : layers())
        if (p.name == name) return true;
    return false;
}

Renderer::Renderer(RenderSettings settings) : settings_(settings) {
    settings_.validate();
    // The planes only looked at are trace planes (renderer/frame_graph_decl.cpp's debug()).
    if (!settings_.tracePlanes) settings_.debugPlanes = false;
}

void Renderer::render(const Scene& scene, const FrameInput& input, FrameHistory& history,
                      Frame& frame, const TraceObserver* observer) const {
    renderFrame(scene, input, &history, frame, observer);
}

Frame Renderer::render(const Scene& scene, const FrameInput& input, FrameHistory& history) const {
    Frame frame;
    renderFrame(scene, input, &history, frame, nullptr);
    return frame;
}

void Renderer::renderWithoutHistory(const Scene& scene, const FrameInput& input, Frame& frame,
                                    const TraceObserver* observer) const {
    renderFrame(scene, input, nullptr, frame, observer);
}

Frame Renderer::renderWithoutHistory(const Scene& scene, const FrameInput& input) const {
    Frame frame;
    renderFrame(scene, input, nullptr, frame, nullptr);
    return frame;
}

namespace {

// A signal traced in mixed or world mode needs the scene's world rays.
void requireWorldRays(const TraceSettings& ts, const WorldRays* world) {
    if (world || !ts.worldRays()) return;
    const bool ssr = ts.ssr && ts.ssrTrace != TraceMode::Screen;
    const std::string flag = ssr ? "--ssr-trace " + std::string(traceModeName(ts.ssrTrace))
                                 : "--ssgi-trace " + std::string(traceModeName(ts.ssgiTrace));
    throw std::invalid_argument(flag +
                                " needs world rays (FrameInput::world), and none were given: "
                                "build them from the scene (world/embree_world_rays.h), or "
                                "trace on screen");
}

}  // namespace

void Renderer::renderFrame(const Scene& scene, const FrameInput& input, FrameHistory* history,
                           Frame& frame, const TraceObserver* observer) const {
    const Claim historyUse(history ? &history->inUse : nullptr, "FrameHistory",
                           "a history carries one sequence, one frame at a time");
    const Claim frameUse(&frame.inUse, "Frame", "give each thread a Frame of its own");
    const ProfileScope slice("render call");
    scene.validate();
    requireWorldRays(settings_.trace, input.world);
    const bool readsLast =
        history && !input.resetHistory && history->readableAt(settings_.width, settings_.height);
    // The last frame's, where usable at this size (none after a cut).
    const FrameHistory* previous =
        readsLast && history->usableAt(settings_.width, settings_.height) ? history : nullptr;
    GraphKey key{settings_, SceneFacts::of(scene), readsLast, history && input.replaceHistory};
    key.lastColor = previous != nullptr;
    key.lastDiffuse = previous && previous->diffuse[0].width() == settings_.width &&
                      previous->diffuse[0].height() == settings_.height;
    const CompiledGraph graph = compileFrameGraph(key);
    const FrameContext c(settings_, graph, scene, input);
    frame.stats = FrameStats{};
    frame.stats.isa = c.isa;
    frame.stats.threads = c.threads > 0 ? c.threads : tbb::this_task_arena::max_concurrency();
    FrameMemory memory(graph, frame, settings_.tracePlanes);
    dropBackFaces(graph, frame);

    // The passes up to the direct light: the rasters over the whole frame, then the resolve,
    // textures, ids and shading tile by tile, one loop, as the graph chains them.
    FrameScheduler passes(graph, c.grid, c.threads, input.cancel, &memory);
    passes.whole(pass::kShadow, [&] { shadowPass(c, scene, frame); });
    passes.whole(
        pass::kVisibility, [&] { visibilityPass(c, scene, frame); }, pass::kBackFaces);
    const bool textured = graph.runs(pass::kTextures);
    ResolveTables tables;
    ResolveArgs ra{};
    const auto resolve = SSRT_DISPATCH(c.isa, resolveTile);
    passes.tiled(
        pass::kResolve, [&](int tile) { resolve(ra, tile); },
        [&] {
            tables =
                buildResolveTables(scene, c.origin, c.view, c.prevViewProj, textured, c.threads);
            ra = resolveArgs(c, tables, textured, frame);
        });
    passes.tiled(pass::kTextures, [&](int tile) { applyTexturesTile(scene, frame, c.grid, tile); });
    passes.tiled(pass::kIds, [&](int tile) { idTile(c.grid, tables.triangles, frame, tile); });
    DirectLighting lighting;
    const std::shared_ptr<const SkyLighting> sky = environmentPass(c, scene, frame);
    const auto shade = SSRT_DISPATCH(c.isa, shadeTile);
    passes.tiled(
        pass::kShading, [&](int tile) { shade(lighting.args, tile); },
        [&] { setDirectArgs(c, scene, sky, input.frameIndex, previous, frame, lighting); });
    passes.run(frame.stats);
    frame.camera = c.trace;
    frame.index = input.frameIndex;
    if (settings_.trace.any()) {
        std::vector<uint8_t> cutOut(scene.instances.size());
        for (std::size_t i = 0; i < cutOut.size(); ++i)
            cutOut[i] = scene.materials[scene.instances[i].material].alphaMode !=
                        Material::AlphaMode::Opaque;
        runTracePasses({settings_, graph, memory, c.isa, input.frameIndex, lighting.light, previous,
                        history, input.resetHistory, input.replaceHistory, observer, input.cancel,
                        input.world, &tables, &cutOut},
                       frame);
        stopIfCancelled(input.cancel);
        memory.step(pass::kHistoryCommit, [&] {
            if (graph.runs(pass::kHistoryCommit)) commitHistory(graph, frame, *history);
        });
    }
    frame.stats.memory = memoryUse(frame, history);
    frame.stats.declared = {{"transient, reused", graph.transientBytes},
                            {"outputs", graph.outputBytes},
                            {"history", graph.historyBytes}};
}

}  // namespace ssrt
