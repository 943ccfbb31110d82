// The embeddable entry point: scene + camera + settings in, named image planes out.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"
#include "core/isa.h"
#include "raster/hiz.h"
#include "raster/raster.h"
#include "raster/raster_stats.h"
#include "raster/shadow_map.h"
#include "renderer/settings.h"
#include "scenes/scene.h"
#include "trace/color_pyramid.h"
#include "trace/march.h"
#include "trace/ray_gen.h"
#include "trace/ssr_resolve.h"
#include "trace/trace_types.h"

namespace ssrt {

// Wall-clock time of one pass, in milliseconds.
struct PassTime {
    std::string name;
    double ms = 0.0;
};

// What one screen-space pass did, over all its samples.
struct TraceStats {
    bool ran = false;
    int spp = 0;
    RayGenStats rays;
    MarchStats march;
};

struct FrameStats {
    std::vector<PassTime> passes;
    TraceStats ssr, ssgi;
    RasterStats visibility;  // camera pass
    RasterStats shadow;      // light pass
    Isa isa = Isa::Scalar;
    int threads = 0;
};

struct Frame {
    int width = 0, height = 0;
    TraceCamera camera;  // the camera it was rendered from, as the trace passes see it
    std::vector<NamedPlane> planes;
    FrameStats stats;

    // Buffers the passes need but do not hand out; kept so that rendering into the same
    // Frame again reuses every allocation (no page faults, no clears).
    struct Scratch {
        VisibilityBuffer visibility;
        ShadowMap shadow;
        PlaneF uv[6];  // UV and its screen derivatives, for textured scenes
        // The screen-space passes (issue 5).
        HiZPyramid hiz;
        RayBatch rays;
        MarchResult march;
        ColorPyramid colorPyramid;
        SsrOutput ssr;  // the resolve's scratch; its colour and opacity are lent the frame's planes
        PlaneF directParts[15];  // direct, emission, envDiffuse, envSpecular, specWeight (RGB each)
        PlaneF hitLight[3];      // DirectArgs::hitLight, for SSGI
        PlaneF previousColor[3];  // last frame's final colour, for reprojected SSR hits
        bool hasPrevious = false;
    } scratch;

    // The plane called `name`; throws std::out_of_range if there is none.
    const PlaneF& plane(std::string_view name) const;
    bool has(std::string_view name) const;
};

// The screen-space pass a traced sample belongs to.
enum class TracePass { Ssr, Ssgi };

// Sees every sample's rays and what the march found, right after the march and before the
// resolve, on the thread that called render(), in pass then sample order. Its time is not in
// any pass time. `ssrt compare` hands them to Embree (truth/ray_check.h), so the
// truth is asked about the very rays that were marched.
using TraceObserver =
    std::function<void(TracePass pass, int sample, const RayBatch& rays, const MarchResult& march)>;

class Renderer {
public:
    explicit Renderer(RenderSettings settings = {});

    const RenderSettings& settings() const { return settings_; }

    // Renders one frame. Planes: color.{R,G,B} (linear, exposed), display.{R,G,B} (tone
    // mapped, sRGB encoded, in [0, 1]), shadow (light visibility, 0..1), the G-buffer
    // viewZ, normal.{X,Y,Z}, albedo.{R,G,B}, metallic, roughness, materialId, motion.{X,Y}
    // (previous minus current position, pixels), and with idPlanes instanceId and
    // triangleId. Background pixels: viewZ 0, ids -1, motion 0. With trace.ssr: ssr.{R,G,B}
    // (reflected radiance, before the BRDF factor), ssrOpacity (0..1: the share of SSR over
    // the environment), ssrHit (share of the pixel's rays that hit), ssrHitDistance (view-space
    // distance to the hit, mean over hits, 0 without one), ssrSteps (mean march steps: the
    // heat map); with trace.ssgi: ssgi.{R,G,B} (incoming diffuse radiance), ssgiHit,
    // ssgiSteps. color and display then hold the composite.
    Frame render(const Scene& scene, const Camera& camera, const Camera& previousCamera) const;
    Frame render(const Scene& scene) const {
        return render(scene, scene.camera, scene.previousCamera);
    }

    // Renders into `frame`, reusing its planes and scratch buffers when their sizes match
    // (what a sequence or a benchmark wants). Safe to call from several threads at once
    // with different frames. `observer` (optional) sees every traced sample.
    void render(const Scene& scene, const Camera& camera, const Camera& previousCamera,
                Frame& frame, const TraceObserver* observer = nullptr) const;

private:
    RenderSettings settings_;
};

}  // namespace ssrt
