// The reference image (truth/reference_image.h): the direct pass's sun with Embree's
// (or the shadow map's) visibility, and the frame's own SSR and SSGI sample sequences, many
// samples of them, traced by Embree.
#include "truth/reference_image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/tiles.h"
#include "renderer/direct_lighting.h"
#include "shading/brdf.h"
#include "shading/sampling.h"
#include "truth/parts.h"
#include "world/hit_light.h"

namespace ssrt {

namespace {

using worldhit::PointSurface;
using worldhit::ShadingContext;
namespace ln = ssrt::lanes;

// The resolve's cap on one ray's weight (trace/ssr_resolve_kernel.cpp): sums stay finite.
constexpr float kMaxWeight = 1.0e20f;
// Enough for any convergence; bounds the progress steps and the run time a typo can ask for.
constexpr int kMaxSpp = 1 << 16;
// Rays per Embree packet: a 4x4 block of pixels (Embree's 16-wide packets).
constexpr int kBlock = 4;

// Progress in steps, reported from the calling thread at most kReports + 1 times.
class ProgressSteps {
public:
    ProgressSteps(const Progress& fn, int total) : fn_(fn), total_(total) {}
    void step() {
        ++done_;
        const int bucket = int(int64_t(done_) * kReports / total_);
        if (fn_ && (bucket > reported_ || done_ == total_)) {
            reported_ = bucket;
            fn_(double(done_) / double(total_));
        }
    }

private:
    static constexpr int kReports = 200;
    const Progress& fn_;
    int total_, done_ = 0, reported_ = -1;
};

// Everything a pass reads, set up once.
struct Setup {
    const Frame& frame;
    DirectLighting lighting;  // with the frame's G-buffer and camera filled in
    ShadingContext ctx;
    Isa isa = Isa::Scalar;
    int threads = 0;
    TileGrid grid{1, 1};
    float maxDistance = 0.0f;
    SsrMethod ssrMethod = SsrMethod::VndfBounded;  // the frame's SSR sampler
    uint32_t frameIndex = 0;                       // the frame's RNG frame
    std::vector<glm::vec3> offset;                 // per pixel: surfaceOffsets
    int firstTile = 0, tileCount = 0;              // the band's tiles (row-major, whole rows)
    const std::atomic<bool>* cancel = nullptr;     // ReferenceSettings::cancel
    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
    explicit Setup(const Frame& f) : frame(f) {}
};

// fn(tile) for the band's tiles, on the setup's threads. Every pixel's value depends only on
// its own rays (per-pixel random numbers), so a band's pixels are the whole frame's bits.
// Once the cancel flag is up the remaining tiles are skipped and the reference ends.
template <class Fn>
void forBandTiles(const Setup& s, Fn&& fn) {
    parallelForTiles(s.tileCount, s.threads, [&](int t) {
        if (!s.cancelled()) fn(s.firstTile + t);
    });
    if (s.cancelled()) throw ReferenceCancelled();
}

void requireTraced(const Frame& frame, const RenderSettings& rs) {
    if (frame.width != rs.width || frame.height != rs.height)
        throw std::invalid_argument("reference: the frame was not rendered with these settings");
    if (!frame.stats.ssr.ran || !frame.stats.ssgi.ran)
        throw std::invalid_argument("reference: the frame needs both trace passes (SSR and SSGI)");
    if (frame.direct.direct[0].width() != frame.width ||
        frame.direct.direct[0].height() != frame.height)
        throw std::invalid_argument("reference: the frame has no direct parts");
}

void fillSetup(Setup& s, const EmbreeScene& embree, const Renderer& renderer,
               const ReferenceSettings& settings) {
    const Frame& f = s.frame;
    const RenderSettings& rs = renderer.settings();
    const Scene& scene = embree.scene();
    std::shared_ptr<const SkyLighting> sky;
    if (scene.sky.kind == Sky::Kind::Image) sky = cachedSkyLighting(scene.sky.image, rs.threads);
    setDirectLighting(scene, rs, f.scratch.shadow, std::move(sky), s.lighting);
    DirectArgs& a = s.lighting.args;
    setDirectGBuffer(f.gbuffer, a);
    a.width = f.width;
    a.height = f.height;
    a.tanHalfX = f.camera.tanHalfX;
    a.tanHalfY = f.camera.tanHalfY;
    std::copy_n(f.camera.viewToWorld, 9, a.viewToWorld);
    requireSameOrigin(embree, f.camera, "the reference");
    std::copy_n(f.camera.position, 3, a.camPos);
    s.ctx = {&a, &embree, settings.visibility};
    s.isa = resolveIsa(rs.isa);
    s.threads = rs.threads;
    s.grid = TileGrid(f.width, f.height);
    s.firstTile = 0;
    s.tileCount = s.grid.count();
    s.maxDistance = settings.maxDistance;
    s.ssrMethod = rs.trace.ssrMethod;
    s.frameIndex = f.index;
}

glm::vec3 rotate(const float* m, glm::vec3 v) {
    return {(m[0] * v.x + m[3] * v.y) + m[6] * v.z, (m[1] * v.x + m[4] * v.y) + m[7] * v.z,
            (m[2] * v.x + m[5] * v.y) + m[8] * v.z};
}

void ensure3(PlaneF p[3], int w, int h) {
    for (int c = 0; c < 3; ++c) p[c].ensureSize(w, h);
}

// How far along the unit ray from the camera away from `toCam` the near plane lies: what lies
// nearer, the rasterizer clipped, so Embree's primary hit must not see it either.
float nearDistance(const Setup& s, glm::vec3 toCam) {
    const float* r = s.frame.camera.viewToWorld;  // column 2 is the view's +Z, behind the camera
    const float cosine = glm::dot(toCam, glm::vec3(r[6], r[7], r[8]));
    return s.frame.camera.nearZ / cosine;
}

// Per surface pixel, the step off its surface that every ray leaving it takes: epsilon
// along the geometric normal, on the camera's side. The G-buffer's point is the true one
// only to float rounding (1e-5 below a floor seen at a distance is typical), enough for a
// grazing ray to hit the pixel's own surface from behind; and the G-buffer has no geometric
// normal (its shading normal would self-shadow at low-poly terminators), so Embree's primary
// hit through the pixel gives it. A pixel Embree misses (a silhouette) steps along its
// shading normal.
void surfaceOffsets(Setup& s) {
    const DirectArgs& a = s.lighting.args;
    const EmbreeScene& embree = *s.ctx.embree;
    const glm::vec3 cam(a.camPos[0], a.camPos[1], a.camPos[2]);
    s.offset.assign(std::size_t(a.width) * a.height, glm::vec3(0.0f));
    forBandTiles(s, [&](int tile) {
        const TileRect r = s.grid.rect(tile);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                if (!(a.g.viewZ[std::size_t(y) * a.g.stride + x] > 0.0f)) continue;
                const PointSurface ps = worldhit::pixelSurface(a, x, y);
                const glm::vec3 toCam(ps.view.x, ps.view.y, ps.view.z);
                glm::vec3 n(ps.n.x, ps.n.y, ps.n.z);
                const EmbreeHit h = embree.intersect(cam, -toCam, nearDistance(s, toCam), INFINITY);
                if (h.hit) {
                    n = embree.surface(cam, -toCam, h).geometricNormal;
                    if (glm::dot(n, toCam) < 0.0f) n = -n;
                }
                s.offset[std::size_t(y) * a.width + x] = n * embree.epsilon();
            }
    });
}

glm::vec3 pointOf(const PointSurface& ps) { return {ps.p.x, ps.p.y, ps.p.z}; }

// Direct: the sun part of each surface pixel with the chosen visibility; the sky (the frame's
// own direct part) on background pixels.
void renderDirect(const Setup& s, PlaneF out[3]) {
    const DirectArgs& a = s.lighting.args;
    const PlaneU16* frameDirect = s.frame.direct.direct;  // f16
    forBandTiles(s, [&](int tile) {
        const TileRect r = s.grid.rect(tile);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                if (!(a.g.viewZ[std::size_t(y) * a.g.stride + x] > 0.0f)) {
                    for (int c = 0; c < 3; ++c)
                        out[c].at(x, y) = decodeF16(frameDirect[c].at(x, y));
                    continue;
                }
                const PointSurface ps = worldhit::pixelSurface(a, x, y);
                const glm::vec3 origin = pointOf(ps) + s.offset[std::size_t(y) * a.width + x];
                const float vis = worldhit::sunVisibility(s.ctx, ps, origin);
                const shade::Parts<float> parts = shade::shadeSurface(a, ps, vis);
                out[0].at(x, y) = parts.sun.x;
                out[1].at(x, y) = parts.sun.y;
                out[2].at(x, y) = parts.sun.z;
            }
    });
}

