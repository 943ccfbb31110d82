// The GL half of the llvmpipe peer: an OpenGL 3.3 core context on EGL's surfaceless
// platform, and the two workloads ssrt is compared on (shadow map, G-buffer).
// Knows nothing of ssrt's scene model, so it can be built and tested on its own.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace peer {

// An indexed triangle mesh as GL draws it (positions and normals per vertex).
struct GlMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;
};

// One draw: a mesh placed in the world, with the material values the G-buffer stores.
struct GlDraw {
    uint32_t mesh = 0;
    glm::mat4 model{1.0f};
    glm::mat4 previousModel{1.0f};
    glm::vec3 albedo{0.8f};
    float metallic = 0.0f;
    float roughness = 0.5f;
    bool doubleSided = false;  // false: back faces culled in the G-buffer, as ssrt does
};

struct GlSceneDesc {
    std::vector<GlMesh> meshes;
    std::vector<GlDraw> draws;
    glm::mat4 view{1.0f}, projection{1.0f};                  // camera, this frame
    glm::mat4 previousView{1.0f}, previousProjection{1.0f};  // camera, one frame earlier
    glm::mat4 lightViewProjection{1.0f};                     // orthographic, fitted to bounds
};

// Share of a target's pixels that the render touched (differ from the clear value).
struct Coverage {
    double fraction = 0.0;
    float centre = 0.0f;  // the centre pixel's value (depth or linear depth)
};

// Owns the EGL display and context; throws std::runtime_error with a clear message when
// EGL or GL cannot start. Sets LP_NUM_THREADS (unless already set) before EGL starts.
class GlContext {
public:
    explicit GlContext(int llvmpipeThreads);
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    std::string renderer() const;  // GL_RENDERER
    std::string version() const;   // GL_VERSION
    bool isLlvmpipe() const;

private:
    void* display_ = nullptr;
    void* context_ = nullptr;
};

// Uploaded geometry, programs and render targets for one scene; needs a current context.
class GlWorkloads {
public:
    GlWorkloads(const GlSceneDesc& desc, int width, int height, int shadowSize);
    ~GlWorkloads();
    GlWorkloads(const GlWorkloads&) = delete;
    GlWorkloads& operator=(const GlWorkloads&) = delete;

    // Issue one full pass (clear + every draw); the caller brackets with glFinish (timeOnce).
    void drawShadow();
    void drawGBuffer();

    Coverage shadowCoverage();   // depth < 1 (cleared to 1)
    Coverage gbufferCoverage();  // linear depth > 0 (cleared to 0)

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Wall time of one run of `pass`, in ms, with glFinish before and after so that only that
// run's work is inside the clock (llvmpipe queues draws and rasterizes on its own threads).
template <class Pass>
double timeOnce(Pass&& pass);

double glFinishAndNowMs();  // glFinish, then a steady-clock timestamp
double medianOf(std::vector<double> values);

template <class Pass>
double timeOnce(Pass&& pass) {
    double t0 = glFinishAndNowMs();
    pass();
    return glFinishAndNowMs() - t0;
}

}  // namespace peer
