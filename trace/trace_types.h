// What the screen-space passes hand each other: the camera as the marchers see it, the rays
// of one pass (one per pixel) and what the march found for each. Plain planes and values, so
// the renderer, the EXR writer and the Embree checks (issue 6) read the same data.
//
// View space is the camera's: x right, y up, the camera looks down -z. A G-buffer `viewZ`
// is the positive distance along -z (0 for background), so a point at pixel (px, py) with
// depth z sits at ((2 (px + 0.5) / width - 1) tanHalfX z, (1 - 2 (py + 0.5) / height)
// tanHalfY z, -z). Pixel rows run top to bottom.
#pragma once

#include <cstdint>
#include <string_view>

#include "core/image.h"
#include "core/plane_table.h"

namespace ssrt {

// Which frame and which of its samples a batch of rays is: the counter-based RNG's inputs
// (core/rng.h), per frame, never settings.
struct RaySeed {
    uint32_t frame = 0;
    uint32_t sample = 0;
};

// The pinhole camera of the frame, as plain numbers.
struct TraceCamera {
    int width = 0, height = 0;
    float tanHalfX = 1.0f, tanHalfY = 1.0f;  // view ray at NDC (x, y): (x tanHalfX, y tanHalfY, -1)
    float nearZ = 0.05f, farZ = 100.0f;      // positive distances
    float viewToWorld[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // rotation, column-major
    // World positions in the passes and the truth are measured from `origin` (the scene's
    // bounds centre, Scene::origin()): a point is origin + position + viewToWorld * view.
    // The marchers read neither.
    float position[3] = {0, 0, 0};  // the camera, from the origin
    float origin[3] = {0, 0, 0};
    // The diagonal of the scene's bounding box (world units): the unit of the march's
    // relative lengths (MarchSettings::maxDistance); 0 where nobody set it.
    float sceneDiagonal = 0.0f;
};

// One ray per pixel, view space, planes of the frame's size. A pixel without a ray
// (background, or a sample the method rejects) has pdf 0 and direction (0, 0, 0); one the
// trace layout leaves out (trace/trace_layout.h) has pdf kPdfLayoutCut. Every reader takes
// pdf > 0 as "a ray".
inline constexpr float kPdfLayoutCut = -1.0f;

struct RayBatch : PlaneTable<RayBatch> {
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
};
inline constexpr int kMarchEndCount = 6;

inline std::string_view marchEndName(MarchEnd e) {
    switch (e) {
        case MarchEnd::Hit: return "hit";
        case MarchEnd::NoRay: return "no_ray";
        case MarchEnd::LeftScreen: return "left_screen";
        case MarchEnd::StepCap: return "step_cap";
        case MarchEnd::Thickness: return "thickness";
        case MarchEnd::BackFace: return "back_face";
    }
    return "?";
}

// What the march found for each pixel's ray.
struct MarchResult : PlaneTable<MarchResult> {
    PlaneF hit;         // 1 hit, 0 not
    PlaneF hitX, hitY;  // hit position in pixels (continuous; pixel centres at +0.5); 0 on a miss
    PlaneF hitZ;        // view Z at the hit (positive); 0 on a miss
    PlaneF steps;       // march steps (or Hi-Z iterations) this ray took
    PlaneF cause;       // MarchEnd as a float

    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        fn("march.hit", g.hit), fn("march.hitX", g.hitX), fn("march.hitY", g.hitY);
        fn("march.hitZ", g.hitZ), fn("march.steps", g.steps), fn("march.cause", g.cause);
    }
};

}  // namespace ssrt
