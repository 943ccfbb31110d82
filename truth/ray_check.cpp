#include "truth/ray_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/plane_view.h"
#include "core/tiles.h"

namespace ssrt {

std::string_view rayClassName(RayClass c) {
    switch (c) {
        case RayClass::NoRay: return "no_ray";
        case RayClass::Agreed: return "agreed";
        case RayClass::FalseHit: return "false_hit";
        case RayClass::MissedOnScreen: return "missed_on_screen";
        case RayClass::TrueMiss: return "true_miss";
        case RayClass::OffScreenTruth: return "offscreen_truth";
    }
    return "?";
}

// ---- Table ------------------------------------------------------------------------------

void RayCheckTable::add(const RayCheckTable& o) {
    rays += o.rays;
    for (int i = 0; i < kRayClassCount; ++i) count[i] += o.count[i], world[i] += o.world[i];
    pixelError.insert(pixelError.end(), o.pixelError.begin(), o.pixelError.end());
    depthError.insert(depthError.end(), o.depthError.begin(), o.depthError.end());
    embreeSeconds += o.embreeSeconds;
    embreeHits += o.embreeHits;
}

uint64_t RayCheckTable::worldRays() const {
    uint64_t n = 0;
    for (uint64_t c : world) n += c;
    return n;
}

double RayCheckTable::screenShare(RayClass c) const {
    return rays ? double(count[int(c)] - world[int(c)]) / double(rays) : 0.0;
}

void RayCheckTable::finish() {
    std::sort(pixelError.begin(), pixelError.end());
    std::sort(depthError.begin(), depthError.end());
}

double RayCheckTable::share(RayClass c) const {
    return rays ? double(count[int(c)]) / double(rays) : 0.0;
}

float RayCheckTable::quantile(const std::vector<float>& sorted, double q) {
    if (sorted.empty()) return 0.0f;
    // Nearest rank: the smallest value with at least ceil(q n) values at or below it (the
    // errors hold infinities, which an interpolation would turn into NaN).
    const double n = double(sorted.size());
    const double rank = std::ceil(std::clamp(q, 0.0, 1.0) * n);
    const std::size_t i = rank < 1.0 ? 0 : std::size_t(rank) - 1;
    return sorted[std::min(i, sorted.size() - 1)];
}

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kPacketSide = 4;  // 4x4 pixels: one 16-ray Embree packet

// Where a batch's pixels lie: the frame's own, or the half frame's, each standing for its
// block's chosen pixel (trace/trace_layout.h). The rays' view-space origins and directions are
// the march's in either case (both cameras share the view), so Embree traces them as they are;
// what the march found is moved into the frame's pixels, where the truth is projected and
// judged, and where the per-pixel planes hold it.
struct BatchGrid {
    const TraceCamera& frame;
    const TraceCamera& batch;  // the camera the rays were marched on (the frame's, or the half's)
    const HalfFrame* half;

    BatchGrid(const TraceCamera& f, const HalfFrame* h)
        : frame(f), batch(h ? h->camera : f), half(h) {}
    PixelOffset framePixel(int x, int y) const {
        return half ? halfSource(x, y, half->offset, frame.width, frame.height) : PixelOffset{x, y};
    }
    // A continuous position in the batch's pixels as the frame's: through the view-space slope
    // (x / z, y / z) both cameras project by (for the half camera of an even size, 2 x).
    void toFramePixels(float& x, float& y) const {
        if (!half) return;
        // (The march reads a half pixel's sample at its centre; it lies at pointX, pointY.)
        x += batch.pointX - 0.5f;
        y += batch.pointY - 0.5f;
        const float sx = (x / float(batch.width) * 2.0f - 1.0f) * batch.tanHalfX;
        const float sy = (1.0f - y / float(batch.height) * 2.0f) * batch.tanHalfY;
        x = (sx / frame.tanHalfX * 0.5f + 0.5f) * float(frame.width);
        y = (0.5f - sy / frame.tanHalfY * 0.5f) * float(frame.height);
    }
};

void requireSizes(const BatchGrid& g, const PlaneF& viewZ, const RayBatch& rays,
                  const MarchResult& m) {
    if (g.frame.width <= 0 || g.frame.height <= 0 || g.batch.width <= 0 || g.batch.height <= 0)
        throw std::invalid_argument("checkRays: the camera has no pixels");
    requireViews("checkRays", g.frame.width, g.frame.height, {viewOf(viewZ, "viewZ")});
    // Every plane of the batches, by its table's name.
    const auto batchPlane = [&](std::string_view name, const PlaneF& p) {
        requireViews("checkRays", g.batch.width, g.batch.height, {viewOf(p, name)});
    };
    rays.forEachPlane(batchPlane);
    m.forEachPlane(batchPlane);
}

glm::vec3 viewOrigin(const RayBatch& r, int x, int y) {
    return {r.ox.at(x, y), r.oy.at(x, y), r.oz.at(x, y)};
}

glm::vec3 viewDirection(const RayBatch& r, int x, int y) {
    return {r.dx.at(x, y), r.dy.at(x, y), r.dz.at(x, y)};
}

// The world ray of a view-space ray: world = position + viewToWorld * view.
struct WorldFrame {
    glm::mat3 rotation;
    glm::vec3 position;

