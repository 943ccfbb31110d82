#include "renderer/world_stage.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/tiles.h"
#include "renderer/pass_reads.h"
#include "renderer/trace_pass.h"
#include "trace/hit_proof.h"
#include "trace/march.h"
#include "trace/trace_layout.h"

namespace ssrt {

namespace {

// A world hit is shown by the pixel it projects onto when that pixel's depth is the hit's
// within 1 % (the proof's thickness: trace/hit_proof.h).
constexpr float kShownThickness = ProofSettings{}.thickness;

// Whether the frame's pixel under view-space point `q` shows it too (on the half frame; on the
// frame the caller's test is this one).
bool shownOnFrame(const WorldStage& w, glm::vec3 q) {
    return !w.onHalf || screenPoint(w.frameCamera, w.frameViewZ, q, kShownThickness).shown;
}

}  // namespace

WorldStage worldStage(const TraceContext& c, const Frame& frame, std::string_view pass,
                      TraceMode mode, bool fullLight, const HalfFrame* half) {
    WorldStage w;
    w.mode = mode;
    if (mode == TraceMode::Screen) return w;
    const PassReads reads(c.graph, frame, pass);
    w.world = c.world;
    // A hidden hit is lit with the frame's shadow map: the pass's declared read, checked made
    // and of its size (the graph frees it after its last declared reader).
    w.light = c.lighting;
    static const PlaneF kUndeclared;
    const ViewF shadow =
        viewOf(reads.has(Res::ShadowMap) ? frame.scratch.shadow.depth : kUndeclared, "shadowMap");
    requireViews(pass, w.light.shadowSize, w.light.shadowSize, {shadow});
    w.light.shadowMap = shadow.data;
    w.light.shadowStride = shadow.stride;
    w.camera = half ? half->camera : c.camera;
    // (PassReads checked the frame's: made, of the frame's size; buildHalfFrame made the half's.)
    w.viewZ = half ? viewOf(half->viewZ, "half.gbuffer.viewZ") : reads.view(Res::ViewZ);
    w.onHalf = half != nullptr;
    if (half) {
        w.frameCamera = c.camera;
        w.frameViewZ = reads.view(Res::ViewZ);
    }
    w.proves = mode == TraceMode::Mixed;
    const ProofTriangles triangles{c.tables->triangles, c.tables->viewPositions, *c.cutOut};
    if (w.proves && half)  // (the chosen pixels' ids, the half frame's thin features)
        w.proof = proofInputs(half->camera, viewOf(half->ids, "half.ids"), w.viewZ, triangles, {},
                              &frame.scratch.half.thin);
    else if (w.proves)
        w.proof = proofInputs(c.camera, reads.ids(Res::VisibilityIds), w.viewZ, triangles, {},
                              &frame.scratch.thin);
    // The world ray leaves the surface a step off it (1e-4 of the scene's diagonal, as the
    // truth's rays do) and ends where the march would give up.
    w.tnear = 1e-4f * c.camera.sceneDiagonal;
    w.tfar = marchLengths(c.ts().march, c.camera.sceneDiagonal).maxDistance;
    w.fullLight = fullLight;
    return w;
}

WorldRayStats answerInWorld(const WorldStage& stage, const RayBatch& rays, MarchResult& march,
                            const TileRect& r, std::vector<WorldLit>& lit) {
    WorldRayStats st;
    const TraceMode mode = stage.mode;
    if (mode == TraceMode::Screen) return st;
    const TraceCamera& cam = stage.camera;
    const float* R = cam.viewToWorld;
    const glm::vec3 eye{cam.position[0], cam.position[1], cam.position[2]};
    const auto toWorld = [R](glm::vec3 v) {
        return glm::vec3{(R[0] * v.x + R[3] * v.y) + R[6] * v.z,
                         (R[1] * v.x + R[4] * v.y) + R[7] * v.z,
                         (R[2] * v.x + R[5] * v.y) + R[8] * v.z};
    };
    // The rect in the batch's own pixels.
    const int x0 = r.x0 - rays.corner.x0, x1 = r.x1 - rays.corner.x0;
    const int y0 = r.y0 - rays.corner.y0, y1 = r.y1 - rays.corner.y0;
    const int w = rays.width();
    std::vector<WorldRay> batch;
    std::vector<int> where;
    batch.reserve(std::size_t(x1 - x0) * std::size_t(y1 - y0));
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            if (!(rays.pdf.at(x, y) > 0.0f)) continue;
            const glm::vec3 o{rays.ox.at(x, y), rays.oy.at(x, y), rays.oz.at(x, y)};
            const glm::vec3 d{rays.dx.at(x, y), rays.dy.at(x, y), rays.dz.at(x, y)};
            // Mixed: the march's hits the proof holds stay screen hits, at the exact point.
            if (stage.proves) {
                // (The origin's pixel position: the chosen pixel's on the half frame.)
                const float fx = float(x + rays.corner.x0) + cam.pointX;
                const float fy = float(y + rays.corner.y0) + cam.pointY;
                const ProvenRay p = proveRay(stage.proof, o, d, fx, fy, march.hit.at(x, y) > 0.5f,
                                             march.hitX.at(x, y), march.hitY.at(x, y));
                if (p.proof == RayProof::CertainHit && shownOnFrame(stage, o + p.t * d)) {
                    march.hitX.at(x, y) = p.at.x;
                    march.hitY.at(x, y) = p.at.y;
                    march.hitZ.at(x, y) = p.at.depth;
                    march.cause.at(x, y) = float(MarchEnd::Proven);
                    ++st.proven;
                    continue;
                }
            }
            batch.push_back({eye + toWorld(o), toWorld(d), stage.tnear, stage.tfar});
            where.push_back(y * w + x);
        }
    std::vector<WorldHit> hits(batch.size());
    stage.world->intersect(batch, hits);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const int x = where[i] % w, y = where[i] / w;
        ++st.sent;
        march.hit.at(x, y) = 0.0f;
        march.hitX.at(x, y) = march.hitY.at(x, y) = march.hitZ.at(x, y) = 0.0f;
        march.cause.at(x, y) = float(MarchEnd::WorldMiss);
        if (!hits[i].hit) {
            ++st.missed;
            continue;
        }
        // The hit in view space (the rotation keeps lengths: t is the view-space distance).
        const glm::vec3 o{rays.ox.at(x, y), rays.oy.at(x, y), rays.oz.at(x, y)};
        const glm::vec3 d{rays.dx.at(x, y), rays.dy.at(x, y), rays.dz.at(x, y)};
        const glm::vec3 q = o + hits[i].t * d;
        // (hitX, hitY are the frame's continuous pixels, as the march writes them; behind the
        // camera hitZ is negative, and the three still give the point: the hit distance the
        // denoiser reads.)
        const ScreenPoint at = screenPoint(cam, stage.viewZ, q, kShownThickness);
        march.hit.at(x, y) = 1.0f;
        march.hitX.at(x, y) = at.x;
        march.hitY.at(x, y) = at.y;
        march.hitZ.at(x, y) = at.depth;
        const bool shown = at.shown && shownOnFrame(stage, q);
        if (shown) {
            // The pixel's own depth: the resolve reads the screen's light there.
            march.hitZ.at(x, y) = stage.viewZ.at(int(at.x), int(at.y));
            march.cause.at(x, y) = float(MarchEnd::WorldShown);
            ++st.shown;
        } else {
            march.cause.at(x, y) = float(MarchEnd::World);
            ++st.hidden;
            lit.push_back({x + rays.corner.x0, y + rays.corner.y0,
                           stage.world->light(batch[i], hits[i], stage.light, stage.fullLight), q});
        }
    }
    return st;
}

