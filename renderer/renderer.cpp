#include "renderer/renderer.h"

#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>

#include "core/tiles.h"
#include "raster/raster.h"
#include "raster/resolve_kernel.h"
#include "raster/shadow_map.h"
#include "renderer/direct_lighting.h"
#include "renderer/sky_lighting.h"
#include "renderer/texture_pass.h"
#include "renderer/trace_pass.h"
#include "shading/direct_kernel.h"

namespace ssrt {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Per-triangle ray-plane and barycentric set-up in view space, and world-space normals per
// vertex, for the resolve kernel.
struct ResolveTables {
    std::vector<ResolveTriangle> triangles;
    std::vector<ResolveInstance> instances;
    std::vector<float> nx, ny, nz;
    std::vector<float> u, v;  // texture coordinates per vertex, only for textured scenes
};

bool anyTextured(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.textured(); });
}

ResolveInstance resolveInstance(const Scene& scene, const Instance& inst, const glm::mat4& view,
                                const glm::mat4& prevViewProj) {
    const Material& m = scene.materials[inst.material];
    ResolveInstance r;
    r.albedo[0] = m.baseColor.r;
    r.albedo[1] = m.baseColor.g;
    r.albedo[2] = m.baseColor.b;
    r.metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    r.roughness = std::clamp(m.roughness, 0.0f, 1.0f);
    r.materialId = float(inst.material);
    // current view -> world -> object (current) -> world (previous) -> previous clip
    const glm::mat4 toPrev =
        prevViewProj * inst.previousTransform * glm::inverse(inst.transform) * glm::inverse(view);
    std::copy_n(glm::value_ptr(toPrev), 16, r.viewToPrevClip);
    return r;
}

// Runs fn(instance, first, end) over chunks of [0, count(instance)) for every instance, so
// that one big mesh still spreads over every thread.
template <class CountFn, class Fn>
void forInstanceChunks(std::size_t instances, int threads, CountFn count, Fn fn) {
    constexpr uint32_t kChunk = 4096;
    std::vector<std::pair<uint32_t, uint32_t>> work;  // (instance, first)
    for (uint32_t i = 0; i < instances; ++i)
        for (uint32_t first = 0; first < count(i); first += kChunk) work.push_back({i, first});
    parallelFor(int(work.size()), threads, [&](int w) {
        const auto [i, first] = work[w];
        fn(i, first, std::min<uint32_t>(count(i), first + kChunk));
    });
}

ResolveTables buildResolveTables(const Scene& scene, const glm::mat4& view,
                                 const glm::mat4& prevViewProj, bool textured, int threads) {
    ResolveTables t;
    std::vector<uint32_t> vertexOffset, triOffset;
    uint32_t nv = 0, nt = 0;
    for (const Instance& inst : scene.instances) {
        vertexOffset.push_back(nv);
        triOffset.push_back(nt);
        nv += uint32_t(scene.meshes[inst.mesh].positions.size());
        nt += uint32_t(scene.meshes[inst.mesh].triangleCount());
        t.instances.push_back(resolveInstance(scene, inst, view, prevViewProj));
    }
    t.triangles.resize(nt);
    t.nx.resize(nv);
    t.ny.resize(nv);
    t.nz.resize(nv);
    if (textured) {
        t.u.resize(nv);
        t.v.resize(nv);
    }
    std::vector<glm::vec3> viewPos(nv);
    auto meshOf = [&](uint32_t i) -> const Mesh& { return scene.meshes[scene.instances[i].mesh]; };
    // View-space positions and world-space unit normals per vertex.
    forInstanceChunks(
        scene.instances.size(), threads,
        [&](uint32_t i) { return uint32_t(meshOf(i).positions.size()); },
        [&](uint32_t i, uint32_t first, uint32_t end) {
            const Instance& inst = scene.instances[i];
            const Mesh& mesh = meshOf(i);
            const glm::mat4 modelView = view * inst.transform;
            const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(inst.transform));
            for (uint32_t v = first; v < end; ++v) {
                const uint32_t g = vertexOffset[i] + v;
                viewPos[g] = glm::vec3(modelView * glm::vec4(mesh.positions[v], 1.0f));
                glm::vec3 n = normalMatrix * mesh.normals[v];
                const float len = glm::length(n);
                n = std::isfinite(len) && len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
                t.nx[g] = n.x;
                t.ny[g] = n.y;
                t.nz[g] = n.z;
                if (textured) {
                    const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[v];
                    t.u[g] = uv.x;
                    t.v[g] = uv.y;
                }
            }
        });
    // Ray-plane and barycentric set-up per triangle.
    forInstanceChunks(
        scene.instances.size(), threads,
        [&](uint32_t i) { return uint32_t(meshOf(i).triangleCount()); },
        [&](uint32_t i, uint32_t first, uint32_t end) {
            const Mesh& mesh = meshOf(i);
            const glm::vec3* pv = viewPos.data() + vertexOffset[i];
            for (uint32_t k = first; k < end; ++k) {
                const uint32_t* idx = &mesh.indices[3 * k];
                const glm::vec3 p0 = pv[idx[0]], e1 = pv[idx[1]] - p0, e2 = pv[idx[2]] - p0;
                const glm::vec3 n = glm::cross(e1, e2);
                const float nn = glm::dot(n, n);
                ResolveTriangle& r = t.triangles[triOffset[i] + k];
                r = ResolveTriangle{};
                r.instance = i;
                r.localTriangle = k;
                for (int c = 0; c < 3; ++c) r.v[c] = vertexOffset[i] + idx[c];
                if (!(nn > 0.0f) || !std::isfinite(nn)) continue;  // never rasterized
                const glm::vec3 un = n / std::sqrt(nn);
                const glm::vec3 g1 = glm::cross(e2, n) / nn, g2 = glm::cross(n, e1) / nn;
                for (int c = 0; c < 3; ++c) {
                    r.p0[c] = p0[c];
                    r.n[c] = un[c];
                    r.g1[c] = g1[c];
                    r.g2[c] = g2[c];
                }
                r.d = glm::dot(un, p0);
            }
        });
    return t;
}

