// Ray generation (issue 5): one ray per pixel, view space, SIMD across pixels.
//
// Specular (SSR) rays reflect the view about a microfacet normal drawn by one of the GGX
// samplers of shading/sampling.h (or about the shading normal: Mirror); diffuse (SSGI) rays
// are cosine-weighted around the shading normal. The kernel is trace/ray_gen_kernel.cpp; see
// trace/README.md ("Ray generation") for the conventions below in prose.
//
// Conventions
// - Everything is in VIEW space: the world normal of the G-buffer is rotated by the
//   transpose of TraceCamera::viewToWorld. The origin is the pixel's surface point
//   ((2 (px + ox) / W - 1) tanHalfX z, (1 - 2 (py + oy) / H) tanHalfY z, -z), z = viewZ,
//   (ox, oy) = TraceCamera::pointX, pointY: the centre, but on a half frame its chosen pixel.
// - Random numbers: randomFloat(y * width + x, frame, sample, dim) with dims
//   kRayGenSpecularDim, kRayGenSpecularDim + 1 (specular) and kRayGenDiffuseDim,
//   kRayGenDiffuseDim + 1 (diffuse), so the two passes draw independent numbers.
// - GGX alpha = brdf::roughnessToAlpha(roughness) = max(roughness^2, 1e-3): roughness 0 is
//   a lobe of alpha 1e-3 (D stays finite in float), not a delta. Mirror is the delta.
// - A pixel with no ray (background, or a sample rejected below) has pdf 0 and direction
//   (0, 0, 0); a background pixel also has origin (0, 0, 0).
// - Rejections (pdf 0, counted in RayGenStats::belowSurface), per method:
//   * every specular method: the shading normal faces away from the viewer (n.v <= 0, at
//     silhouettes with interpolated normals): the upper-hemisphere lobe has no view to
//     reflect, so no ray (not flipped: a flipped normal would reflect into the surface the
//     pixel shows);
//   * Mirror: otherwise never (the reflection of v about n has n.r = n.v > 0);
//   * GgxNdf: the sampled half vector faces away from the viewer (v.m <= 0: a microfacet
//     the view cannot see), or the reflection is below the horizon (n.r <= 0);
//   * VndfEllipsoid, VndfSphericalCaps: visible normals only, so only n.r <= 0;
//   * VndfBounded: the bound cuts away most, not all, of the caps that reflect below the
//     horizon; the rest (n.r <= 0) is rejected;
//   * diffuse: the cosine sampler never reaches the horizon (z >= 2^-12 for u < 1), but a
//     direction with n.r <= 0 after the rotation to view space would be rejected too.
// - pdf: the solid-angle PDF of the reflected direction, from the sampler's own PDF
//   function (ggxNdfReflectionPdf, vndfReflectionPdf, vndfBoundedReflectionPdf) evaluated on
//   the direction drawn; it integrates to 1 - (rejected fraction) over the accepted
//   directions. Mirror writes pdf 1 for its delta (the weight of a delta sample is the
//   BRDF's reflectance, not f/pdf). Diffuse: cos(theta) / pi.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/plane_view.h"
#include "core/tiles.h"
#include "trace/ray_gen_kernel.h"
#include "trace/trace_types.h"

