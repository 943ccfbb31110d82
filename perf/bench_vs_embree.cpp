// The same screen-space rays traced by Embree 3 (world space, the truth) and by the three
// marchers (screen space), in one run: corridor and cornell at 1920x1080, mirror rays
// (coherent) and VNDF-bounded GGX rays (incoherent), threads 1 and 2.
//
//   ./build/perf/ssrt_bench --benchmark_filter=VsEmbree
//
// Set-up, once per scene (not timed): the G-buffer of a frame rendered with the trace passes
// off, its Hi-Z pyramid, and the truth's Embree scene (world/embree_scene.h: one BVH
// per mesh and one over the instances, RTC_BUILD_QUALITY_HIGH; its build time, second of two
// builds, is the counter build_ms). Once per ray kind: the RayBatch from trace/ray_gen.h, the same
// rays in world space (origin = camera position + viewToWorld * view origin, direction =
// viewToWorld * view direction; the rotation keeps lengths, so t is the view-space distance)
// and Embree's answer for every ray, which the agreement counters compare with.
//
// What Embree is asked: the first hit in [tnear, tfar], tnear = 1e-4 x the scene's bounding
// diagonal (the origin lies on the surface; this steps off it without skipping real
// geometry), tfar = MarchSettings::maxDistance (the marchers give up at that view-space
// length), so both answer the same question. Embree sees both faces of every triangle (the
// marchers end on back faces: that difference shows in the agreement counters).
//
// Benchmarks (names start with VsEmbree so one filter takes them all):
// - VsEmbree_embree/<scene>_<rays>_<single|packet16|exact>/<threads>: Embree alone,
//   EmbreeScene::intersect per ray (rtcIntersect1) or intersect16 per 4x4 pixel block
//   (rtcIntersect16), or those packets as the renderer's world rays (EmbreeWorldRays: each
//   hit made exact by ssrt's ray-triangle test), over 64x64 tiles (parallelForTiles).
//   Counters: Mrays/s, build_ms, triangles, e_hit (share of traced rays that hit), vs_single
//   (share of rays whose answer differs from rtcIntersect1's: a sanity check, expect 0),
//   native16 (1 when Embree runs 16-wide packets natively, i.e. its AVX-512 kernels).
// - VsEmbree_<marcher>/<scene>_<rays>/<threads>: each iteration marches the batch (timed:
//   the benchmark's manual time), builds the Hi-Z pyramid for hiz (timed apart), and traces
//   the same rays with Embree (packet16, timed apart), interleaved so that the drift of a
//   shared machine hits both alike. Counters: Mrays/s (marcher), embree_Mrays/s, ratio
//   (marcher rate / Embree rate), ratio_hiz (hiz only: Hi-Z build included), and agreement
//   with Embree as shares of the traced rays: both (both hit), both_far (both hit, hit
//   points more than agree_tol apart), m_only (marcher hit, Embree none within tfar),
//   e_only (Embree hit, marcher none). agree_tol = 1 % of the scene's bounding diagonal.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/isa.h"
#include "core/tiles.h"
#include "raster/hiz.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "trace/march.h"
#include "trace/ray_gen.h"
#include "trace/trace_types.h"
#include "world/embree_scene.h"
#include "world/embree_world_rays.h"

using namespace ssrt;

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kWidth = 1920, kHeight = 1080;
constexpr float kAgreeScale = 1e-2f;  // agreement tolerance, times the diagonal
constexpr float kNoHit = std::numeric_limits<float>::infinity();

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// ---- Embree scene ----------------------------------------------------------------------

// The truth's scene, built twice: the first build also starts Embree's threads, so the second
// one's time is build_ms.
std::unique_ptr<EmbreeScene> buildEmbree(const Scene& s) {
    auto first = std::make_unique<EmbreeScene>(s);
    first.reset();
    return std::make_unique<EmbreeScene>(s);
}

