// A signal's world rays (TraceSettings::ssrTrace; trace/world_rays.h), one batch at
// a time, between the march and the resolve: which rays go to world space (every one in world
// mode), traced, and each answer written into the march's result as the screen would have
// given it. A world hit on a pixel that shows it (its depth the pixel's within 1 %) becomes a
// screen hit there, so the resolve reads the screen's light for it, as for a march hit.
//
// A world hit no pixel shows (off the frame, or hidden) is lit at the hit (WorldRays::light:
// the direct pass's model, the frame's shadow map) and handed to the resolve as a WorldLit.
//
// In mixed mode a march hit the proof holds (trace/hit_proof.h) stays a screen hit, at its
// exact point, and only the rest are traced. SSR's stage lights a hidden hit with the whole
// direct light, SSGI's with the bounce's Lambert part (WorldRays::light).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/plane_view.h"
#include "core/tiles.h"
#include "renderer/renderer.h"
#include "trace/hit_proof.h"
#include "trace/trace_types.h"
#include "trace/world_rays.h"

namespace ssrt {

struct TraceContext;
struct Frame;
struct DirectArgs;
struct HalfFrame;

// What a signal's world stage reads, made once per pass (worldStage) with its views checked
// where the pass's reads are (PassReads).
struct WorldStage {
    TraceMode mode = TraceMode::Screen;
    const WorldRays* world = nullptr;
    // A hidden hit's light: the direct pass's lighting, with the frame's shadow map from the
    // pass's declared read.
    DirectArgs light{};
    TraceCamera camera{};
    ViewF viewZ;  // the depth of the camera's frame (the frame's, or the half's): where a world
                  // hit is shown
    // On the half frame: the frame's camera and depth, which must show the hit too. (The half
    // pixel's chosen surface may show a hit that the frame's pixel under it does not: a hit
    // beside a depth edge within the block; that one is hidden, lit at the hit.)
    bool onHalf = false;
    TraceCamera frameCamera{};
    ViewF frameViewZ;
    bool proves = false;  // mixed: `proof` holds the proof's inputs
    ProofInputs proof;
    float tnear = 0.0f, tfar = 0.0f;  // the world ray's interval (view-space distance)
    bool fullLight = true;            // WorldRays::light's `full`: the signal's light model
};

// The stage of pass `pass` tracing in `mode` (Screen: a stage that does nothing), on the
// frame, or on the half frame `half` (SSGI's TraceLayout::Half: its camera and depth say where
// a hit is shown; world mode only, as it holds no triangle ids to prove a march hit with).
WorldStage worldStage(const TraceContext& c, const Frame& frame, std::string_view pass,
                      TraceMode mode, bool fullLight, const HalfFrame* half = nullptr);

// Answers the rays of `rays` (a tile's batch or the frame's, at its corner) inside `r` (the
// stage's camera's pixels: the frame's or the half frame's) in world space by the stage's mode
// and writes the answers into `march`; the hidden hits' light goes to `lit`, in row order.
// Screen mode does nothing. Each answered ray's
// MarchResult::cause says how it was answered (MarchEnd::Proven, WorldShown, World,
// WorldMiss); the counts are returned.
WorldRayStats answerInWorld(const WorldStage& w, const RayBatch& rays, MarchResult& march,
                            const TileRect& r, std::vector<WorldLit>& lit);

// The same over the frame's batch, tile by tile of `grid` (each tile's counts in `perTile`,
// its lit hits in row order after the tile before's).
WorldRayStats answerInWorldByTile(const WorldStage& w, const TileGrid& grid, const RayBatch& rays,
                                  MarchResult& march, std::vector<WorldRayStats>& perTile,
                                  std::vector<WorldLit>& lit);

// Mixed tracing's tile classifier (FidelityFX's hybrid reflections classify tiles by their
// last frame's hits; here by the proof): a tile of a pass's grid where the proof held for
// fewer than kMixedMinProven of its rays the last time it was marched skips its march and
// proof this frame, and sends every ray to world space, where a ray costs less than its march
// and proof together. Each tile marches again one frame in kMixedProbeFrames, so a tile whose
// view changed is measured again. What it keeps lives in the sequence's history
// (FrameHistory::mixedSsr, mixedSsgi).
inline constexpr float kMixedMinProven = 0.9f;
inline constexpr uint32_t kMixedProbeFrames = 8;
class MixedTileClassifier {
public:
    // `pass`'s tiles on `camera`'s grid (the frame's, or the half frame's).
    MixedTileClassifier(const TraceContext& c, TracePass pass, const TraceCamera& camera);
    const TileGrid& grid() const { return grid_; }
    // One entry per tile (1: skip; RayMarcher::skipTiles), or none (march all): outside mixed
    // mode, without a sequence's history, after a cut or a change of grid.
    const std::vector<uint8_t>& skips() const { return skips_; }
    // A sample's world-stage counts, one per tile, added to the frame's.
    void add(const std::vector<WorldRayStats>& perTile);
    // What the marched tiles proved, kept in the sequence's history for the next frame (a
    // skipped tile keeps its last share); outside mixed mode, nothing is kept.
    void keep() const;

private:
    const TraceContext& c_;
    TracePass pass_;
    TileGrid grid_;
    std::vector<uint8_t> skips_;
    std::vector<WorldRayStats> perTile_;
};

}  // namespace ssrt
