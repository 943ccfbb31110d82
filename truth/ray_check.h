// Ray checks: the very rays a screen-space pass marched, traced by Embree in world space,
// and each ray put in one class by comparing the two answers.
//
// For a pixel's ray (view-space origin o and unit direction d from the RayBatch, pdf > 0):
// the world ray is camera.position + viewToWorld o, viewToWorld d; Embree's first hit with t
// in [tnear, maxDistance] (tnear = EmbreeScene::epsilon(), off the origin's own surface;
// maxDistance = MarchSettings::maxDistance, where the marchers give up). Both faces count.
//
// The true hit is "visible on screen" when it projects inside the frame, between the near and
// far planes (as the rasterizer clips), onto a pixel whose G-buffer viewZ is the hit's own
// depth within the depth tolerance (nothing nearer covers it; background pixels never see it).
//
// Classes (per ray; a pixel without a ray is NoRay and in no count):
//   Agreed          march hit, true hit visible, and the march's hit pixel within
//                   pixelTolerance of the true hit's projection and its view Z within
//                   depthTolerance (relative) of the true hit's.
//   FalseHit        march hit, but not Agreed: the true first hit is elsewhere, not visible,
//                   or there is none within maxDistance (a leak through a gap or behind a thin
//                   object, a hit on the wrong layer).
//   MissedOnScreen  march missed, the true hit is visible on screen: screen space could have
//                   found it.
//   TrueMiss        march missed and Embree finds nothing within maxDistance.
//   OffScreenTruth  march missed; the true hit exists but is not visible (off the frame,
//                   behind the camera, or hidden behind nearer geometry): screen space cannot
//                   know it.
// Hit-position error (for rays where both hit, Agreed or FalseHit): the distance in pixels
// between the march's (hitX, hitY) and the true hit's projection (infinite when the true hit
// does not project in front of the camera), and |hitZ - trueZ| / trueZ.
//
// The layouts (trace/trace_layout.h). Checkerboard: the batch is the frame's, its untraced
// pixels have no ray (pdf <= 0). Half: the batch is the half frame's (rays and march results
// of half->camera's size); each ray is traced by Embree from the view-space origin and
// direction the march used (the half pixel's, on the half-resolution depth buffer), while the
// truth is judged in the frame, as for the full layout: projected by the frame's camera,
// "visible" against the frame's viewZ, and the march's hit moved from half pixels into the
// frame's (continuous) pixels through the view-space slope, so pixelTolerance and the pixel
// errors are in full-resolution pixels for every layout. (The half depth buffer holds one
// depth per 2x2 block, its chosen pixel's, at the block's centre: a hit found on it can lie
// a pixel or so from where the frame's own depth puts the surface.)
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/image.h"
#include "trace/trace_layout.h"
#include "trace/trace_types.h"
#include "world/embree_scene.h"

namespace ssrt {

enum class RayClass : uint8_t { NoRay, Agreed, FalseHit, MissedOnScreen, TrueMiss, OffScreenTruth };
inline constexpr int kRayClassCount = 6;
// "no_ray", "agreed", "false_hit", "missed_on_screen", "true_miss", "offscreen_truth".
std::string_view rayClassName(RayClass c);

struct RayCheckSettings {
    float pixelTolerance = 2.0f;   // pixels, for Agreed
    float depthTolerance = 0.02f;  // relative view Z, for Agreed and for "visible on screen"
    float maxDistance = 30.0f;     // scene units: marchLengths().maxDistance of the pass checked
};

// Counts and error distributions over every ray checked (several samples add up).
struct RayCheckTable {
    uint64_t rays = 0;                             // rays checked (pdf > 0)
    std::array<uint64_t, kRayClassCount> count{};  // per RayClass (NoRay stays 0)
    // Of those, the rays answered in world space after the march (mixed and world tracing:
    // MarchEnd::World, WorldShown, WorldMiss), per RayClass; the rest were the screen's.
    std::array<uint64_t, kRayClassCount> world{};
    std::vector<float> pixelError;  // one per ray where both hit (sorted by finish())
    std::vector<float> depthError;  // relative, same rays
    double embreeSeconds = 0.0;     // wall clock of Embree's traversal alone
    uint64_t embreeHits = 0;

    void add(const RayCheckTable& other);  // combine (in a fixed order)
    void finish();                         // sorts the error lists
    double share(RayClass c) const;        // count / rays (0 without rays)
    uint64_t worldRays() const;            // the rays answered in world space
    // The screen's answers (not world rays) in class c, over all rays (0 without rays): a
    // FalseHit's share is the screen's false accepts.
    double screenShare(RayClass c) const;
    // Quantile q in [0, 1] of a sorted error list (0 when empty).
    static float quantile(const std::vector<float>& sorted, double q);
};

// Per-pixel results of one sample's check: the channels of a pass's check resource
// (Res::SsrCheck, Res::SsgiCheck: renderer/resources.cpp), planes of the frame's size, in the
// table's order. A pixel that traced no ray (a layout's untraced pixel, a cut one, the
// background) holds NoRay (0) and 0 in every plane; the half layout's ray is written at its
// block's chosen pixel.
enum RayCheckChannel : int {
    kCheckClass,       // RayClass as a float
    kCheckPixelError,  // where both hit, else 0 (inf stays inf)
    kCheckDepthError,  // where both hit, else 0
    kCheckTrueT,       // Embree's hit distance (0: no true hit)
    kCheckChannels
};
// Check planes of a caller's own (a frame holds its passes' as outputs).
using CheckPlanes = std::array<PlaneF, kCheckChannels>;

// Checks one sample's rays: Embree traces them (16-ray packets over tiles, `threads`
// workers, 0 = every core), each is classified. Writes `planes` (kCheckChannels of them, as
// above; sized here) when not null. `camera` and
// `viewZ` are the frame's (for "visible on screen"); `half`, when not null, the half frame the
// batches were marched on (TraceLayout::Half, above). Throws std::invalid_argument on planes
// of the wrong size.
RayCheckTable checkRays(const EmbreeScene& embree, const TraceCamera& camera, const PlaneF& viewZ,
                        const RayBatch& rays, const MarchResult& march,
                        const RayCheckSettings& settings, PlaneF* planes, int threads,
                        const HalfFrame* half = nullptr);

}  // namespace ssrt