// The rays of a RayBatch in world space, per pixel (index y * width + x).
struct WorldBatch {
    int width = 0, height = 0;
    std::vector<float> o[3], d[3];
    std::vector<uint8_t> valid;  // pdf > 0
    uint64_t count = 0;          // valid rays
    float tnear = 0.0f, tfar = 0.0f;
};

WorldBatch toWorld(const RayBatch& rays, const glm::mat3& viewToWorld, glm::vec3 camPos,
                   float tnear, float tfar) {
    WorldBatch wr;
    wr.width = rays.width();
    wr.height = rays.height();
    wr.tnear = tnear;
    wr.tfar = tfar;
    const std::size_t n = std::size_t(wr.width) * std::size_t(wr.height);
    for (int c = 0; c < 3; ++c) wr.o[c].resize(n), wr.d[c].resize(n);
    wr.valid.resize(n);
    for (int y = 0; y < wr.height; ++y)
        for (int x = 0; x < wr.width; ++x) {
            const std::size_t i = std::size_t(y) * wr.width + x;
            const glm::vec3 o = camPos + viewToWorld * glm::vec3(rays.ox.at(x, y), rays.oy.at(x, y),
                                                                 rays.oz.at(x, y));
            const glm::vec3 d =
                viewToWorld * glm::vec3(rays.dx.at(x, y), rays.dy.at(x, y), rays.dz.at(x, y));
            for (int c = 0; c < 3; ++c) wr.o[c][i] = o[c], wr.d[c][i] = d[c];
            wr.valid[i] = rays.pdf.at(x, y) > 0.0f;
            wr.count += wr.valid[i];
        }
    return wr;
}

// Single: rtcIntersect1 per ray; Packet16: rtcIntersect16 per 4x4 block; Exact: the same
// packets through EmbreeWorldRays (world/embree_world_rays.h), each hit's distance and
// barycentrics recomputed by ssrt's exact test, as the renderer's world rays are.
enum class EmbreeMode { Single, Packet16, Exact };

const char* modeName(EmbreeMode mode) {
    switch (mode) {
        case EmbreeMode::Single: return "_single";
        case EmbreeMode::Packet16: return "_packet16";
        case EmbreeMode::Exact: return "_exact";
    }
    return "";
}

// Traces every valid ray; t[i] = hit distance, or kNoHit (no ray, or no hit in range).
void traceEmbree(const EmbreeScene& es, const WorldBatch& wr, EmbreeMode mode, int threads,
                 float* t) {
    const TileGrid grid(wr.width, wr.height);
    auto origin = [&](std::size_t i) { return glm::vec3(wr.o[0][i], wr.o[1][i], wr.o[2][i]); };
    auto direction = [&](std::size_t i) { return glm::vec3(wr.d[0][i], wr.d[1][i], wr.d[2][i]); };
    parallelForTiles(grid.count(), threads, [&](int tile) {
        const TileRect r = grid.rect(tile);
        if (mode == EmbreeMode::Single) {
            for (int y = r.y0; y < r.y1; ++y)
                for (int x = r.x0; x < r.x1; ++x) {
                    const std::size_t i = std::size_t(y) * wr.width + x;
                    t[i] = kNoHit;
                    if (!wr.valid[i]) continue;
                    const EmbreeHit h = es.intersect(origin(i), direction(i), wr.tnear, wr.tfar);
                    if (h.hit) t[i] = h.t;
                }
            return;
        }
        // Packets: the valid rays of each 4x4 pixel block.
        glm::vec3 o[16], d[16];
        EmbreeHit hits[16];
        std::size_t lane[16];
        const EmbreeWorldRays exact(es);
        ssrt::WorldRay rays[16];
        ssrt::WorldHit exactHits[16];
        for (int by = r.y0; by < r.y1; by += 4)
            for (int bx = r.x0; bx < r.x1; bx += 4) {
                int n = 0;
                for (int y = by; y < std::min(by + 4, r.y1); ++y)
                    for (int x = bx; x < std::min(bx + 4, r.x1); ++x) {
                        const std::size_t i = std::size_t(y) * wr.width + x;
                        t[i] = kNoHit;
                        if (!wr.valid[i]) continue;
                        o[n] = origin(i), d[n] = direction(i), lane[n++] = i;
                    }
                if (n == 0) continue;
                if (mode == EmbreeMode::Exact) {
                    for (int k = 0; k < n; ++k) rays[k] = {o[k], d[k], wr.tnear, wr.tfar};
                    exact.intersect(std::span(rays, n), std::span(exactHits, n));
                    for (int k = 0; k < n; ++k)
                        if (exactHits[k].hit) t[lane[k]] = exactHits[k].t;
                    continue;
                }
                es.intersect16(n, o, d, wr.tnear, wr.tfar, hits);
                for (int k = 0; k < n; ++k)
                    if (hits[k].hit) t[lane[k]] = hits[k].t;
            }
    });
}