namespace ssrt {

enum class SsrMethod { Mirror, GgxNdf, VndfEllipsoid, VndfSphericalCaps, VndfBounded };

inline constexpr SsrMethod kAllSsrMethods[] = {
    SsrMethod::Mirror, SsrMethod::GgxNdf, SsrMethod::VndfEllipsoid, SsrMethod::VndfSphericalCaps,
    SsrMethod::VndfBounded};

// "mirror", "ggx_ndf", "vndf_ellipsoid", "vndf_spherical_caps", "vndf_bounded".
std::string_view ssrMethodName(SsrMethod);
// The method named by ssrMethodName; nullopt for anything else.
std::optional<SsrMethod> parseSsrMethod(std::string_view);

// The random-number dimensions (see the conventions above).
inline constexpr uint32_t kRayGenSpecularDim = 16;  // and 17
inline constexpr uint32_t kRayGenDiffuseDim = 18;   // and 19

struct RayGenStats {
    uint64_t pixels = 0;  // surface pixels considered (viewZ > 0)
    uint64_t rays = 0;    // rays written with pdf > 0
    // samples that fell below the surface (rejected: pdf 0), counted per method (see above)
    uint64_t belowSurface = 0;
    uint64_t background = 0;  // background pixels (no ray)
    // surface pixels left without a ray because the composite would not show what it found
    // (specular: roughness at or past the cut; diffuse: no diffuse colour); not in
    // belowSurface
    uint64_t hidden = 0;
    // surface pixels the trace layout leaves without a ray (trace/trace_layout.h: the
    // checkerboard's other phase, a half-resolution frame's unchosen pixels); not hidden
    uint64_t cut = 0;
    // of `cut`, the traced phase's pixels the thinned checkerboard left without a ray
    // (RayGenCheckerboard::historyFrames)
    uint64_t sparse = 0;
    void add(const RayGenStats&);
};

// The checkerboard cut (trace/trace_layout.h): when `on`, only pixels with ((x ^ y ^ frame)
// & 1) == phase get rays; a surface pixel of the other phase that would have had one (not
// hidden) is left with pdf kPdfLayoutCut, direction 0, and counted as `cut`. The random
// numbers, and so the rays, of the traced pixels are those of the full layout.
//
// Thinned where the history is long (trace/trace_layout.h, sparseBlockPick): with
// `historyFrames` (the last frame's history lengths, of the camera's size) a traced-phase pixel
// whose length at its previous position (the G-buffer's motion, then required) is at least
// `sparseMin`, and which is not its 2x2 block's pick, is cut as well (counted in `cut` and in
// `sparse`). The block's pick keeps its ray whatever its history, so every cut pixel has a
// traced pixel among its eight neighbours (trace/reconstruct.h).
struct RayGenCheckerboard {
    bool on = false;
    uint32_t phase = 0;
    ViewF historyFrames{};  // absent (no data): not thinned
    float sparseMin = 0.0f;
};

// Specular (SSR) rays: one per pixel for sample index `sample` of frame `frame`; origin = the
// pixel's view-space surface point, direction = reflection of the view direction about a
// sampled microfacet normal (Mirror: about the shading normal). The PDF is the solid-angle
// PDF of the reflected direction (Mirror: 1, a delta). Writes every pixel. `rays` is sized to
// the camera; `g` (viewZ, normal, roughness) must have the camera's size (else
// std::invalid_argument).
// threads: 0 = every core. A surface pixel whose perceptual roughness is not below
// `maxRoughness` (NaN included) gets no ray, as one rejected below the surface but counted
// as `hidden`: the renderer passes the resolve's roughnessFadeEnd, where SSR's opacity is 0
// whatever the ray finds (HDRP does not trace there either). +infinity (the default) cuts
// nothing; NaN is std::invalid_argument. The random numbers of the other pixels do not
// depend on it, so neither do their rays.
RayGenStats generateSpecularRays(Isa isa, SsrMethod method, uint32_t frame, uint32_t sample,
                                 const TraceCamera& camera, const GBufferView& g, RayBatch& rays,
                                 int threads,
                                 float maxRoughness = std::numeric_limits<float>::infinity(),
                                 RayGenCheckerboard checkerboard = {});

// Which pixels generateDiffuseRays leaves without a ray besides the background.
enum class DiffuseCut {
    None,
    // albedo (1 - metallic) is 0 in every channel (metals); a NaN colour keeps its ray
    NoDiffuseColour,
};

// Diffuse (SSGI) rays: cosine-weighted hemisphere around the shading normal; pdf = cos/pi.
// (g.roughness is not read and may be null.) With DiffuseCut::NoDiffuseColour a surface
// pixel without a diffuse colour gets no ray, counted as `hidden`: the composite multiplies
// SSGI by that colour, and a pixel without a ray contributes 0 (trace/ssgi.h), so its image
// is the same; g.albedo and g.metallic are then required. The other pixels' rays do not
// change a bit.
RayGenStats generateDiffuseRays(Isa isa, uint32_t frame, uint32_t sample, const TraceCamera& camera,
                                const GBufferView& g, RayBatch& rays, int threads,
                                DiffuseCut cut = DiffuseCut::None,
                                RayGenCheckerboard checkerboard = {});

// One pass's ray generation, checked and set up once, then run tile by tile: over the frame by
// the two functions above, or one tile at a time by a trace pass's tile chain
// (trace/tile_chain.h). The same rays either way: a pixel's ray depends on its pixel alone.
class RayGenerator {
public:
    // The arguments of generateSpecularRays and generateDiffuseRays, less the batch and threads.
    static RayGenerator specular(Isa isa, SsrMethod method, uint32_t frame, uint32_t sample,
                                 const TraceCamera& camera, const GBufferView& g,
                                 float maxRoughness, RayGenCheckerboard checkerboard);
    static RayGenerator diffuse(Isa isa, uint32_t frame, uint32_t sample, const TraceCamera& camera,
                                const GBufferView& g, DiffuseCut cut,
                                RayGenCheckerboard checkerboard);
    const TileGrid& grid() const { return grid_; }
    // Tile `tile`'s rays into `rays`: the frame's batch (planes of the camera's size, corner
    // (0, 0)) or a tile's (planes of at least the tile's size, corner at the tile's corner).
    RayGenStats tile(int tile, RayBatch& rays) const;
    // Every tile's into the frame's batch (sized here), counted in tile order.
    RayGenStats frame(RayBatch& rays, int threads) const;

private:
    RayGenerator(Isa isa, RayGenLobe lobe, uint32_t frame, uint32_t sample, uint32_t dim,
                 const TraceCamera& camera, const GBufferView& g, float maxRoughness,
                 bool onlyDiffuse, RayGenCheckerboard checkerboard);
    RayGenArgs args_{};
    TileGrid grid_;
    decltype(&isa_scalar::generateRaysTile) kernel_ = nullptr;
};

}  // namespace ssrt