// One traced ray of a pixel: its world direction, pdf and the radiance it brought back.
struct TracedRay {
    int x, y;
    glm::vec3 dir;
    float pdf;
    glm::vec3 radiance;
};

// Traces one sample's rays (view space, as generated) of one tile with Embree, 16 at a time
// over 4x4 pixel blocks, and hands each to `use` in pixel order. shadeHit(ray, origin, hit)
// gives a hit's radiance (SSR: the whole direct model; SSGI: the diffuse path).
template <class ShadeHit, class Use>
void traceTile(const Setup& s, const RayBatch& rays, int tile, ShadeHit&& shadeHit, Use&& use) {
    const DirectArgs& a = s.lighting.args;
    const EmbreeScene& embree = *s.ctx.embree;
    const glm::vec3 cam(a.camPos[0], a.camPos[1], a.camPos[2]);
    const TileRect r = s.grid.rect(tile);
    for (int by = r.y0; by < r.y1; by += kBlock)
        for (int bx = r.x0; bx < r.x1; bx += kBlock) {
            std::array<glm::vec3, 16> org, dir;
            std::array<TracedRay, 16> out;
            int n = 0;
            for (int y = by; y < std::min(by + kBlock, r.y1); ++y)
                for (int x = bx; x < std::min(bx + kBlock, r.x1); ++x) {
                    const float pdf = rays.pdf.at(x, y);
                    if (!(pdf > 0.0f)) continue;
                    const glm::vec3 o(rays.ox.at(x, y), rays.oy.at(x, y), rays.oz.at(x, y));
                    const glm::vec3 d(rays.dx.at(x, y), rays.dy.at(x, y), rays.dz.at(x, y));
                    // The frame's ray, stepped off its surface (surfaceOffsets).
                    org[n] =
                        (cam + rotate(a.viewToWorld, o)) + s.offset[std::size_t(y) * a.width + x];
                    dir[n] = glm::normalize(rotate(a.viewToWorld, d));
                    out[n] = {x, y, dir[n], pdf, glm::vec3(0.0f)};
                    ++n;
                }
            if (n == 0) continue;
            std::array<EmbreeHit, 16> hits;
            embree.intersect16(n, org.data(), dir.data(), embree.epsilon(), s.maxDistance,
                               hits.data());
            for (int i = 0; i < n; ++i) {
                out[i].radiance = hits[i].hit ? shadeHit(out[i], org[i], hits[i])
                                              : worldhit::missRadiance(s.ctx, dir[i]);
                use(out[i]);
            }
        }
}

