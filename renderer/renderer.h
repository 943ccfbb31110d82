// The embeddable entry point: scene + camera + settings in, named image planes out.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/image.h"
#include "core/isa.h"
#include "raster/raster.h"
#include "raster/raster_stats.h"
#include "raster/shadow_map.h"
#include "scenes/scene.h"

namespace ssrt {

struct RenderSettings {
    int width = 1280;
    int height = 720;
    int threads = 0;              // worker threads; 0 = every core
    std::optional<Isa> isa;       // nullopt: best the CPU runs (or $SSRT_ISA)
    int shadowMapSize = 2048;     // texels per side
    float shadowBias = 1.5f;      // constant depth bias, in shadow-map texels of depth
    float shadowSlopeBias = 2.0f; // extra bias per unit of tan(angle to the light), texels
    int pcfRadius = 1;            // PCF kernel is (2r+1)^2 texels
    float exposure = 1.0f;        // scale on linear radiance before the tone map
    uint32_t frame = 0;           // frame index (feeds the counter-based RNG)
    bool idPlanes = true;         // also hand out instanceId and triangleId float planes

    // Throws std::invalid_argument with a one-line message naming the bad field.
    void validate() const;
};

inline constexpr int kMaxImageSize = 8192;  // per side; the fixed-point budget in raster/

// Wall-clock time of one pass, in milliseconds.
struct PassTime {
    std::string name;
    double ms = 0.0;
};

struct FrameStats {
    std::vector<PassTime> passes;
    RasterStats visibility;  // camera pass
    RasterStats shadow;      // light pass
    Isa isa = Isa::Scalar;
    int threads = 0;
};

struct Frame {
    int width = 0, height = 0;
    std::vector<NamedPlane> planes;
    FrameStats stats;

    // Buffers the passes need but do not hand out; kept so that rendering into the same
    // Frame again reuses every allocation (no page faults, no clears).
    struct Scratch {
        VisibilityBuffer visibility;
        ShadowMap shadow;
        PlaneF uv[6];  // UV and its screen derivatives, for textured scenes
    } scratch;

    // The plane called `name`; throws std::out_of_range if there is none.
    const PlaneF& plane(std::string_view name) const;
    bool has(std::string_view name) const;
};

class Renderer {
public:
    explicit Renderer(RenderSettings settings = {});

    const RenderSettings& settings() const { return settings_; }

    // Renders one frame. Planes: color.{R,G,B} (linear, exposed), display.{R,G,B} (tone
    // mapped, sRGB encoded, in [0, 1]), shadow (light visibility, 0..1), the G-buffer
    // viewZ, normal.{X,Y,Z}, albedo.{R,G,B}, metallic, roughness, materialId, motion.{X,Y}
    // (previous minus current position, pixels), and with idPlanes instanceId and
    // triangleId. Background pixels: viewZ 0, ids -1, motion 0.
    Frame render(const Scene& scene, const Camera& camera, const Camera& previousCamera) const;
    Frame render(const Scene& scene) const {
        return render(scene, scene.camera, scene.previousCamera);
    }

    // Renders into `frame`, reusing its planes and scratch buffers when their sizes match
    // (what a sequence or a benchmark wants). Safe to call from several threads at once
    // with different frames.
    void render(const Scene& scene, const Camera& camera, const Camera& previousCamera,
                Frame& frame) const;

private:
    RenderSettings settings_;
};

}  // namespace ssrt
