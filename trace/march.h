// The three screen-space marchers (issue 5): linear (fixed view-space step), DDA
// (perspective-correct, McGuire & Mara 2014) and Hi-Z traversal (Uludag 2014; AMD FidelityFX
// SSSR). One entry point marches one ray per pixel of a RayBatch against the G-buffer and
// writes a MarchResult per pixel plus per-pass statistics. See trace/README.md, "Marchers".
//
// Every marcher works per 64x64 tile, packs the tile's rays (pdf > 0) and marches them
// kWidth at a time (SIMD across rays); a lane's path depends only on its own ray, so the
// results are the same bits for every ISA and thread count.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/tiles.h"
#include "raster/hiz.h"
#include "trace/march_kernel.h"
#include "trace/trace_types.h"

namespace ssrt {

enum class Marcher { Linear, Dda, HiZ };

// "linear", "dda", "hiz".
std::string_view marcherName(Marcher marcher);
// The marcher with that name, or nullopt.
std::optional<Marcher> parseMarcher(std::string_view name);

struct MarchSettings {
    // Linear and DDA: most steps per ray; Hi-Z: most traversal iterations per ray.
    int maxSteps = 512;
    // Lengths are relative by default, so that a scene in millimetres or kilometres, or far
    // from the origin, traces the same rays (issue 16): each has an absolute twin in scene
    // units that replaces it when > 0 (see marchLengths()).
    //
    // Ray length after which a ray ends (MarchEnd::StepCap), as a multiple of the scene's
    // bounding-box diagonal (TraceCamera::sceneDiagonal). 1 loses nothing: from a point
    // inside the bounds every surface is nearer than the diagonal.
    float maxDistance = 1.0f;
    float maxDistanceAbsolute = 0.0f;  // view-space length (scene units); 0: use maxDistance
    // Linear: step length as a fraction of the ray origin's view depth (a constant step on
    // screen wherever the surface is).
    float linearStep = 0.015f;
    float linearStepAbsolute = 0.0f;  // view-space step (scene units); 0: use linearStep
    // Depth a ray may be behind the depth buffer and still hit it, as a fraction of the depth
    // buffer's view depth there (a depth pyramid's footprint grows with depth, and so does
    // the depth error of what it stores). The linear marcher adds the ray's depth change over
    // one step (step |dir.z|), so the threshold grows with the step; DDA tests the ray's
    // depth interval of one step against [z, z + thickness]; Hi-Z validates its hit with it.
    float thickness = 0.03f;
    float thicknessAbsolute = 0.0f;  // view-space depth (scene units); 0: use thickness
    // The depth interval from the scene (raster/back_depth.h): where a pixel's back face is
    // known (marchRays' backZ), a ray hits it only within [z, back face]; the thickness
    // above is then the fallback where it is not. Off: the thickness everywhere. (Off by
    // default, the medium preset's; high and ultra turn it on: renderer/quality.cpp.)
    bool backFaces = false;
    // DDA: pixels per step along the major axis (>= 1).
    float ddaStride = 2.0f;
    // DDA: the first step is offset by ddaJitter * u strides, u = randomFloat(pixel, frame,
    // sample, 0) in [0, 1) (core/rng.h); 0 turns jitter off.
    float ddaJitter = 1.0f;
    // DDA: binary search steps between the last two samples once a hit is found.
    int refineSteps = 4;
    // Hi-Z: finest level the traversal descends to (0 = full resolution).
    int hizMostDetailedLevel = 0;
    // Hi-Z: level the traversal starts at (>= hizMostDetailedLevel; clamped to the pyramid).
    int hizStartLevel = 0;

    // Throws std::invalid_argument naming the first bad field.
    void validate() const;
};

// The march's lengths for one frame: each absolute setting where it is > 0, else the
// relative one resolved. thickness(z) = z * thicknessScale + thicknessBias and the linear
// step of a ray from depth d is d * stepScale + stepBias (one of each pair is 0).
struct MarchLengths {
    float maxDistance;  // view-space length (scene units)
    float stepScale, stepBias;
    float thicknessScale, thicknessBias;
};
// Throws std::invalid_argument when a relative maxDistance meets a sceneDiagonal that is
// not finite and > 0.
MarchLengths marchLengths(const MarchSettings& settings, float sceneDiagonal);

struct MarchStats {
    uint64_t rays = 0;  // rays traced: pdf > 0, finite non-zero direction, origin in front of
                        // the camera (other pixels end as NoRay and are not counted)
    uint64_t ends[kMarchEndCount] = {};      // per MarchEnd (ends[Hit] = hits); NoRay not counted
    uint64_t steps = 0;                      // sum of steps over rays
    uint64_t laneSlots = 0, laneActive = 0;  // lanes issued per step vs lanes still marching
    std::vector<uint64_t> stepHistogram;     // rays by steps taken (index = steps, clamped to
                                             // maxSteps)