// Output planes, in the order the frame lists them.
enum PlaneIndex {
    kColorR,
    kColorG,
    kColorB,
    kDisplayR,
    kDisplayG,
    kDisplayB,
    kShadow,
    kViewZ,
    kNormalX,
    kNormalY,
    kNormalZ,
    kAlbedoR,
    kAlbedoG,
    kAlbedoB,
    kMetallic,
    kRoughness,
    kMaterialId,
    kMotionX,
    kMotionY,
    kInstanceId,
    kTriangleId,
    kPlaneCount
};
const char* const kPlaneNames[kPlaneCount] = {
    "color.R",  "color.G",   "color.B",    "display.R", "display.G", "display.B",  "shadow",
    "viewZ",    "normal.X",  "normal.Y",   "normal.Z",  "albedo.R",  "albedo.G",   "albedo.B",
    "metallic", "roughness", "materialId", "motion.X",  "motion.Y",  "instanceId", "triangleId"};

// Gives the frame its planes, keeping the existing ones when names and sizes match. Every
// pixel of every plane is written by a pass, so none is cleared here.
void ensurePlanes(Frame& f, int w, int h, bool idPlanes, const TraceSettings& trace) {
    std::vector<const char*> names(kPlaneNames,
                                   kPlaneNames + (idPlanes ? kPlaneCount : kInstanceId));
    for (const char* n : tracePlaneNames(trace)) names.push_back(n);
    bool same = f.planes.size() == names.size();
    for (std::size_t i = 0; same && i < names.size(); ++i)
        same = f.planes[i].name == names[i] && f.planes[i].plane.width() == w &&
               f.planes[i].plane.height() == h;
    if (same) return;
    f.planes.clear();
    for (const char* n : names) f.planes.push_back({n, PlaneF(w, h, kUninitialized)});
}

void writeIdPlanes(const std::vector<ResolveTriangle>& tris, const PlaneU32& ids, PlaneF& instance,
                   PlaneF& triangle, const TileGrid& grid, int threads) {
    parallelForTiles(grid.count(), threads, [&](int tile) {
        const TileRect r = grid.rect(tile);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                const uint32_t id = ids.at(x, y);
                const bool hit = id != kNoPrimitive;
                instance.at(x, y) = hit ? float(tris[id].instance) : -1.0f;
                triangle.at(x, y) = hit ? float(tris[id].localTriangle) : -1.0f;
            }
    });
}

}  // namespace

