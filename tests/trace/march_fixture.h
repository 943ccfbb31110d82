// Inputs for the marcher tests and benchmarks: a synthetic G-buffer with an analytic answer
// (a floor, a box front face, a back wall, sky above), G-buffers of rendered built-in scenes,
// and mirror rays built from a G-buffer.
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "core/image.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "trace/march.h"
#include "trace/trace_types.h"

namespace ssrt::test {

// A G-buffer: the planes the marchers read, and the camera.
struct GBuf {
    TraceCamera camera;
    PlaneF viewZ, nx, ny, nz;
    // Its view, with `roughness` when given (for specular rays).
    GBufferView view(const PlaneF* roughness = nullptr) const {
        return gbufferView("test", camera.width, camera.height,
                           {{kGViewZ, &viewZ},
                            {kGNormalX, &nx},
                            {kGNormalY, &ny},
                            {kGNormalZ, &nz},
                            {kGRoughness, roughness}});
    }
};

inline TraceCamera makeCamera(int w, int h, float fovYDeg) {
    TraceCamera c;
    c.width = w;
    c.height = h;
    c.tanHalfY = std::tan(glm::radians(fovYDeg) * 0.5f);
    c.tanHalfX = c.tanHalfY * float(w) / float(h);
    c.sceneDiagonal = 30.0f;  // the default maxDistance (1 diagonal) is then 30 units
    return c;
}

// View direction (not normalised, z = -1) through the centre of pixel (x, y).
inline glm::vec3 pixelDir(const TraceCamera& c, float px, float py) {
    return {(2.0f * px / float(c.width) - 1.0f) * c.tanHalfX,
            (1.0f - 2.0f * py / float(c.height)) * c.tanHalfY, -1.0f};
}

// Pixel position of a view point.
inline glm::vec2 projectToPixel(const TraceCamera& c, glm::vec3 p) {
    const float d = -p.z;
    return {(p.x / (d * c.tanHalfX) * 0.5f + 0.5f) * float(c.width),
            (0.5f - p.y / (d * c.tanHalfY) * 0.5f) * float(c.height)};
}

// The synthetic scene, in view space (identity camera rotation):
//   floor y = kFloorY (normal +y), box front face z = -kBoxZ for x in [-1, 1],
//   y in [kFloorY, kBoxTop] (normal +z), back wall z = -kWallZ for y <= kWallTop (normal
//   +z), background above the wall.
struct BoxScene {
    static constexpr float kFloorY = -1.0f, kBoxZ = 6.0f, kBoxTop = 0.5f, kWallZ = 10.0f,
                           kWallTop = 3.0f;
};

inline GBuf makeBoxGBuffer(int w, int h) {
    GBuf g;
    g.camera = makeCamera(w, h, 60.0f);
    for (PlaneF* p : {&g.viewZ, &g.nx, &g.ny, &g.nz}) *p = PlaneF(w, h, 0.0f);
    using S = BoxScene;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 v = pixelDir(g.camera, float(x) + 0.5f, float(y) + 0.5f);
            float z = 0.0f;
            glm::vec3 n(0.0f);
            // Back wall.
            if (v.y * S::kWallZ <= S::kWallTop) z = S::kWallZ, n = {0, 0, 1};
            // Box front face.
            const float bx = v.x * S::kBoxZ, by = v.y * S::kBoxZ;
            if (bx >= -1.0f && bx <= 1.0f && by >= S::kFloorY && by <= S::kBoxTop &&
                (z == 0.0f || S::kBoxZ < z))
                z = S::kBoxZ, n = {0, 0, 1};
            // Floor.
            if (v.y < 0.0f) {
                const float fz = S::kFloorY / v.y;
                if (z == 0.0f || fz < z) z = fz, n = {0, 1, 0};
            }
            g.viewZ.at(x, y) = z;
            g.nx.at(x, y) = n.x;
            g.ny.at(x, y) = n.y;
            g.nz.at(x, y) = n.z;
        }
    return g;
}