// The resolve's weight of a ray for its own pixel: D V n.l / pdf (the pixel's GGX lobe over
// the sampler's pdf, capped like the resolve's), 0 below the pixel's horizon.
float ssrWeight(const PointSurface& ps, glm::vec3 dir, float pdf) {
    using namespace ssrt::brdf;
    const ln::V3<float> l{dir.x, dir.y, dir.z};
    const float NoLraw = ln::dot(ps.n, l);
    if (!(NoLraw > 0.0f)) return 0.0f;
    const float NoL = ln::saturate(NoLraw);
    const float NoV = std::max(ln::dot(ps.n, ps.view), 1e-4f);
    const float NoH = ln::saturate(ln::dot(ps.n, ln::normalize(ps.view + l)));
    const float alpha = roughnessToAlpha(ps.roughness);
    return std::min(D_GGX(NoH, alpha) * V_SmithGGXCorrelated(NoV, NoL, alpha) * NoL / pdf,
                    kMaxWeight);
}

// Per-pixel sums over samples, in double (spp can be large), in sample order per pixel.
struct Sums {
    int width = 0;
    std::vector<double> w, l[3];
    Sums(int wd, int h) : width(wd), w(std::size_t(wd) * h, 0.0) {
        for (auto& v : l) v.assign(w.size(), 0.0);
    }
    void add(int x, int y, double weight, glm::vec3 radiance) {
        const std::size_t i = std::size_t(y) * width + x;
        w[i] += weight;
        for (int c = 0; c < 3; ++c) l[c][i] += weight * double(radiance[c]);
    }
};