// ---- Workloads ---------------------------------------------------------------------------

struct RayKind {
    RayBatch rays;
    WorldBatch world;
    std::vector<float> embreeT;  // Embree's answer (single rays, every core)
    uint64_t embreeHits = 0;
};

struct Workload {
    Scene scene;
    TraceCamera camera;
    PlaneF viewZ, normal[3], roughness;
    HiZPyramid hiz;
    std::unique_ptr<EmbreeScene> embree;
    float diagonal = 0.0f;
    std::map<SsrMethod, std::unique_ptr<RayKind>> kinds;

    GBufferView g() const {
        return gbufferView("bench", camera.width, camera.height,
                           {{kGViewZ, &viewZ},
                            {kGNormalX, &normal[0]},
                            {kGNormalY, &normal[1]},
                            {kGNormalZ, &normal[2]},
                            {kGRoughness, &roughness}});
    }
    glm::mat3 viewToWorld() const { return glm::make_mat3(camera.viewToWorld); }
};

Workload& workload(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Workload>> cache;
    auto& w = cache[name];
    if (w) return *w;
    w = std::make_unique<Workload>();
    w->scene = makeBuiltinScene(name);
    // The G-buffer of a frame without the trace passes.
    RenderSettings rs;
    rs.width = kWidth;
    rs.height = kHeight;
    rs.shadowMapSize = 256;
    rs.idPlanes = false;
    rs.trace.ssr = rs.trace.ssgi = false;
    const Frame f = Renderer(rs).renderWithoutHistory(w->scene);
    w->viewZ = f.gbuffer.viewZ.clone();
    for (int c = 0; c < 3; ++c) w->normal[c] = f.gbuffer.normal[c].clone();
    w->roughness = f.gbuffer.roughness.clone();
    // The camera as renderer.cpp builds it.
    const Camera& cam = w->scene.camera;
    TraceCamera& tc = w->camera;
    tc.width = kWidth;
    tc.height = kHeight;
    tc.tanHalfY = std::tan(glm::radians(cam.fovY) * 0.5f);
    tc.tanHalfX = tc.tanHalfY * float(kWidth) / float(kHeight);
    tc.nearZ = cam.nearZ;
    tc.farZ = cam.farZ;
    // The relative march lengths (issue 16) resolve against it, as the world rays' tfar does.
    tc.sceneDiagonal = w->scene.diagonal();
    const glm::mat3 v2w = glm::mat3(glm::inverse(cam.view()));
    std::copy_n(glm::value_ptr(v2w), 9, tc.viewToWorld);
    buildHiZ(w->viewZ, w->hiz, 0);
    w->embree = buildEmbree(w->scene);
    glm::vec3 lo, hi;
    w->scene.bounds(lo, hi);
    w->diagonal = glm::length(hi - lo);
    return *w;
}

