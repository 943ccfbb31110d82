#include "raster/alpha_test.h"

#include "raster/geometry.h"
#include "scenes/material_alpha.h"

namespace ssrt {

AlphaTriangle alphaTriangle(const glm::vec4 clip[3], const glm::vec2 uv[3], const RasterView& view,
                            uint32_t primId, uint32_t material) {
    // With columns c_i = (x_i, y_i, w_i) of the clip-space vertices, the point of barycentrics
    // b seen at NDC (X, Y) has (X w, Y w, w) = M b, so b_i / w = row_i(M^-1) . (X, Y, 1) and
    // row_i(M^-1) = (c_{i+1} x c_{i+2}) / det M. The UV is sum_i uv_i b_i = (sum_i uv_i b_i / w)
    // / (sum_i b_i / w): the ratio cancels det M, so the cross products serve as they are
    // (no division, and a sign of det M that flips both).
    glm::dvec3 c[3];
    for (int i = 0; i < 3; ++i) c[i] = {clip[i].x, clip[i].y, clip[i].w};
    AlphaTriangle a{};
    a.primId = primId;
    a.material = material;
    // NDC at the centre of pixel (x, y): X = (x + 0.5) sx - 1, Y = 1 - (y + 0.5) sy.
    const double sx = 2.0 / view.width, sy = 2.0 / view.height;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 r = glm::cross(c[(i + 1) % 3], c[(i + 2) % 3]);
        const double p[3] = {(r.x * (0.5 * sx - 1.0) + r.y * (1.0 - 0.5 * sy)) + r.z, r.x * sx,
                             -r.y * sy};
        for (int k = 0; k < 3; ++k) {
            a.u[k] += double(uv[i].x) * p[k];
            a.v[k] += double(uv[i].y) * p[k];
            a.q[k] += p[k];
        }
    }
    return a;
}

uint64_t alphaTestPixels(const AlphaTestArgs& args, uint32_t slot, int blockX, int blockY,
                         int first, uint64_t bits) {
    const AlphaTriangle& t = args.triangles[slot];
    const Scene& scene = *args.scene;
    const Material& m = scene.materials[t.material];
    uint64_t kept = 0;
    for (uint64_t rest = bits; rest; rest &= rest - 1) {
        const int l = __builtin_ctzll(rest);
        const int n = first + l;
        const double x = blockX + n % kBlockSize, y = blockY + n / kBlockSize;
        const double q = (t.q[0] + t.q[1] * x) + t.q[2] * y;
        const glm::vec2 uv(float(((t.u[0] + t.u[1] * x) + t.u[2] * y) / q),
                           float(((t.v[0] + t.v[1] * x) + t.v[2] * y) / q));
        if (alphaPasses(scene, m, uv)) kept |= uint64_t(1) << l;
    }
    return kept;
}

}  // namespace ssrt