// SSR: the weighted mean of `spp` rays' radiance; a pixel none of whose rays weighs anything
// (its lobe never left the surface) keeps the prefiltered sky, as the frame's opacity 0 does.
void renderSsr(const Setup& s, int spp, ProgressSteps& progress, PlaneF out[3]) {
    const Frame& f = s.frame;
    Sums sums(f.width, f.height);
    RayBatch rays;
    const DirectArgs& a = s.lighting.args;
    for (int k = 0; k < spp; ++k) {
        generateSpecularRays(s.isa, s.ssrMethod, s.frameIndex, uint32_t(k), f.camera,
                             s.lighting.args.g, rays, s.threads);
        forBandTiles(s, [&](int tile) {
            const auto shade = [&](const TracedRay& t, glm::vec3 o, const EmbreeHit& h) {
                return worldhit::hitRadiance(s.ctx, o, t.dir, h, true);
            };
            traceTile(s, rays, tile, shade, [&](const TracedRay& t) {
                const PointSurface ps = worldhit::pixelSurface(a, t.x, t.y);
                sums.add(t.x, t.y, ssrWeight(ps, t.dir, t.pdf), t.radiance);
            });
        });
        progress.step();
    }
    const PlaneU16* envSpecular = f.direct.envSpecular;  // f16
    const PlaneF& viewZ = f.gbuffer.viewZ;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const std::size_t i = std::size_t(y) * f.width + x;
            for (int c = 0; c < 3; ++c)
                out[c].at(x, y) = !(viewZ.at(x, y) > 0.0f) ? 0.0f
                                  : sums.w[i] > 0.0        ? float(sums.l[c][i] / sums.w[i])
                                                           : decodeF16(envSpecular[c].at(x, y));
        }
}

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited": the local direction l (normal
// on +z) around the unit normal n.
glm::vec3 aroundNormal(glm::vec3 n, const ln::V3<float>& l) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    const glm::vec3 t(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const glm::vec3 bt(b, sign + n.y * n.y * a, -n.y);
    return glm::normalize((t * l.x + bt * l.y) + n * l.z);
}

// An SSGI ray's radiance as a diffuse path of up to `bounces` hits (reference_image.h):
// L = L_1 + r_1 (L_2 + r_2 (...)), summed forward with the path's throughput. One bounce is
// hitRadiance's SSGI light itself: the one-bounce reference to the bit.
glm::vec3 diffusePath(const Setup& s, const TracedRay& ray, glm::vec3 origin, const EmbreeHit& hit,
                      uint32_t sample, int bounces) {
    if (bounces == 1) return worldhit::hitRadiance(s.ctx, origin, ray.dir, hit, false);
    // Converged: up to kMaxBounces hits, ending where the throughput is negligible. A fixed
    // count ends only where it is 0, so its N bounces are exactly N.
    const bool converged = bounces == ReferenceSettings::kConverged;
    const float negligible = converged ? ReferenceSettings::kNegligibleThroughput : 0.0f;
    if (converged) bounces = ReferenceSettings::kMaxBounces;
    const EmbreeScene& embree = *s.ctx.embree;
    const uint32_t pixel = uint32_t(ray.y) * uint32_t(s.frame.width) + uint32_t(ray.x);
    worldhit::DiffuseVertex v = worldhit::diffuseVertex(s.ctx, origin, ray.dir, hit);
    glm::vec3 radiance = v.radiance, throughput = v.reflectance;
    for (int k = 1; k < bounces; ++k) {
        if (!(std::max({throughput.x, throughput.y, throughput.z}) > negligible)) break;
        // The next direction: cosine-weighted around x_k's shading normal.
        const uint32_t dim = kReferenceBounceDim + 2u * uint32_t(k - 1);
        const float u1 = randomFloat(pixel, s.frameIndex, sample, dim);
        const float u2 = randomFloat(pixel, s.frameIndex, sample, dim + 1u);
        const glm::vec3 dir = aroundNormal(v.normal, sampling::sampleCosineHemisphere(u1, u2));
        if (!(glm::dot(dir, v.geometricNormal) > 0.0f)) break;  // into its own surface
        // From 0: the origin is already epsilon off its surface, and a near start of epsilon
        // would step through a wall that close (a hit within epsilon of a corner), letting
        // the path escape; the plane it leaves lies behind it.
        const EmbreeHit h = embree.intersect(v.origin, dir, 0.0f, s.maxDistance);
        if (!h.hit) {
            radiance += throughput * worldhit::missRadiance(s.ctx, dir);
            break;
        }
        v = worldhit::diffuseVertex(s.ctx, v.origin, dir, h);
        radiance += throughput * v.radiance;
        throughput *= v.reflectance;
    }
    return radiance;
}