    explicit WorldFrame(const TraceCamera& c)
        : position(c.position[0], c.position[1], c.position[2]) {
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row) rotation[col][row] = c.viewToWorld[col * 3 + row];
    }
};

// Traces one 4x4 block's rays (pdf > 0) as one packet; writes each one's true t (0 for no
// hit) and leaves pixels without a ray at 0. Returns the hits.
uint64_t traceBlock(const EmbreeScene& embree, const WorldFrame& wf, const RayBatch& rays,
                    float tfar, int bx, int by, int bx1, int by1, PlaneF& trueT) {
    glm::vec3 org[16], dir[16];
    int px[16], py[16], n = 0;
    for (int y = by; y < by1; ++y)
        for (int x = bx; x < bx1; ++x) {
            trueT.at(x, y) = 0.0f;
            if (!(rays.pdf.at(x, y) > 0.0f)) continue;
            org[n] = wf.position + wf.rotation * viewOrigin(rays, x, y);
            dir[n] = wf.rotation * viewDirection(rays, x, y);
            px[n] = x, py[n] = y, ++n;
        }
    if (n == 0) return 0;
    EmbreeHit hits[16];
    embree.intersect16(n, org, dir, embree.epsilon(), tfar, hits);
    uint64_t count = 0;
    for (int k = 0; k < n; ++k) {
        if (!hits[k].hit) continue;
        trueT.at(px[k], py[k]) = hits[k].t;
        ++count;
    }
    return count;
}

// Embree's first hit for every ray, tile by tile in 4x4 packets: trueT per pixel of the batch.
uint64_t traceAll(const EmbreeScene& embree, const TraceCamera& batch, const RayBatch& rays,
                  float tfar, PlaneF& trueT, int threads) {
    const TileGrid grid(batch.width, batch.height);
    const WorldFrame wf(batch);
    std::vector<uint64_t> hits(std::size_t(grid.count()), 0);
    parallelForTiles(grid.count(), threads, [&](int tile) {
        const TileRect r = grid.rect(tile);
        for (int by = r.y0; by < r.y1; by += kPacketSide)
            for (int bx = r.x0; bx < r.x1; bx += kPacketSide)
                hits[std::size_t(tile)] +=
                    traceBlock(embree, wf, rays, tfar, bx, by, std::min(bx + kPacketSide, r.x1),
                               std::min(by + kPacketSide, r.y1), trueT);
    });
    uint64_t total = 0;
    for (uint64_t h : hits) total += h;
    return total;
}

// Where the true hit sits in the frame, and whether the camera sees it there.
struct TrueHit {
    bool exists = false;
    float t = 0.0f;
    glm::vec3 point{0.0f};       // view space
    float z = 0.0f;              // view Z (positive in front of the camera)
    float px = 0.0f, py = 0.0f;  // continuous pixel position (when z > 0)
    bool projects = false;       // in front of the camera: px, py mean something
    bool visible = false;
};

TrueHit locateTrueHit(const TraceCamera& cam, const PlaneF& viewZ, const RayBatch& rays,
                      const RayCheckSettings& s, float t, int x, int y) {
    TrueHit h;
    if (!(t > 0.0f)) return h;
    h.exists = true;
    // The rotation keeps lengths: the view-space hit is o + t d.
    const glm::vec3 p = viewOrigin(rays, x, y) + t * viewDirection(rays, x, y);
    h.t = t;
    h.point = p;
    h.z = -p.z;
    if (!(h.z > 0.0f)) return h;
    h.projects = true;
    h.px = (p.x / (h.z * cam.tanHalfX) * 0.5f + 0.5f) * float(cam.width);
    h.py = (0.5f - p.y / (h.z * cam.tanHalfY) * 0.5f) * float(cam.height);
    // Between the near and far planes, as the rasterizer clips.
    if (h.z < cam.nearZ || h.z > cam.farZ || !(h.px >= 0.0f && h.px < float(cam.width)) ||
        !(h.py >= 0.0f && h.py < float(cam.height)))
        return h;
    // Visible: the pixel it lands on shows this depth (background shows nothing).
    const float z = viewZ.at(int(h.px), int(h.py));
    h.visible = z > 0.0f && std::abs(z - h.z) <= s.depthTolerance * h.z;
    return h;
}

struct PixelCheck {
    RayClass cls = RayClass::NoRay;
    bool bothHit = false;
    float pixelError = 0.0f, depthError = 0.0f;
};

