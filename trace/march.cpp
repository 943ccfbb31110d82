#include "trace/march.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/plane_view.h"
#include "core/rng.h"
#include "core/tiles.h"
#include "trace/march_fields.h"
#include "trace/march_kernel.h"

namespace ssrt {

std::string_view marcherName(Marcher marcher) {
    switch (marcher) {
        case Marcher::Linear: return "linear";
        case Marcher::Dda: return "dda";
        case Marcher::HiZ: return "hiz";
    }
    return "?";
}

std::optional<Marcher> parseMarcher(std::string_view name) {
    for (Marcher m : {Marcher::Linear, Marcher::Dda, Marcher::HiZ})
        if (marcherName(m) == name) return m;
    return std::nullopt;
}

static_assert(kLastHiZLevel == kMaxHiZLevels - 1);

void MarchSettings::validate() const {
    // Each field in its range (trace/march_fields.h), then the levels' order.
    checkFields(kMarchFields, *this, "MarchSettings");
    if (hizStartLevel < hizMostDetailedLevel)
        throw std::invalid_argument(
            "MarchSettings.hizStartLevel: expected a level >= hizMostDetailedLevel (" +
            std::to_string(hizMostDetailedLevel) + "), got " + std::to_string(hizStartLevel));
}

MarchLengths marchLengths(const MarchSettings& s, float sceneDiagonal) {
    MarchLengths l{};
    if (s.maxDistanceAbsolute > 0.0f) {
        l.maxDistance = s.maxDistanceAbsolute;
    } else {
        if (!std::isfinite(sceneDiagonal) || !(sceneDiagonal > 0.0f))
            throw std::invalid_argument(
                "marchRays: a relative maxDistance needs the camera's sceneDiagonal (finite, > 0)");
        l.maxDistance = s.maxDistance * sceneDiagonal;
    }
    const bool absStep = s.linearStepAbsolute > 0.0f;
    l.stepScale = absStep ? 0.0f : s.linearStep;
    l.stepBias = absStep ? s.linearStepAbsolute : 0.0f;
    const bool absThick = s.thicknessAbsolute > 0.0f;
    l.thicknessScale = absThick ? 0.0f : s.thickness;
    l.thicknessBias = absThick ? s.thicknessAbsolute : 0.0f;
    return l;
}

// ---- Statistics -------------------------------------------------------------------------

void MarchStats::add(const MarchStats& o) {
    rays += o.rays;
    for (int i = 0; i < kMarchEndCount; ++i) ends[i] += o.ends[i];
    steps += o.steps;
    laneSlots += o.laneSlots;
    laneActive += o.laneActive;
    if (stepHistogram.size() < o.stepHistogram.size()) stepHistogram.resize(o.stepHistogram.size());
    for (std::size_t i = 0; i < o.stepHistogram.size(); ++i) stepHistogram[i] += o.stepHistogram[i];
}

double MarchStats::meanSteps() const { return rays ? double(steps) / double(rays) : 0.0; }

int MarchStats::stepsPercentile(double p) const {
    uint64_t total = 0;
    for (uint64_t c : stepHistogram) total += c;
    if (total == 0) return 0;
    // The smallest step count s with at least ceil(p total) rays at or below it.
    const double want = std::clamp(p, 0.0, 1.0) * double(total);
    uint64_t seen = 0;
    for (std::size_t s = 0; s < stepHistogram.size(); ++s) {
        seen += stepHistogram[s];
        if (double(seen) >= want && seen > 0) return int(s);
    }
    return int(stepHistogram.size()) - 1;
}

int MarchStats::maxStepsTaken() const {
    for (std::size_t s = stepHistogram.size(); s-- > 0;)
        if (stepHistogram[s]) return int(s);
    return 0;
}

// ---- The pass ---------------------------------------------------------------------------

namespace {

// One tile's packed rays and results (structure of arrays, padded to kMarchPad).
struct TileScratch {
    enum {
        kOx,
        kOy,
        kOz,
        kDx,
        kDy,
        kDz,
        kPx,
        kPy,
        kJitter,
        kHit,
        kHitX,
        kHitY,
        kHitZ,
        kSteps,
        kCause,
        kArrays
    };
    std::vector<float> data;
    std::vector<int8_t> key;  // per tile pixel: the ray's bucket, -1 for no ray
    std::size_t capacity = 0;
    float* array(int i) { return data.data() + std::size_t(i) * capacity; }
};

// Rays are packed bucket by bucket: 64 sectors of the ray's screen-space direction at its
// origin, times toward / away from the camera (128 buckets); within a bucket in 4x4 pixel
// blocks (block rows, then rows in a block). Neighbouring rays of one bucket take similar
// paths, so a lane group's rays end after similar step counts (fewer idle lanes) and read
// nearby cells. Only the order of the rays changes: each lane's path depends on its own ray
// alone, so no result bit does (tests/trace/march_test.cpp holds every ray to the same ray
// marched alone). The keys come from marchSortKeys (trace/march_keys_kernel.cpp): the screen
// direction of a view point's motion along the ray (origin o, direction d) is (sx (o.x d.z -
// d.x o.z), sy (d.y o.z - o.y d.z)) up to a positive factor (the derivative of x/(-z), y/(-z)
// along the ray); its angle is binned by the "diamond angle" in [0, 4), monotonic in the
// angle, no arctangent.
constexpr int kSortBuckets = 2 * kSortSectors;
constexpr int kSortBlock = 4;
// marchSortKeys reads a tile's row segments in whole lane groups: tiles start at multiples
// of the widest group, and plane rows are padded to one (core/image.h).
static_assert(kTileSize % kMarchPad == 0);

}  // namespace

RayMarcher::RayMarcher(Isa isa, Marcher marcher, const MarchSettings& settings, RaySeed seed,
                       const TraceCamera& camera, const GBufferView& g, const PlaneF* backZ,
                       const HiZPyramid* hiz, int threads)
    : grid_(camera.width, camera.height), seed_(seed), maxSteps_(settings.maxSteps) {
    settings.validate();
    const int w = camera.width, h = camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("marchRays: the camera has no pixels");
    if (!(camera.tanHalfX > 0.0f) || !(camera.tanHalfY > 0.0f) || !(camera.nearZ > 0.0f))
        throw std::invalid_argument("marchRays: camera needs tanHalfX, tanHalfY, nearZ > 0");
    requireGBuffer("marchRays", g, kGViewZ | kGNormal, w, h);

    MarchKernelArgs& proto = proto_;
    proto.width = w;
    proto.height = h;
    proto.sx = float(w) / (2.0f * camera.tanHalfX);
    proto.sy = float(h) / (2.0f * camera.tanHalfY);
    // A pixel's sample at (i + pointX, j + pointY) of the camera projects to (i + 0.5,
    // j + 0.5), where the march reads it (TraceCamera::pointX: a half frame's chosen pixel).
    proto.cx = float(w) * 0.5f - (camera.pointX - 0.5f);
    proto.cy = float(h) * 0.5f - (camera.pointY - 0.5f);
    proto.nearZ = camera.nearZ;
    std::copy(camera.viewToWorld, camera.viewToWorld + 9, proto.viewToWorld);
    proto.g = g;
    proto.backZ = nullptr;
    if (settings.backFaces && backZ) {
        const ViewF back = viewOf(*backZ, "backZ");
        requireViews("marchRays", w, h, {back});
        proto.backZ = back.data;
        if (backZ->stride() != g.stride)
            throw std::invalid_argument("marchRays: backZ and viewZ of different strides");
    }
    proto.maxSteps = settings.maxSteps;
    const MarchLengths lengths = marchLengths(settings, camera.sceneDiagonal);
    proto.maxDistance = lengths.maxDistance;
    proto.stepScale = lengths.stepScale;
    proto.stepBias = lengths.stepBias;
    proto.thicknessScale = lengths.thicknessScale;
    proto.thicknessBias = lengths.thicknessBias;
    proto.ddaStride = settings.ddaStride;
    proto.refineSteps = settings.refineSteps;
    if (marcher == Marcher::HiZ) {
        if (!hiz || hiz->levels() < 1 || hiz->minZ[0].width() != w || hiz->minZ[0].height() != h)
            throw std::invalid_argument("marchRays: the hiz marcher needs a pyramid of viewZ");
        proto.hizLevels = std::min(hiz->levels(), kMaxHiZLevels);
        for (int L = 0; L < proto.hizLevels; ++L) {
            const PlaneF& p = hiz->minZ[std::size_t(L)];
            proto.hizMin[L] = p.row(0);
            proto.hizStride[L] = p.stride();
            proto.hizWidth[L] = p.width();
            proto.hizHeight[L] = p.height();
            proto.hizWidthF[L] = float(p.width());
            proto.hizHeightF[L] = float(p.height());
        }
        // The packed reciprocal copy for the hardware gather: buildHiZ's, or made here for a
        // pyramid without one (of more than kMaxHiZLevels levels, only those are read).
        const HiZPacked* inv = &hiz->invMinPacked;
        std::vector<std::size_t> ownOffset;
        const std::vector<std::size_t>* offset = &hiz->packedOffset;
        if (inv->empty() || offset->size() != hiz->minZ.size()) {
            packInverseMin(hiz->minZ, packed_, ownOffset, threads);
            inv = &packed_, offset = &ownOffset;
        }
        if (!inv->empty()) {
            for (int L = 0; L < proto.hizLevels; ++L) {
                proto.hizOffset[L] = float((*offset)[std::size_t(L)]);
                proto.hizPitch[L] = float(hiZPackedPitch(proto.hizWidth[L]));
                proto.hizRowShift[L] = float(hiZPackedPitchLog2(proto.hizWidth[L]) + 4);
            }
            proto.hizInvPacked = inv->data();
        }
        proto.mostDetailedLevel = std::min(settings.hizMostDetailedLevel, proto.hizLevels - 1);
        proto.startLevel =
            std::clamp(settings.hizStartLevel, proto.mostDetailedLevel, proto.hizLevels - 1);
    }
    kernel_ = marcher == Marcher::Linear ? SSRT_DISPATCH(isa, marchLinearKernel)
              : marcher == Marcher::Dda  ? SSRT_DISPATCH(isa, marchDdaKernel)
                                         : SSRT_DISPATCH(isa, marchHiZKernel);
    sortKeys_ = SSRT_DISPATCH(isa, marchSortKeys);
    if (marcher == Marcher::Dda) ddaJitter_ = settings.ddaJitter;
}

MarchStats RayMarcher::tile(int tile, const RayBatch& rays, MarchResult& result) const {
    const TileRect rect = grid_.rect(tile);
    if (!holdsTile(rays.corner, rays.ox.width(), rays.ox.height(), rect) ||
        !holdsTile(result.corner, result.hit.width(), result.hit.height(), rect))
        throw std::invalid_argument("marchRays: a batch does not hold the tile");
    const int w = proto_.width;
    const BatchCorner in = rays.corner, out = result.corner;
    const bool jitter = ddaJitter_ > 0.0f;
    const std::size_t histogramSize = std::size_t(maxSteps_) + 1;
    MarchStats st;
    st.stepHistogram.assign(histogramSize, 0);
    // Every pixel "no ray" (what the march then overwrites for the rays it marches).
    const auto noRays = [&] {
        for (int y = rect.y0; y < rect.y1; ++y) {
            const int yy = y - out.y0, x0 = rect.x0 - out.x0, x1 = rect.x1 - out.x0;
            for (PlaneF* p : {&result.hit, &result.hitX, &result.hitY, &result.hitZ, &result.steps})
                std::fill(p->row(yy) + x0, p->row(yy) + x1, 0.0f);
            std::fill(result.cause.row(yy) + x0, result.cause.row(yy) + x1,
                      float(int(MarchEnd::NoRay)));
        }
    };
    if (skip_ || (skipTiles_ && (*skipTiles_)[std::size_t(tile)])) {
        noRays();
        return st;
    }
    thread_local TileScratch scratch;
    const std::size_t cap = std::size_t(kTileSize * kTileSize + kMarchPad);
    if (scratch.capacity != cap) {
        scratch.capacity = cap;
        scratch.data.assign(cap * TileScratch::kArrays, 0.0f);
        scratch.key.resize(cap);
    }
    // Which pixels have a ray (pdf > 0, finite non-zero direction, origin in front of the
    // camera), and each ray's bucket.
    int8_t* key = scratch.key.data();
    int counts[kSortBuckets + 1] = {};
    const int tw = rect.x1 - rect.x0;
    MarchKernelArgs ka = proto_;
    ka.count = tw;
    for (int y = rect.y0; y < rect.y1; ++y) {
        const int x = rect.x0 - in.x0, yy = y - in.y0;
        int8_t* k = key + (y - rect.y0) * tw;
        ka.pdf = rays.pdf.row(yy) + x;
        ka.ox = rays.ox.row(yy) + x;
        ka.oy = rays.oy.row(yy) + x;
        ka.oz = rays.oz.row(yy) + x;
        ka.dx = rays.dx.row(yy) + x;
        ka.dy = rays.dy.row(yy) + x;
        ka.dz = rays.dz.row(yy) + x;
        ka.key = k;
        sortKeys_(ka);
        for (int i = 0; i < tw; ++i)
            if (k[i] >= 0) ++counts[k[i] + 1];
    }
    for (int b = 1; b <= kSortBuckets; ++b) counts[b] += counts[b - 1];
    const int n = counts[kSortBuckets];
    float* A[TileScratch::kArrays];
    for (int i = 0; i < TileScratch::kArrays; ++i) A[i] = scratch.array(i);
    // Pack them bucket by bucket; within a bucket in 4x4 blocks (block rows, then rows).
    for (int by = rect.y0; by < rect.y1; by += kSortBlock)
        for (int bx = rect.x0; bx < rect.x1; bx += kSortBlock)
            for (int y = by; y < std::min(by + kSortBlock, rect.y1); ++y) {
                const int8_t* k = key + (y - rect.y0) * tw;
                const int yy = y - in.y0;
                const float *OX = rays.ox.row(yy), *OY = rays.oy.row(yy), *OZ = rays.oz.row(yy);
                const float *DX = rays.dx.row(yy), *DY = rays.dy.row(yy), *DZ = rays.dz.row(yy);
                for (int x = bx; x < std::min(bx + kSortBlock, rect.x1); ++x) {
                    const int b = k[x - rect.x0];
                    if (b < 0) continue;
                    const int i = counts[b]++, xx = x - in.x0;
                    A[TileScratch::kOx][i] = OX[xx];
                    A[TileScratch::kOy][i] = OY[xx];
                    A[TileScratch::kOz][i] = OZ[xx];
                    A[TileScratch::kDx][i] = DX[xx];
                    A[TileScratch::kDy][i] = DY[xx];
                    A[TileScratch::kDz][i] = DZ[xx];
                    A[TileScratch::kPx][i] = float(x);
                    A[TileScratch::kPy][i] = float(y);
                    const uint32_t pixel = uint32_t(y) * uint32_t(w) + uint32_t(x);
                    A[TileScratch::kJitter][i] =
                        jitter ? ddaJitter_ * randomFloat(pixel, seed_.frame, seed_.sample, 0)
                               : 0.0f;
                }
            }
    // Pad the last lane group with copies of the first ray (their results are dropped).
    const int padded = (n + kMarchPad - 1) / kMarchPad * kMarchPad;
    for (int i = n; i < padded; ++i)
        for (int k = 0; k <= TileScratch::kJitter; ++k) A[k][i] = n ? A[k][0] : 0.0f;
    noRays();
    if (n == 0) return st;
    MarchKernelArgs args = proto_;
    args.count = n;
    args.ox = A[TileScratch::kOx];
    args.oy = A[TileScratch::kOy];
    args.oz = A[TileScratch::kOz];
    args.dx = A[TileScratch::kDx];
    args.dy = A[TileScratch::kDy];
    args.dz = A[TileScratch::kDz];
    args.pixelX = A[TileScratch::kPx];
    args.pixelY = A[TileScratch::kPy];
    args.jitter = A[TileScratch::kJitter];
    args.hit = A[TileScratch::kHit];
    args.hitX = A[TileScratch::kHitX];
    args.hitY = A[TileScratch::kHitY];
    args.hitZ = A[TileScratch::kHitZ];
    args.steps = A[TileScratch::kSteps];
    args.cause = A[TileScratch::kCause];
    args.laneSlots = args.laneActive = 0;
    kernel_(args);
    // Scatter the results and count (plane pointers and counters in locals: stores through
    // float pointers would otherwise make the compiler reload them per ray).
    st.rays = uint64_t(n);
    st.laneSlots = args.laneSlots;
    st.laneActive = args.laneActive;
    const std::size_t outStride = result.hit.stride();  // all six: one size, one stride
    // The kernel's outputs in the result's table order (hit, hitX, hitY, hitZ, steps, cause).
    const float* const from[6] = {args.hit,  args.hitX,  args.hitY,
                                  args.hitZ, args.steps, args.cause};
    float* to[6];
    int k = 0;
    result.forEachPlane([&](std::string_view, PlaneF& p) { to[k++] = p.row(0); });
    uint64_t ends[kMarchEndCount] = {}, steps = 0;
    uint64_t* const histogram = st.stepHistogram.data();
    for (int i = 0; i < n; ++i) {
        const std::size_t at = std::size_t(int(args.pixelY[i]) - out.y0) * outStride +
                               std::size_t(int(args.pixelX[i]) - out.x0);
        for (int p = 0; p < 6; ++p) to[p][at] = from[p][i];
        const int cause = int(args.cause[i]);
        if (cause >= 0 && cause < kMarchEndCount) ++ends[cause];
        const uint64_t s = uint64_t(args.steps[i]);
        steps += s;
        ++histogram[std::min<std::size_t>(std::size_t(s), histogramSize - 1)];
    }
    st.steps = steps;
    for (int c = 0; c < kMarchEndCount; ++c) st.ends[c] = ends[c];
    return st;
}

void RayMarcher::skipTiles(const std::vector<uint8_t>& tiles) {
    if (tiles.empty()) return;
    if (tiles.size() != std::size_t(grid_.count()))
        throw std::invalid_argument("RayMarcher: skipTiles is not one per tile");
    skipTiles_ = &tiles;
}

MarchStats marchRays(Isa isa, Marcher marcher, const MarchSettings& settings, RaySeed seed,
                     const TraceCamera& camera, const GBufferView& g, const PlaneF* backZ,
                     const HiZPyramid* hiz, const RayBatch& rays, MarchResult& result, int threads,
                     bool skip, const std::vector<uint8_t>* skipTiles) {
    settings.validate();
    const int w = rays.width(), h = rays.height();
    if (w <= 0 || h <= 0) throw std::invalid_argument("marchRays: the ray batch is empty");
    if (camera.width != w || camera.height != h)
        throw std::invalid_argument("marchRays: camera size does not match the ray batch");
    RayMarcher march(isa, marcher, settings, seed, camera, g, backZ, hiz, threads);
    if (skip) march.skipMarch();
    if (skipTiles) march.skipTiles(*skipTiles);
    result.ensureSize(w, h);
    result.corner = {};
    const TileGrid& grid = march.grid();
    std::vector<MarchStats> tileStats(std::size_t(grid.count()));
    parallelForTiles(grid.count(), threads, [&](int tile) {
        tileStats[std::size_t(tile)] = march.tile(tile, rays, result);
    });
    MarchStats total;
    total.stepHistogram.assign(std::size_t(settings.maxSteps) + 1, 0);
    for (const MarchStats& s : tileStats) total.add(s);
    return total;
}

}  // namespace ssrt
