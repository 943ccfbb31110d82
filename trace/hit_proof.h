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
//     ray passes: such hits stay uncertain).
// Measured against Embree (a proven hit counts as right when Embree's first hit is at its
// distance within 0.1 %), default preset, 640x360, one frame: a march hit alone is not
// the true answer for 2.5 to 11 % of SSR's hits and 7.5 to 36 % of SSGI's (the ray check's
// classes); a proven hit is wrong for 0 to 0.09 % of the proven hits on cornell and corridor,
// 0.02 % (SSR) and 0.5 % (SSGI) on spheres and 0.2 to 0.3 % on fence, where a ray crosses a
// thin visible wire between the march's samples. Of all rays, 13 to 63 % of SSR's and 6 to
// 31 % of SSGI's are proven. The exact test did most of it: thickness, facing and distance
// alone leave the false share near the march's own.
//
// A proven hit's distance is the exact test's, which mixed tracing uses in place of the
// march's.
#pragma once

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

// What the proof reads of the frame: its camera (pixel centres, projection), its visibility
// ids (raster/raster.h) and viewZ as views, and the triangles they name. Made by
// proofInputs, which checks the views.
struct ProofInputs {
    TraceCamera camera;
    ViewU32 ids;
    ViewF viewZ;
    ProofTriangles triangles;
    ProofSettings settings;
};

// The inputs, their views checked (requireViews: present, of the camera's size); else
// std::invalid_argument naming the view.
ProofInputs proofInputs(const TraceCamera& camera, ViewU32 ids, ViewF viewZ,
                        ProofTriangles triangles, ProofSettings settings = {});

struct ProvenRay {
    RayProof proof = RayProof::NoRay;
    float t = 0.0f;  // a certain hit's exact distance along the ray (view space)
};

// One ray: view-space origin and unit direction, the pixel it left from and the pixel the
// march hit (continuous, in the frame's pixels: centres at +0.5).
ProvenRay proveRay(const ProofInputs& in, glm::vec3 origin, glm::vec3 direction, float fromX,
                   float fromY, bool marchHit, float hitX, float hitY);

}  // namespace ssrt
