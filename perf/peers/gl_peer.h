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

// The first triangle id of each draw, then the number of triangles in all: the triangles of
// every draw, numbered in draw order and within a draw in index order (the numbering ssrt's
// visibility buffer uses, one draw being one instance).
std::vector<uint32_t> firstTriangles(const GlSceneDesc& desc);

// The id target's value where no triangle was drawn (ssrt's kNoPrimitive).
inline constexpr uint32_t kNoTriangle = 0xffffffffu;

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
    int subpixelBits() const;  // GL_SUBPIXEL_BITS: the rasterizer's vertex snapping grid

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

    // Untimed: the G-buffer's geometry again into an id target (R32UI, firstTriangles() +
    // gl_PrimitiveID, kNoTriangle where empty) and a linear depth target, so that the timed
    // pass writes exactly the four targets it always did.
    void drawIds();

    // Read-backs, rows top-down (as ssrt stores them; GL reads bottom-up), outside any clock.
    std::vector<float> readShadowDepth();         // window depth in [0, 1], 1 where empty
    std::vector<float> readLinearDepth();         // the timed G-buffer's, 0 where empty
    std::vector<float> readIdPassDepth();         // the id pass's linear depth, 0 where empty
    std::vector<uint32_t> readIdPassTriangles();  // the id pass's triangle ids

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