PixelCheck classify(const BatchGrid& g, const MarchResult& m, const TrueHit& truth,
                    const RayCheckSettings& s, int x, int y) {
    PixelCheck c;
    if (!(m.hit.at(x, y) > 0.0f)) {
        c.cls = !truth.exists   ? RayClass::TrueMiss
                : truth.visible ? RayClass::MissedOnScreen
                                : RayClass::OffScreenTruth;
        return c;
    }
    c.cls = RayClass::FalseHit;
    if (!truth.exists) return c;
    // Both hit: the errors. A truth behind the camera has no pixel and no relative depth to
    // compare with, so both errors are infinite there (never Agreed).
    c.bothHit = true;
    const float inf = std::numeric_limits<float>::infinity();
    c.pixelError = inf;
    c.depthError = inf;
    if (truth.projects) {
        float hx = m.hitX.at(x, y), hy = m.hitY.at(x, y);
        g.toFramePixels(hx, hy);
        const float ex = hx - truth.px, ey = hy - truth.py;
        c.pixelError = std::sqrt(ex * ex + ey * ey);
        c.depthError = std::abs(m.hitZ.at(x, y) - truth.z) / truth.z;
    }
    // A world ray's hit that no pixel shows (mixed and world tracing) agrees where it is the
    // true hit, in front of the camera or behind it: its view-space point (hitZ negative behind
    // the camera) within the depth tolerance of the true distance (hitX, hitY in the pixels of
    // the camera it was marched on). One a pixel shows is a screen hit there, checked as the
    // march's are.
    if (m.cause.at(x, y) == float(MarchEnd::World)) {
        const float z = m.hitZ.at(x, y);
        const TraceCamera& b = g.batch;
        const glm::vec3 p{(2.0f * m.hitX.at(x, y) / float(b.width) - 1.0f) * b.tanHalfX * z,
                          (1.0f - 2.0f * m.hitY.at(x, y) / float(b.height)) * b.tanHalfY * z,
                          0.0f - z};
        if (glm::length(p - truth.point) <= s.depthTolerance * truth.t) c.cls = RayClass::Agreed;
        return c;
    }
    if (truth.visible && c.pixelError <= s.pixelTolerance && c.depthError <= s.depthTolerance)
        c.cls = RayClass::Agreed;
    return c;
}

void writePlanes(PlaneF* planes, const PixelCheck& c, float trueT, PixelOffset p) {
    if (!planes) return;
    planes[kCheckClass].at(p.x, p.y) = float(int(c.cls));
    planes[kCheckPixelError].at(p.x, p.y) = c.bothHit ? c.pixelError : 0.0f;
    planes[kCheckDepthError].at(p.x, p.y) = c.bothHit ? c.depthError : 0.0f;
    planes[kCheckTrueT].at(p.x, p.y) = trueT;
}

// Classifies one tile's rays (of the batch) into its own table (row order within the tile).
void classifyTile(const BatchGrid& g, const PlaneF& viewZ, const RayBatch& rays,
                  const MarchResult& m, const RayCheckSettings& s, const PlaneF& trueT,
                  PlaneF* planes, const TileRect& r, RayCheckTable& table) {
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            PixelCheck c;
            if (rays.pdf.at(x, y) > 0.0f) {
                const TrueHit truth = locateTrueHit(g.frame, viewZ, rays, s, trueT.at(x, y), x, y);
                c = classify(g, m, truth, s, x, y);
                ++table.rays;
                ++table.count[int(c.cls)];
                if (answeredInWorld(MarchEnd(int(m.cause.at(x, y))))) ++table.world[int(c.cls)];
                if (c.bothHit) {
                    table.pixelError.push_back(c.pixelError);
                    table.depthError.push_back(c.depthError);
                }
            }
            writePlanes(planes, c, trueT.at(x, y), g.framePixel(x, y));
        }
}

}  // namespace

RayCheckTable checkRays(const EmbreeScene& embree, const TraceCamera& cam, const PlaneF& viewZ,
                        const RayBatch& rays, const MarchResult& march,
                        const RayCheckSettings& settings, PlaneF* planes, int threads,
                        const HalfFrame* half) {
    const BatchGrid g(cam, half);
    requireSizes(g, viewZ, rays, march);
    requireSameOrigin(embree, cam, "checkRays");
    if (!(settings.maxDistance > 0.0f))
        throw std::invalid_argument("checkRays: maxDistance must be > 0");
    if (planes)
        for (int i = 0; i < kCheckChannels; ++i) {
            planes[i].ensureSize(cam.width, cam.height);
            // (The half frame's rays write only their chosen pixels: the others hold no ray.)
            if (half) planes[i].fill(0.0f);
        }
    // Embree first, alone, so that its wall clock is its own.
    PlaneF trueT(g.batch.width, g.batch.height);
    RayCheckTable total;
    const auto t0 = Clock::now();
    total.embreeHits = traceAll(embree, g.batch, rays, settings.maxDistance, trueT, threads);
    total.embreeSeconds = std::chrono::duration<double>(Clock::now() - t0).count();

    // Then the classes, per tile of the batch, combined in tile order.
    const TileGrid grid(g.batch.width, g.batch.height);
    std::vector<RayCheckTable> tiles(std::size_t(grid.count()));
    parallelForTiles(grid.count(), threads, [&](int tile) {
        classifyTile(g, viewZ, rays, march, settings, trueT, planes, grid.rect(tile),
                     tiles[std::size_t(tile)]);
    });
    for (const RayCheckTable& t : tiles) total.add(t);
    return total;
}

}  // namespace ssrt
