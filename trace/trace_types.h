// What the screen-space passes hand each other: the rays of one pass (one per pixel) and
// what the march found for each, with the camera as the marchers see it (core/camera.h, whose
// view-space conventions they follow). Plain planes and values, so the renderer, the EXR
// writer and the Embree checks (issue 6) read the same data.
#pragma once

#include <cstdint>
#include <string_view>

#include "core/camera.h"
#include "core/image.h"
#include "core/plane_table.h"
#include "core/tiles.h"

namespace ssrt {

// Which frame and which of its samples a batch of rays is: the counter-based RNG's inputs
// (core/rng.h), per frame, never settings.
struct RaySeed {
    uint32_t frame = 0;
    uint32_t sample = 0;
};

// One ray per pixel, view space, planes of the frame's size. A pixel without a ray
// (background, or a sample the method rejects) has pdf 0 and direction (0, 0, 0); one the
// trace layout leaves out (trace/trace_layout.h) has pdf kPdfLayoutCut. Every reader takes
// pdf > 0 as "a ray".
inline constexpr float kPdfLayoutCut = -1.0f;

// A batch lies in the frame at its `corner` (core/tiles.h, BatchCorner). A batch of the whole
// frame has corner (0, 0); a tile's batch (a trace pass's tile chain, trace/tile_chain.h) has
// planes of one tile's size and the tile's corner, so that its rays and march results stay in
// the core's cache between the stages.

struct RayBatch : PlaneTable<RayBatch> {
    BatchCorner corner;
    PlaneF ox, oy, oz;  // origin: the pixel's surface point (no offset; marchers skip their
                        // own pixel)
    PlaneF dx, dy, dz;  // unit direction
    PlaneF pdf;         // solid-angle PDF of the direction (0: no ray)

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        fn("ray.ox", g.ox), fn("ray.oy", g.oy), fn("ray.oz", g.oz);
        fn("ray.dx", g.dx), fn("ray.dy", g.dy), fn("ray.dz", g.dz), fn("ray.pdf", g.pdf);
    }
    int width() const { return ox.width(); }
    int height() const { return ox.height(); }
};

// Why a ray ended, per pixel (MarchResult::cause, as a float).
enum class MarchEnd : uint8_t {
    Hit = 0,
    NoRay = 1,       // pdf 0: nothing was traced
    LeftScreen = 2,  // left the frame (or passed the near/far plane) before a hit
    StepCap = 3,     // ran out of steps or iterations
    Thickness = 4,   // crossed the depth buffer but behind the surface by more than the thickness
    BackFace = 5,    // met a surface whose normal faces the ray's direction
    // Written after the march, not by it (mixed and world tracing, renderer/world_stage.h),
    // and not among the march's own ends (kMarchEndCount): how the ray was answered.
    World = 6,       // a world ray's hit no pixel shows, lit at the hit; hitX, hitY, hitZ its
                     // projection and depth
    WorldShown = 7,  // a world ray's hit a pixel shows: a screen hit there
    WorldMiss = 8,   // a world ray that met nothing within the march's maximum distance
    Proven = 9,      // a march hit the proof holds (trace/hit_proof.h), at its exact point
};
inline constexpr int kMarchEndCount = 6;
inline constexpr int kAnswerEndCount = 10;  // the march's ends and the answers after it
inline bool answeredInWorld(MarchEnd e) {
    return e == MarchEnd::World || e == MarchEnd::WorldShown || e == MarchEnd::WorldMiss;
}

inline std::string_view marchEndName(MarchEnd e) {
    switch (e) {
        case MarchEnd::Hit: return "hit";
        case MarchEnd::NoRay: return "no_ray";
        case MarchEnd::LeftScreen: return "left_screen";
        case MarchEnd::StepCap: return "step_cap";
        case MarchEnd::Thickness: return "thickness";
        case MarchEnd::BackFace: return "back_face";
        case MarchEnd::World: return "world";
        case MarchEnd::WorldShown: return "world_shown";
        case MarchEnd::WorldMiss: return "world_miss";
        case MarchEnd::Proven: return "proven";
    }
    return "?";
}

// What the march found for each pixel's ray.
struct MarchResult : PlaneTable<MarchResult> {
    BatchCorner corner;  // as RayBatch's
    PlaneF hit;          // 1 hit, 0 not
    PlaneF hitX, hitY;   // hit position in pixels (continuous; pixel centres at +0.5); 0 on a miss
    PlaneF hitZ;         // view Z at the hit (positive); 0 on a miss
    PlaneF steps;        // march steps (or Hi-Z iterations) this ray took
    PlaneF cause;        // MarchEnd as a float

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        fn("march.hit", g.hit), fn("march.hitX", g.hitX), fn("march.hitY", g.hitY);
        fn("march.hitZ", g.hitZ), fn("march.steps", g.steps), fn("march.cause", g.cause);
    }
};

// Whether a tile's rays and their march results share one corner and hold the tile: what the
// stages after the march check.
inline bool sameCornerHolds(const RayBatch& rays, const MarchResult& march, const TileRect& r) {
    const BatchCorner c = rays.corner;
    return c.x0 == march.corner.x0 && c.y0 == march.corner.y0 &&
           holdsTile(c, rays.pdf.width(), rays.pdf.height(), r) &&
           holdsTile(c, march.hit.width(), march.hit.height(), r);
}

}  // namespace ssrt
