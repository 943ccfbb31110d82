// Which screen-space hits are proven: the strict acceptance of mixed tracing. A marched ray
// that hit is a certain hit only where every test holds; any other ray is uncertain, and mixed
// tracing sends it to world space (trace/world_rays.h). No ray is a certain miss yet: a ray
// that leaves the screen, runs out of steps or passes behind a surface may meet what the
// screen does not show.
//
// The tests, on the triangle seen at the pixel the march hit (its visibility id):
//   - the ray meets that very triangle: ssrt's exact ray-triangle test (core/ray_triangle.h)
//     on its view-space corners; the point it meets projects onto a pixel whose depth is
//     the point's within `thickness` (relative): the point is on screen, nothing hides it;
//   - it meets the side the camera sees (a ray arriving from behind a surface is not proven);
//   - the hit is at least `minPixels` from the ray's own pixel (a hit at its origin is its own
//     surface, as SSSR refuses);
//   - the triangle's material cuts nothing out (an alpha cut-out may leave a hole where the
//     ray passes: such hits stay uncertain);
//   - nothing the screen shows lies on the ray before the hit (the thin-feature check: the
//     triangles of the pixels in front of their neighbours drawn beside the ray's path on
//     screen, by the exact test), so a pole the march stepped over is not crossed unseen.
// Measured against Embree (a proven hit counts as right when Embree's first hit is at its
// distance within 0.1 %), default preset, 640x360, one frame: a march hit alone is not
// the true answer for 2.5 to 11 % of SSR's hits and 7.5 to 36 % of SSGI's (the ray check's
// classes); a proven hit is wrong for 0 to 0.09 % of the proven hits on cornell and corridor,
// 0.02 % (SSR) and 0.5 % (SSGI) on spheres and 0.2 to 0.3 % on fence, where a ray crosses a
// thin visible wire between the march's samples. Of all rays, 13 to 63 % of SSR's and 6 to
// 31 % of SSGI's are proven. The exact test did most of it: thickness, facing and distance
// alone leave the false share near the march's own. (Those figures are before the thin-
// feature check. With it, SSR's proven hits that are wrong, as a share of all its rays: fence
// 0.023 % (0.103 % without), cornell 0.0095 %, corridor 0.0041 %, spheres 0.0027 %.)
//
// A proven hit's distance is the exact test's, which mixed tracing uses in place of the
// march's.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>

#include "core/camera.h"
#include "core/image.h"
#include "core/plane_view.h"
#include "raster/resolve_kernel.h"

namespace ssrt {

enum class RayProof : uint8_t {
    NoRay = 0,       // pdf <= 0: nothing was traced
    CertainHit = 1,  // the march's hit is proven (above)
    CertainMiss = 2,
    Uncertain = 3,  // a world ray must answer it
};

// The visible triangles as the proof reads them: the G-buffer resolve's tables (renderer/
// resolve_tables.h), indexed by visibility id, and the view-space position of every vertex.
struct ProofTriangles {
    std::span<const ResolveTriangle> triangles;  // by visibility id
    std::span<const glm::vec3> viewPositions;    // by ResolveTriangle::v
    std::span<const uint8_t> cutOut;             // by instance: 1 where an alpha test cuts
};

struct ProofSettings {
    float thickness = 0.01f;  // relative depth, the exact hit against the pixel's
    float minPixels = 2.0f;   // the hit's distance from the ray's pixel, in pixels
};

// The pixels the thin-feature check looks at: those in front of a neighbour (a pixel of their
// 3x3 more than 2 % deeper, or the background), where something the march can step over is
// drawn. Level 0 holds their depth (+infinity elsewhere), each coarser level the least of
// its 8x8 cells below (8 and 64 pixels a side). Made once a frame by findThinFeatures.
struct ThinFeatures {
    static constexpr int kLevels = 3, kCellLog2 = 3;
    static constexpr float kStep = 1.02f;  // a neighbour this much deeper is behind
    std::array<PlaneF, kLevels> levels;
};
void findThinFeatures(ViewF viewZ, ThinFeatures& out, int threads);

// What the proof reads of the frame: its camera (pixel centres, projection), its visibility
// ids (raster/raster.h) and viewZ as views, and the triangles they name. Made by
// proofInputs, which checks the views.
struct ProofInputs {
    TraceCamera camera;
    ViewU32 ids;
    ViewF viewZ;
    ProofTriangles triangles;
    ProofSettings settings;
    // Optional: views of the frame's thin features (ThinFeatures::levels), with which the
    // thin-feature check looks only at them and skips the stretches of a path far from any
    // (absent: at every pixel).
    std::array<ViewF, ThinFeatures::kLevels> thin{};
};

// The inputs, their views checked (requireViews: present, of the camera's size); else
// std::invalid_argument naming the view.
ProofInputs proofInputs(const TraceCamera& camera, ViewU32 ids, ViewF viewZ,
                        ProofTriangles triangles, ProofSettings settings = {},
                        const ThinFeatures* thin = nullptr);

// Where a view-space point lies on screen: its continuous pixel (centres at +0.5) and depth,
// and whether the pixel there shows it (on the frame, its viewZ the point's depth within
// `thickness`, relative). Behind the camera the depth is negative and x, y the projection
// through it, which still gives the point back (P = ((2 x / W - 1) tanHalfX z, (1 - 2 y / H)
// tanHalfY z, -z)); a point in the camera's plane (z = 0) has none.
struct ScreenPoint {
    float x = 0.0f, y = 0.0f, depth = 0.0f;
    bool front = false;  // in front of the camera
    bool shown = false;  // a pixel shows it
};
ScreenPoint screenPoint(const TraceCamera& camera, ViewF viewZ, glm::vec3 point, float thickness);

struct ProvenRay {
    RayProof proof = RayProof::NoRay;
    float t = 0.0f;  // a certain hit's exact distance along the ray (view space)
    ScreenPoint at;  // a certain hit's point on screen (shown)
};

// One ray: view-space origin and unit direction, the pixel it left from and the pixel the
// march hit (continuous, in the frame's pixels: centres at +0.5).
ProvenRay proveRay(const ProofInputs& in, glm::vec3 origin, glm::vec3 direction, float fromX,
                   float fromY, bool marchHit, float hitX, float hitY);

}  // namespace ssrt