const RayKind& rayKind(Workload& w, SsrMethod method) {
    auto& k = w.kinds[method];
    if (k) return *k;
    k = std::make_unique<RayKind>();
    generateSpecularRays(defaultIsa(), method, 0, 0, w.camera, w.g(), k->rays, 0);
    k->world =
        toWorld(k->rays, w.viewToWorld(), w.scene.camera.position - w.embree->origin(),
                w.embree->epsilon(), marchLengths(MarchSettings{}, w.scene.diagonal()).maxDistance);
    k->embreeT.resize(k->world.valid.size());
    traceEmbree(*w.embree, k->world, EmbreeMode::Single, 0, k->embreeT.data());
    for (float t : k->embreeT) k->embreeHits += t != kNoHit;
    return *k;
}

// ---- Benchmarks --------------------------------------------------------------------------

void embreeBench(benchmark::State& state, std::string scene, SsrMethod method, EmbreeMode mode) {
    const int threads = int(state.range(0));
    Workload& w = workload(scene);
    const RayKind& k = rayKind(w, method);
    std::vector<float> t(k.world.valid.size());
    double sec = 0.0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        traceEmbree(*w.embree, k.world, mode, threads, t.data());
        sec += secondsSince(t0);
        benchmark::DoNotOptimize(t.data());
    }
    // Sanity: this mode's answers against the reference (single rays): hit/miss or distance
    // (relative 1e-4) differs.
    uint64_t hits = 0, differ = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        hits += t[i] != kNoHit;
        const float r = k.embreeT[i];
        if ((t[i] == kNoHit) != (r == kNoHit) || (r != kNoHit && std::abs(t[i] - r) > 1e-4f * r))
            ++differ;
    }
    state.counters["Mrays/s"] = double(k.world.count) * 1e-6 * double(state.iterations()) / sec;
    state.counters["build_ms"] = w.embree->stats().buildMs;
    state.counters["triangles"] = double(w.embree->stats().triangles);
    state.counters["e_hit"] = double(hits) / double(k.world.count);
    state.counters["vs_single"] = double(differ) / double(k.world.count);
    state.counters["rays"] = double(k.world.count);
    state.counters["native16"] = double(w.embree->nativePackets16());
}

struct Agreement {
    uint64_t both = 0, bothFar = 0, marcherOnly = 0, embreeOnly = 0;
};

Agreement agree(const Workload& w, const RayKind& k, const MarchResult& m) {
    const TraceCamera& c = w.camera;
    const float tol = kAgreeScale * w.diagonal;
    Agreement a;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const std::size_t i = std::size_t(y) * c.width + x;
            if (!k.world.valid[i]) continue;
            const bool mh = m.hit.at(x, y) > 0.0f, eh = k.embreeT[i] != kNoHit;
            if (mh && eh) {
                ++a.both;
                // Both hit points in view space: the marcher's from its pixel and depth,
                // Embree's along the view-space ray (t is a length: the rotation keeps it).
                const float z = m.hitZ.at(x, y);
                const glm::vec3 pm(
                    (2.0f * m.hitX.at(x, y) / float(c.width) - 1.0f) * c.tanHalfX * z,
                    (1.0f - 2.0f * m.hitY.at(x, y) / float(c.height)) * c.tanHalfY * z, -z);
                const glm::vec3 o(k.rays.ox.at(x, y), k.rays.oy.at(x, y), k.rays.oz.at(x, y));
                const glm::vec3 d(k.rays.dx.at(x, y), k.rays.dy.at(x, y), k.rays.dz.at(x, y));
                const glm::vec3 pe = o + k.embreeT[i] * d;
                // Written so that a NaN or inf hit point counts as far.
                if (!(glm::length(pm - pe) <= tol)) ++a.bothFar;
            } else if (mh) {
                ++a.marcherOnly;
            } else if (eh) {
                ++a.embreeOnly;
            }
        }
    return a;
}