// SSGI: the plain mean of `spp` cosine rays' radiance (a pixel without a ray in a sample adds
// 0 for it, as trace/ssgi.h counts), each ray a diffuse path of `bounces` hits.
void renderSsgi(const Setup& s, int spp, int bounces, ProgressSteps& progress, PlaneF out[3]) {
    const Frame& f = s.frame;
    Sums sums(f.width, f.height);
    RayBatch rays;
    for (int k = 0; k < spp; ++k) {
        generateDiffuseRays(s.isa, s.frameIndex, uint32_t(k), f.camera, s.lighting.args.g, rays,
                            s.threads);
        forBandTiles(s, [&](int tile) {
            const auto shade = [&](const TracedRay& t, glm::vec3 o, const EmbreeHit& h) {
                return diffusePath(s, t, o, h, uint32_t(k), bounces);
            };
            traceTile(s, rays, tile, shade,
                      [&](const TracedRay& t) { sums.add(t.x, t.y, 1.0, t.radiance); });
        });
        progress.step();
    }
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            for (int c = 0; c < 3; ++c)
                out[c].at(x, y) = float(sums.l[c][std::size_t(y) * f.width + x] / double(spp));
}

}  // namespace

RowBand referenceBand(int height, int index, int count) {
    if (height < 1 || count < 1 || index < 0 || index >= count)
        throw std::invalid_argument("reference band " + std::to_string(index) + " of " +
                                    std::to_string(count) + " of " + std::to_string(height) +
                                    " rows");
    const long long tileRows = (height + kTileSize - 1) / kTileSize;
    const auto rowOf = [&](long long k) {
        return int(std::min<long long>(height, tileRows * k / count * kTileSize));
    };
    return {rowOf(index), rowOf(index + 1)};
}

void ReferenceSettings::validate() const {
    if (spp < 1 || spp > kMaxSpp)
        throw std::invalid_argument("reference spp must be between 1 and " +
                                    std::to_string(kMaxSpp));
    if (!std::isfinite(maxDistance) || !(maxDistance > 0.0f))
        throw std::invalid_argument("reference maxDistance must be finite and > 0");
    if (bounces != kConverged && (bounces < 1 || bounces > kMaxBounces))
        throw std::invalid_argument("reference bounces must be between 1 and " +
                                    std::to_string(kMaxBounces) + ", or converged");
}

ReferenceImage renderReference(const EmbreeScene& embree, const Renderer& renderer,
                               const Frame& frame, const ReferenceSettings& settings,
                               const Progress& progress, std::optional<RowBand> band) {
    settings.validate();
    requireTraced(frame, renderer.settings());
    Setup s(frame);
    s.cancel = settings.cancel;
    fillSetup(s, embree, renderer, settings);
    if (band) {
        if (band->y0 < 0 || band->y0 >= band->y1 || band->y1 > frame.height ||
            band->y0 % kTileSize != 0 || (band->y1 % kTileSize != 0 && band->y1 != frame.height))
            throw std::invalid_argument("reference: rows [" + std::to_string(band->y0) + ", " +
                                        std::to_string(band->y1) +
                                        ") are not a band of whole tile rows of the frame");
        const int firstRow = band->y0 / kTileSize;
        const int endRow = (band->y1 + kTileSize - 1) / kTileSize;
        s.firstTile = firstRow * s.grid.tilesX;
        s.tileCount = (endRow - firstRow) * s.grid.tilesX;
    }
    const int w = frame.width, h = frame.height;
    ReferenceImage ref;
    for (PlaneF* p : {ref.color, ref.direct, ref.ssr, ref.ssgi, ref.specular, ref.diffuse})
        ensure3(p, w, h);
    ProgressSteps steps(progress, 1 + 2 * settings.spp);
    surfaceOffsets(s);
    renderDirect(s, ref.direct);
    steps.step();
    renderSsr(s, settings.spp, steps, ref.ssr);
    renderSsgi(s, settings.spp, settings.bounces, steps, ref.ssgi);
    composeReference(s.isa, frame, renderer.settings().exposure, s.lighting.args.anyEmissive,
                     s.threads, ref);
    return ref;
}

}  // namespace ssrt