// A rendered built-in scene's G-buffer (and its perceptual roughness, where asked).
inline GBuf renderGBuffer(const std::string& scene, int w, int h, PlaneF* roughness = nullptr) {
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.shadowMapSize = 256;
    rs.idPlanes = false;
    const Scene s = makeBuiltinScene(scene);
    const Frame f = Renderer(rs).renderWithoutHistory(s);
    GBuf g;
    g.camera = makeCamera(w, h, s.camera.fovY);
    g.camera.nearZ = s.camera.nearZ;
    g.camera.farZ = s.camera.farZ;
    const glm::mat3 toWorld = glm::transpose(glm::mat3(s.camera.view()));
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) g.camera.viewToWorld[c * 3 + r] = toWorld[c][r];
    g.viewZ = f.gbuffer.viewZ.clone();
    g.nx = f.gbuffer.normal[0].clone();
    g.ny = f.gbuffer.normal[1].clone();
    g.nz = f.gbuffer.normal[2].clone();
    if (roughness) *roughness = f.gbuffer.roughness.clone();
    return g;
}

inline glm::mat3 viewToWorld(const TraceCamera& c) {
    glm::mat3 m;
    for (int col = 0; col < 3; ++col)
        for (int r = 0; r < 3; ++r) m[col][r] = c.viewToWorld[col * 3 + r];
    return m;
}

// The view-space surface point of pixel (x, y) at depth z.
inline glm::vec3 surfacePoint(const TraceCamera& c, int x, int y, float z) {
    return pixelDir(c, float(x) + 0.5f, float(y) + 0.5f) * z;
}

// Mirror rays from every surface pixel (pdf 1); background pixels get no ray.
inline RayBatch mirrorRays(const GBuf& g) {
    const int w = g.viewZ.width(), h = g.viewZ.height();
    RayBatch rays;
    rays.ensureSize(w, h);
    const glm::mat3 toView = glm::transpose(viewToWorld(g.camera));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float z = g.viewZ.at(x, y);
            glm::vec3 o(0.0f), d(0.0f);
            float pdf = 0.0f;
            if (z > 0.0f) {
                o = surfacePoint(g.camera, x, y, z);
                const glm::vec3 n =
                    glm::normalize(toView * glm::vec3(g.nx.at(x, y), g.ny.at(x, y), g.nz.at(x, y)));
                d = glm::normalize(glm::reflect(glm::normalize(o), n));
                pdf = 1.0f;
            }
            rays.ox.at(x, y) = o.x, rays.oy.at(x, y) = o.y, rays.oz.at(x, y) = o.z;
            rays.dx.at(x, y) = d.x, rays.dy.at(x, y) = d.y, rays.dz.at(x, y) = d.z;
            rays.pdf.at(x, y) = pdf;
        }
    return rays;
}

// No ray anywhere (for tests that set a few rays by hand).
inline RayBatch emptyRays(int w, int h) {
    RayBatch rays;
    rays.ensureSize(w, h);
    for (PlaneF* p : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.pdf})
        p->fill(0.0f);
    return rays;
}

inline void setRay(RayBatch& rays, const GBuf& g, int x, int y, glm::vec3 d) {
    const glm::vec3 o = surfacePoint(g.camera, x, y, g.viewZ.at(x, y));
    d = glm::normalize(d);
    rays.ox.at(x, y) = o.x, rays.oy.at(x, y) = o.y, rays.oz.at(x, y) = o.z;
    rays.dx.at(x, y) = d.x, rays.dy.at(x, y) = d.y, rays.dz.at(x, y) = d.z;
    rays.pdf.at(x, y) = 1.0f;
}

// Marches with any marcher (building the pyramid for Hi-Z).
inline MarchStats march(Marcher m, const MarchSettings& s, const GBuf& g, const RayBatch& rays,
                        MarchResult& out, Isa isa = Isa::Scalar, int threads = 1,
                        RaySeed seed = {}) {
    HiZPyramid hiz;
    if (m == Marcher::HiZ) buildHiZ(g.viewZ, hiz, threads);
    return marchRays(isa, m, s, seed, g.camera, g.view(), nullptr,
                     m == Marcher::HiZ ? &hiz : nullptr, rays, out, threads);
}

}  // namespace ssrt::test