WorldRayStats answerInWorldByTile(const WorldStage& w, const TileGrid& grid, const RayBatch& rays,
                                  MarchResult& march, std::vector<WorldRayStats>& perTile,
                                  std::vector<WorldLit>& lit) {
    WorldRayStats st;
    perTile.resize(std::size_t(grid.count()));
    for (int t = 0; t < grid.count(); ++t) {
        perTile[std::size_t(t)] = answerInWorld(w, rays, march, grid.rect(t), lit);
        st.add(perTile[std::size_t(t)]);
    }
    return st;
}

namespace {

MixedTiles* mixedTiles(const TraceContext& c, TracePass pass) {
    if (!c.sequence) return nullptr;
    return pass == TracePass::Ssr ? &c.sequence->mixedSsr : &c.sequence->mixedSsgi;
}

bool sameGrid(const MixedTiles& m, const TileGrid& grid) {
    return m.tilesX == grid.tilesX && m.tilesY == grid.tilesY;
}

}  // namespace

MixedTileClassifier::MixedTileClassifier(const TraceContext& c, TracePass pass,
                                         const TraceCamera& camera)
    : c_(c), pass_(pass), grid_(camera.width, camera.height) {
    const MixedTiles* last = mixedTiles(c, pass);
    if (traceMode(c, pass) != TraceMode::Mixed || !last || c.resetHistory ||
        !sameGrid(*last, grid_))
        return;
    skips_.assign(std::size_t(grid_.count()), 0);
    for (int t = 0; t < grid_.count(); ++t) {
        const float p = last->proven[std::size_t(t)];
        const bool probe = (c.frameIndex + uint32_t(t)) % kMixedProbeFrames == 0;
        skips_[std::size_t(t)] = p >= 0.0f && p < kMixedMinProven && !probe;
    }
}

void MixedTileClassifier::add(const std::vector<WorldRayStats>& perTile) {
    perTile_.resize(perTile.size());
    for (std::size_t t = 0; t < perTile.size(); ++t) perTile_[t].add(perTile[t]);
}

void MixedTileClassifier::keep() const {
    MixedTiles* keep = mixedTiles(c_, pass_);
    if (!keep) return;
    if (traceMode(c_, pass_) != TraceMode::Mixed) {
        *keep = MixedTiles();
        return;
    }
    if (c_.resetHistory || !sameGrid(*keep, grid_)) {
        keep->tilesX = grid_.tilesX, keep->tilesY = grid_.tilesY;
        keep->proven.assign(std::size_t(grid_.count()), -1.0f);
    }
    for (std::size_t t = 0; t < perTile_.size(); ++t) {
        if (!skips_.empty() && skips_[t]) continue;
        const uint64_t rays = perTile_[t].proven + perTile_[t].sent;
        keep->proven[t] = rays ? float(double(perTile_[t].proven) / double(rays)) : -1.0f;
    }
}

}  // namespace ssrt
