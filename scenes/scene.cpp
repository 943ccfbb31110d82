#include "scenes/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <stdexcept>

namespace ssrt {

glm::vec3 Sky::radiance(glm::vec3 dir) const {
    if (kind == Kind::Constant) return zenith * intensity;
    if (kind == Kind::Image) {
        if (!image || image->width <= 0 || image->height <= 0) return glm::vec3(0.0f);
        // The lat-long mapping of shading/environment.h, nearest texel.
        const double pi = 3.14159265358979323846;
        const double u = 0.5 + std::atan2(double(dir.x), -double(dir.z)) / (2.0 * pi);
        const double v = std::atan2(std::hypot(double(dir.x), double(dir.z)), double(dir.y)) / pi;
        const int x = std::clamp(int(u * image->width), 0, image->width - 1);
        const int y = std::clamp(int(v * image->height), 0, image->height - 1);
        const float* p = image->rgb.data() + (std::size_t(y) * image->width + x) * 3;
        return glm::vec3(p[0], p[1], p[2]) * intensity;
    }
    const float y = dir.y;
    if (y < 0.0f) return ground * intensity;
    // Horizon to zenith over the upper hemisphere, smooth at the horizon.
    const float t = 1.0f - (1.0f - y) * (1.0f - y);
    return glm::mix(horizon, zenith, t) * intensity;
}

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::viewFrom(glm::vec3 origin) const {
    const glm::dvec3 o(origin);
    return glm::mat4(glm::lookAt(glm::dvec3(position) - o, glm::dvec3(target) - o, glm::dvec3(up)));
}

glm::mat4 transformFrom(const glm::mat4& m, glm::vec3 origin) {
    glm::dmat4 d(m);
    for (int c = 0; c < 4; ++c) d[c] -= glm::dvec4(glm::dvec3(origin) * d[c].w, 0.0);
    return glm::mat4(d);
}

glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(glm::radians(fovY), aspect, nearZ, farZ);
}

std::size_t Scene::triangleCount() const {
    std::size_t n = 0;
    for (const Instance& inst : instances) n += meshes[inst.mesh].triangleCount();
    return n;
}

float Bounds::diagonal() const {
    const float d = glm::length(hi - lo);
    return d > 0.0f && std::isfinite(d) ? d : 1.0f;
}

Bounds Scene::bounds() const {
    Bounds b;
    bounds(b.lo, b.hi);
    return b;
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(-std::numeric_limits<float>::max());
    for (const Instance& inst : instances) {
        for (const glm::vec3& p : meshes[inst.mesh].positions) {
            const glm::vec3 w = glm::vec3(inst.transform * glm::vec4(p, 1.0f));
            if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z)) continue;
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
    if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);
}

void Scene::validate() const {
    if (sky.kind == Sky::Kind::Image) {
        if (!sky.image) throw std::invalid_argument("sky: image kind without an image");
        const SkyImage& img = *sky.image;
        if (img.width <= 0 || img.height <= 0 ||
            img.rgb.size() != std::size_t(3) * img.width * img.height)
            throw std::invalid_argument("sky image '" + img.source +
                                        "': " + std::to_string(img.width) + "x" +
                                        std::to_string(img.height) + " needs " +
                                        std::to_string(3L * img.width * img.height) +
                                        " floats, has " + std::to_string(img.rgb.size()));
        // shading/environment.h indexes texels with floats, exact below 2^24.
        if (std::size_t(img.width) * img.height > (std::size_t(1) << 24))
            throw std::invalid_argument("sky image '" + img.source +
                                        "': more than 2^24 texels (16777216)");
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const Mesh& mesh = meshes[m];
        if (mesh.indices.size() % 3 != 0)
            throw std::invalid_argument("mesh " + std::to_string(m) +
                                        ": index count is not a multiple of 3");
        if (mesh.normals.size() != mesh.positions.size())
            throw std::invalid_argument("mesh " + std::to_string(m) +
                                        ": normal count differs from position count");
        if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
            throw std::invalid_argument("mesh " + std::to_string(m) +
                                        ": UV count differs from position count");
        if (!mesh.uvs1.empty() && mesh.uvs1.size() != mesh.positions.size())
            throw std::invalid_argument("mesh " + std::to_string(m) +
                                        ": second UV set's count differs from position count");
        if (!mesh.tangents.empty() && mesh.tangents.size() != mesh.positions.size())
            throw std::invalid_argument("mesh " + std::to_string(m) +
                                        ": tangent count differs from position count");
        for (uint32_t i : mesh.indices)
            if (i >= mesh.positions.size())
                throw std::invalid_argument("mesh " + std::to_string(m) + ": index " +
                                            std::to_string(i) + " out of range");
    }
    for (std::size_t i = 0; i < instances.size(); ++i) {
        if (instances[i].mesh >= meshes.size())
            throw std::invalid_argument("instance " + std::to_string(i) + ": no mesh " +
                                        std::to_string(instances[i].mesh));
        if (instances[i].material >= materials.size())
            throw std::invalid_argument("instance " + std::to_string(i) + ": no material " +
                                        std::to_string(instances[i].material));
    }
    for (std::size_t m = 0; m < materials.size(); ++m) {
        const Material& mat = materials[m];
        for (int32_t t : {mat.baseColorTexture, mat.metallicRoughnessTexture, mat.normalTexture,
                          mat.occlusionTexture, mat.emissiveTexture})
            if (t < -1 ||
                (t >= 0 && (std::size_t(t) >= textures.size() || textures[t].levels.empty())))
                throw std::invalid_argument("material " + std::to_string(m) + ": no texture " +
                                            std::to_string(t));
        for (int set : {mat.baseColorUv.set, mat.metallicRoughnessUv.set, mat.normalUv.set,
                        mat.occlusionUv.set, mat.emissiveUv.set})
            if (set != 0 && set != 1)
                throw std::invalid_argument("material " + std::to_string(m) + ": no UV set " +
                                            std::to_string(set));
        if (!std::isfinite(mat.normalScale) || !std::isfinite(mat.occlusionStrength))
            throw std::invalid_argument("material " + std::to_string(m) +
                                        ": normal scale or occlusion strength not finite");
    }
    // A NaN cutoff would cut out everything without a word.
    for (std::size_t m = 0; m < materials.size(); ++m)
        if (!std::isfinite(materials[m].baseColorAlpha) || !std::isfinite(materials[m].alphaCutoff))
            throw std::invalid_argument("material " + std::to_string(m) +
                                        ": alpha and alpha cutoff must be finite");
}

}  // namespace ssrt