const PlaneF& Frame::plane(std::string_view name) const {
    for (const NamedPlane& p : planes)
        if (p.name == name) return p.plane;
    throw std::out_of_range("frame has no plane '" + std::string(name) + "'");
}

bool Frame::has(std::string_view name) const {
    for (const NamedPlane& p : planes)
        if (p.name == name) return true;
    return false;
}

Renderer::Renderer(RenderSettings settings) : settings_(settings) { settings_.validate(); }

Frame Renderer::render(const Scene& scene, const Camera& camera, const Camera& prevCamera) const {
    Frame frame;
    render(scene, camera, prevCamera, frame);
    return frame;
}

void Renderer::render(const Scene& scene, const Camera& camera, const Camera& prevCamera,
                      Frame& frame, const TraceObserver* observer) const {
    scene.validate();
    const RenderSettings& s = settings_;
    const Isa isa = resolveIsa(s.isa);
    const int threads = s.threads;
    const int w = s.width, h = s.height;
    const float aspect = float(w) / float(h);
    const glm::mat4 view = camera.view(), proj = camera.projection(aspect);
    const glm::mat4 prevViewProj = prevCamera.projection(aspect) * prevCamera.view();

    frame.width = w;
    frame.height = h;
    frame.stats = FrameStats{};
    frame.stats.isa = isa;
    frame.stats.threads = threads > 0 ? threads : tbb::this_task_arena::max_concurrency();
    auto pass = [&](const char* name, Clock::time_point t0) {
        frame.stats.passes.push_back({name, msSince(t0)});
    };
    RasterOptions ro;
    ro.isa = isa;
    ro.threads = threads;

    // Shadow map of the directional light.
    auto t0 = Clock::now();
    ShadowMap& shadow = frame.scratch.shadow;
    renderShadowMap(scene, s.shadowMapSize, ro, shadow, frame.stats.shadow);
    pass("shadow", t0);

    // Visibility: depth and triangle ids.
    t0 = Clock::now();
    RasterView rv;
    rv.viewProj = proj * view;
    rv.width = w;
    rv.height = h;
    rv.nearW = camera.nearZ;
    const TransformedVertices tv = transformVertices(scene, rv, threads);
    ro.clearDepth = 1.0f / camera.farZ;
    RasterTimes rt;
    VisibilityBuffer& vb = frame.scratch.visibility;
    rasterize(scene, tv, rv, ro, vb, frame.stats.visibility, &rt);
    frame.stats.passes.push_back({"geometry", msSince(t0) - rt.rasterMs});
    frame.stats.passes.push_back({"visibility", rt.rasterMs});

    // Resolve: the G-buffer for visible pixels.
    t0 = Clock::now();
    const bool textured = anyTextured(scene);
    const ResolveTables tables = buildResolveTables(scene, view, prevViewProj, textured, threads);
    ensurePlanes(frame, w, h, s.idPlanes, s.trace);
    PlaneF* gplanes[kResolveOutputs];
    for (int i = 0; i < kResolveOutputs; ++i) gplanes[i] = &frame.planes[kViewZ + i].plane;
    const TileGrid grid(w, h);
    const float tanHalfY = std::tan(glm::radians(camera.fovY) * 0.5f);
    ResolveArgs ra{};
    ra.triangles = tables.triangles.data();
    ra.instances = tables.instances.data();
    ra.normalX = tables.nx.data();
    ra.normalY = tables.ny.data();
    ra.normalZ = tables.nz.data();
    ra.ids = vb.ids.row(0);
    ra.idStride = vb.ids.stride();
    ra.width = w;
    ra.height = h;
    ra.tilesX = grid.tilesX;
    ra.tanHalfX = tanHalfY * aspect;
    ra.tanHalfY = tanHalfY;
    ra.nearZ = camera.nearZ;
    ra.farZ = camera.farZ;
    for (int i = 0; i < kResolveOutputs; ++i) ra.out[i] = gplanes[i]->row(0);
    ra.outStride = gplanes[0]->stride();
    if (textured) {
        ra.u = tables.u.data();
        ra.v = tables.v.data();
        for (int i = 0; i < kResolveUvOutputs; ++i) {
            PlaneF& p = frame.scratch.uv[i];
            p.ensureSize(w, h);
            // The kernel writes every output with one stride.
            if (p.stride() != ra.outStride) throw std::logic_error("texture UV plane stride");
            ra.out[kResolveOutputs + i] = p.row(0);
        }
    }
    const auto resolve = SSRT_DISPATCH(isa, resolveTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { resolve(ra, tile); });
    pass("resolve", t0);

    // Textures: base colour, metallic and roughness texels into the G-buffer.
    if (textured) {
        t0 = Clock::now();
        TexturePlanes tp;
        for (int i = 0; i < kResolveUvOutputs; ++i) tp.uv[i] = &frame.scratch.uv[i];
        tp.materialId = gplanes[kMaterialId - kViewZ];
        for (int i = 0; i < 3; ++i) tp.albedo[i] = gplanes[kAlbedoR - kViewZ + i];
        tp.metallic = gplanes[kMetallic - kViewZ];
        tp.roughness = gplanes[kRoughness - kViewZ];
        applyTextures(scene, tp, grid, threads);
        pass("textures", t0);
    }

    // Instance and triangle ids as float planes, from the visibility buffer (optional).
    if (s.idPlanes) {
        t0 = Clock::now();
        writeIdPlanes(tables.triangles, vb.ids, frame.planes[kInstanceId].plane,
                      frame.planes[kTriangleId].plane, grid, threads);
        pass("ids", t0);
    }

    // An equirect sky's prefiltered levels and irradiance: built on its first frame, then
    // taken from the cache (renderer/sky_lighting.h).
    const Sky& sky = scene.sky;
    std::shared_ptr<const SkyLighting> skyLighting;
    if (sky.kind == Sky::Kind::Image) {
        t0 = Clock::now();
        skyLighting = cachedSkyLighting(sky.image, threads);
        pass("environment", t0);
    }

    // Direct light, sky and tone map.
    t0 = Clock::now();
    DirectLighting lighting;
    setDirectLighting(scene, s, shadow, skyLighting, lighting);
    DirectArgs& da = lighting.args;
    for (int i = 0; i < 10; ++i) da.g[i] = gplanes[i]->row(0);
    da.gStride = gplanes[0]->stride();
    da.width = w;
    da.height = h;
    da.tilesX = grid.tilesX;
    da.tanHalfX = ra.tanHalfX;
    da.tanHalfY = ra.tanHalfY;
    const glm::mat3 viewToWorld = glm::mat3(glm::inverse(view));
    std::copy_n(glm::value_ptr(viewToWorld), 9, da.viewToWorld);
    std::copy_n(glm::value_ptr(camera.position), 3, da.camPos);
    for (int i = 0; i < 7; ++i) da.out[i] = frame.planes[kColorR + i].plane.row(0);
    da.outStride = frame.planes[kColorR].plane.stride();
    // With the screen-space passes on, the direct pass also hands out its parts for the
    // composite (shading/direct_kernel.h).
    if (s.trace.any()) {
        da.compensation = &energyTables();
        float** parts[5] = {da.direct, da.emission, da.envDiffuse, da.envSpecular, da.specWeight};
        for (int i = 0; i < 15; ++i) {
            PlaneF& p = frame.scratch.directParts[i];
            p.ensureSize(w, h);
            if (p.stride() != da.outStride) throw std::logic_error("direct part plane stride");
            parts[i / 3][i % 3] = p.row(0);
        }
        if (s.trace.ssgi)
            for (int c = 0; c < 3; ++c) {
                PlaneF& p = frame.scratch.hitLight[c];
                p.ensureSize(w, h);
                if (p.stride() != da.outStride) throw std::logic_error("hit light plane stride");
                da.hitLight[c] = p.row(0);
            }
    }
    const auto shade = SSRT_DISPATCH(isa, shadeTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { shade(da, tile); });
    pass("shading", t0);

    TraceCamera& tc = frame.camera;
    tc.width = w;
    tc.height = h;
    tc.tanHalfX = ra.tanHalfX;
    tc.tanHalfY = ra.tanHalfY;
    tc.nearZ = camera.nearZ;
    tc.farZ = camera.farZ;
    std::copy_n(da.viewToWorld, 9, tc.viewToWorld);
    std::copy_n(da.camPos, 3, tc.position);
    if (s.trace.any()) runTracePasses(s, isa, tc, da, frame, observer);
}

}  // namespace ssrt
