#include "scenes/tangents.h"

#include <cmath>

namespace ssrt {

namespace {

// Any unit vector perpendicular to the unit n (Frisvad-style pick of the smaller axis).
glm::vec3 anyPerpendicular(glm::vec3 n) {
    const glm::vec3 axis =
        std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::normalize(axis - n * glm::dot(n, axis));
}

bool usable(glm::vec3 v) {
    const float l2 = glm::dot(v, v);
    return std::isfinite(l2) && l2 > 1e-20f;
}

}  // namespace

std::vector<glm::vec4> generateTangents(const Mesh& mesh, int uvSet) {
    const std::vector<glm::vec2>& uvs = uvSet == 1 ? mesh.uvs1 : mesh.uvs;
    const std::size_t n = mesh.positions.size();
    std::vector<glm::vec3> dPdu(n, glm::vec3(0.0f)), dPdv(n, glm::vec3(0.0f));
    if (uvs.size() == n) {
        for (std::size_t k = 0; k + 2 < mesh.indices.size(); k += 3) {
            const uint32_t i0 = mesh.indices[k], i1 = mesh.indices[k + 1], i2 = mesh.indices[k + 2];
            const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
            const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
            const glm::vec2 d1 = uvs[i1] - uvs[i0], d2 = uvs[i2] - uvs[i0];
            // e1 = d1.x dP/du + d1.y dP/dv, e2 likewise: solve the 2x2 system.
            const float det = d1.x * d2.y - d2.x * d1.y;
            if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) continue;
            const glm::vec3 su = (e1 * d2.y - e2 * d1.y) / det;
            const glm::vec3 sv = (e2 * d1.x - e1 * d2.x) / det;
            if (!usable(su) || !usable(sv)) continue;
            for (uint32_t i : {i0, i1, i2}) {
                dPdu[i] += su;
                dPdv[i] += sv;
            }
        }
    }
    std::vector<glm::vec4> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 nrm = mesh.normals[i];
        // Gram-Schmidt: the part of dP/du perpendicular to the normal.
        const glm::vec3 t = dPdu[i] - nrm * glm::dot(nrm, dPdu[i]);
        if (!usable(t)) {
            out[i] = glm::vec4(anyPerpendicular(nrm), 1.0f);
            continue;
        }
        const glm::vec3 tu = glm::normalize(t);
        // glTF's bitangent is -dP/dv (see the header).
        const float w = glm::dot(glm::cross(nrm, tu), -dPdv[i]) < 0.0f ? -1.0f : 1.0f;
        out[i] = glm::vec4(tu, w);
    }
    return out;
}

std::vector<glm::vec4> meshTangents(const Mesh& mesh, int uvSet) {
    return mesh.tangents.empty() ? generateTangents(mesh, uvSet) : mesh.tangents;
}

glm::vec4 worldTangent(const glm::mat4& transform, glm::vec4 t) {
    const glm::mat3 m(transform);
    glm::vec3 d = m * glm::vec3(t);
    const float len = glm::length(d);
    d = std::isfinite(len) && len > 0.0f ? d / len : glm::vec3(0.0f);
    const float w = glm::determinant(m) < 0.0f ? -t.w : t.w;
    return glm::vec4(d, w);
}

glm::vec3 perturbNormal(glm::vec3 n, glm::vec4 tangent, glm::vec3 texel, float scale) {
    const glm::vec3 m = glm::normalize(glm::vec3(
        (texel.x * 2.0f - 1.0f) * scale, (texel.y * 2.0f - 1.0f) * scale, texel.z * 2.0f - 1.0f));
    const glm::vec3 t0 = glm::vec3(tangent) - n * glm::dot(n, glm::vec3(tangent));
    if (!usable(t0)) return n;
    const glm::vec3 t = glm::normalize(t0);
    const glm::vec3 b = glm::cross(n, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
    const glm::vec3 p = (t * m.x + b * m.y) + n * m.z;
    if (!usable(p)) return n;
    const glm::vec3 out = glm::normalize(p);
    return std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z) ? out : n;
}

}  // namespace ssrt