void marcherBench(benchmark::State& state, std::string scene, SsrMethod method, Marcher marcher) {
    const int threads = int(state.range(0));
    const Isa isa = defaultIsa();
    Workload& w = workload(scene);
    const RayKind& k = rayKind(w, method);
    const MarchSettings settings;
    MarchResult result;
    MarchStats stats;
    HiZPyramid hiz;
    std::vector<float> t(k.world.valid.size());
    double hizSec = 0.0, marchSec = 0.0, embreeSec = 0.0;
    for (auto _ : state) {
        auto t0 = Clock::now();
        if (marcher == Marcher::HiZ) buildHiZ(w.viewZ, hiz, threads);
        hizSec += secondsSince(t0);
        t0 = Clock::now();
        stats = marchRays(isa, marcher, settings, {}, w.camera, w.g(), nullptr,
                          marcher == Marcher::HiZ ? &hiz : nullptr, k.rays, result, threads);
        const double marchIter = secondsSince(t0);
        marchSec += marchIter;
        state.SetIterationTime(marchIter);
        benchmark::DoNotOptimize(result.hit.row(0));
        t0 = Clock::now();
        traceEmbree(*w.embree, k.world, EmbreeMode::Packet16, threads, t.data());
        embreeSec += secondsSince(t0);
        benchmark::DoNotOptimize(t.data());
    }
    if (stats.rays != k.world.count) state.SkipWithError("marcher and Embree ray counts differ");
    const double iters = double(state.iterations());
    const double mrays = double(k.world.count) * 1e-6 * iters;
    // Rates over the same iterations: the marcher's seconds (also the manual time), the Hi-Z
    // builds' and Embree's, each summed apart.
    state.counters["Mrays/s"] = mrays / marchSec;
    state.counters["embree_Mrays/s"] = mrays / embreeSec;
    state.counters["ratio"] = embreeSec / marchSec;
    if (marcher == Marcher::HiZ) {
        state.counters["hiz_ms"] = hizSec * 1e3 / iters;
        state.counters["ratio_hiz"] = embreeSec / (marchSec + hizSec);
    }
    const Agreement a = agree(w, k, result);
    const double n = double(k.world.count);
    state.counters["m_hit"] = double(stats.ends[0]) / n;
    state.counters["e_hit"] = double(k.embreeHits) / n;
    state.counters["both"] = double(a.both) / n;
    state.counters["both_far"] = double(a.bothFar) / n;
    state.counters["m_only"] = double(a.marcherOnly) / n;
    state.counters["e_only"] = double(a.embreeOnly) / n;
    state.counters["agree_tol"] = kAgreeScale * w.diagonal;
    state.SetLabel(std::string(isaName(isa)));
}

const char* kindName(SsrMethod m) { return m == SsrMethod::Mirror ? "mirror" : "vndf"; }

// Registered in this order: Embree alone first, then the marchers beside it.
const bool kRegistered = [] {
    const char* scenes[] = {"corridor", "cornell"};
    const SsrMethod kinds[] = {SsrMethod::Mirror, SsrMethod::VndfBounded};
    for (const char* s : scenes)
        for (SsrMethod k : kinds)
            for (EmbreeMode mode : {EmbreeMode::Single, EmbreeMode::Packet16, EmbreeMode::Exact}) {
                const std::string name =
                    std::string("VsEmbree_embree/") + s + "_" + kindName(k) + modeName(mode);
                benchmark::RegisterBenchmark(name.c_str(), embreeBench, std::string(s), k, mode)
                    ->Arg(1)
                    ->Arg(2)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
            }
    for (const char* s : scenes)
        for (SsrMethod k : kinds)
            for (Marcher m : {Marcher::Linear, Marcher::Dda, Marcher::HiZ}) {
                const std::string name = std::string("VsEmbree_") + std::string(marcherName(m)) +
                                         "/" + s + "_" + kindName(k);
                benchmark::RegisterBenchmark(name.c_str(), marcherBench, std::string(s), k, m)
                    ->Arg(1)
                    ->Arg(2)
                    ->Unit(benchmark::kMillisecond)
                    ->UseManualTime();
            }
    return true;
}();

}  // namespace