    void add(const MarchStats& other);  // combine (tile order)
    double meanSteps() const;
    int stepsPercentile(double p) const;  // p in [0, 1], from the histogram
    int maxStepsTaken() const;
    double laneUtilisation() const {
        return laneSlots ? double(laneActive) / double(laneSlots) : 0;
    }
};

// Marches every pixel's ray of `rays` against `g` (viewZ, normal) and `backZ`, the
// back-face depth layer (raster/back_depth.h: 0 where unknown; read with
// MarchSettings::backFaces), or null: the thickness everywhere. Writes every pixel of
// `result` (ensureSize'd here). `hiz` must be built from g.viewZ when marcher == HiZ (may be
// null otherwise). Throws std::invalid_argument on bad settings or mismatched sizes.
// `seed` is the batch's frame and sample, for the DDA jitter. `skip`: RayMarcher::skipMarch;
// `skipTiles`: RayMarcher::skipTiles.
MarchStats marchRays(Isa isa, Marcher marcher, const MarchSettings& settings, RaySeed seed,
                     const TraceCamera& camera, const GBufferView& g, const PlaneF* backZ,
                     const HiZPyramid* hiz, const RayBatch& rays, MarchResult& result, int threads,
                     bool skip = false, const std::vector<uint8_t>* skipTiles = nullptr);

// One march, checked and set up once (the camera's, the settings' and the pyramid's
// arguments), then run tile by tile: over the frame by marchRays, or one tile at a time by the
// trace pass's tile chain (trace/tile_chain.h). The same results either way: a ray's path
// depends on its own ray alone. It points into `hiz`, `g` and `backZ`: they outlive it.
class RayMarcher {
public:
    // marchRays' arguments less the batches; `threads` only packs a pyramid without its copy.
    RayMarcher(Isa isa, Marcher marcher, const MarchSettings& settings, RaySeed seed,
               const TraceCamera& camera, const GBufferView& g, const PlaneF* backZ,
               const HiZPyramid* hiz, int threads);
    RayMarcher(const RayMarcher&) = delete;  // (the arguments point into packed_)
    RayMarcher& operator=(const RayMarcher&) = delete;
    const TileGrid& grid() const { return grid_; }
    // Tile `tile`'s rays of `rays` into `result`, every pixel of the tile written; each is the
    // frame's batch (planes of the camera's size, corner (0, 0)) or a tile's (planes of at
    // least the tile's size, corner at the tile's corner).
    MarchStats tile(int tile, const RayBatch& rays, MarchResult& result) const;
    // Leaves every ray unmarched: tile() writes each pixel as without a ray (hit 0,
    // MarchEnd::NoRay) and counts none. For world tracing (TraceMode::World), which answers
    // every ray after the march (renderer/world_stage.h): the march would be thrown away, and
    // tracing in Embree costs about what the march does.
    void skipMarch() { skip_ = true; }
    // The same for the tiles whose entry of `tiles` (one per tile of grid(), outliving the
    // marcher; empty: none) is not 0: mixed tracing's tile classifier (renderer/world_stage.h).
    // Throws std::invalid_argument for a list of another length.
    void skipTiles(const std::vector<uint8_t>& tiles);

private:
    MarchKernelArgs proto_{};
    HiZPacked packed_;
    TileGrid grid_;
    RaySeed seed_;
    float ddaJitter_ = 0.0f;  // 0: no jitter
    int maxSteps_ = 0;
    bool skip_ = false;
    const std::vector<uint8_t>* skipTiles_ = nullptr;  // null: none
    decltype(&isa_scalar::marchHiZKernel) kernel_ = nullptr;
    decltype(&isa_scalar::marchSortKeys) sortKeys_ = nullptr;
};

}  // namespace ssrt
