// The scene model: plain structs, no more than a scene needs (see DESIGN.md).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "scenes/texture.h"

namespace ssrt {

// Indexed triangles; normals per vertex (same count as positions), UVs optional: two sets
// (glTF's TEXCOORD_0 and TEXCOORD_1), each empty or one per position; tangents optional too.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec2> uvs1;  // the second set, for textures with UvTransform::set 1
    // glTF's TANGENT: xyz the unit tangent (along +u), w = +-1 the handedness, bitangent =
    // w cross(normal, tangent). Empty: generated where a normal map needs them
    // (scenes/tangents.h).
    std::vector<glm::vec4> tangents;
    std::vector<uint32_t> indices;  // three per triangle, counter-clockwise = front

    std::size_t triangleCount() const { return indices.size() / 3; }
};

// How one texture slot maps the mesh's UVs: which set (glTF's texCoord), then glTF's
// KHR_texture_transform:
// uv' = linear * uv + offset, with linear = R(rotation) S(scale) and
//   R = [ cos  sin ]   (rows; counter-clockwise in UV space, whose v points down the image,
//       [-sin  cos ]    as the extension's worked example reads: offset (0, 1), rotation
//                       90 degrees and scale 0.5 pick the lower-left quadrant).
// The screen derivatives of the UV go through `linear` alone, before the level of detail.
struct UvTransform {
    glm::vec2 row0{1.0f, 0.0f};  // u' = dot(row0, uv) + offset.x
    glm::vec2 row1{0.0f, 1.0f};  // v' = dot(row1, uv) + offset.y
    glm::vec2 offset{0.0f};
    int set = 0;  // 0: Mesh::uvs, 1: Mesh::uvs1 (not part of the transform)

    bool identity() const {
        return row0 == glm::vec2(1.0f, 0.0f) && row1 == glm::vec2(0.0f, 1.0f) &&
               offset == glm::vec2(0.0f);
    }
    glm::vec2 linear(glm::vec2 d) const { return {glm::dot(row0, d), glm::dot(row1, d)}; }
    glm::vec2 apply(glm::vec2 uv) const { return linear(uv) + offset; }
};

// glTF 2.0 metallic-roughness; roughness is perceptual (alpha = roughness^2).
struct Material {
    std::string name;
    glm::vec3 baseColor{0.8f};
    float metallic = 0.0f;
    float roughness = 0.5f;
    glm::vec3 emissive{0.0f};
    bool doubleSided = false;  // false: back faces are culled (glTF's default)
    // Indices into Scene::textures, or -1. The texel multiplies the factor: base colour by
    // RGB, metallic by B and roughness by G (glTF's metallic-roughness texture). UVs are
    // the mesh's (a mesh without UVs samples at (0, 0)).
    int32_t baseColorTexture = -1;
    int32_t metallicRoughnessTexture = -1;
    UvTransform baseColorUv, metallicRoughnessUv;  // identity: the mesh's UVs as they are
    // Normal, occlusion and emissive textures (glTF 2.0 section 3.9.3-3.9.5), -1 when absent.
    //   normal:    linear tangent-space normals, n = normalize((2 texel - 1) (scale, scale, 1))
    //              in the frame (tangent, bitangent, normal) of Mesh::tangents;
    //   occlusion: linear, R: occlusion = 1 + strength (R - 1), on indirect light only (the
    //              sky's diffuse and specular, SSR and SSGI; not the sun, not emission);
    //   emissive:  sRGB decoded (as base colour), RGB multiplies `emissive`.
    int32_t normalTexture = -1;
    int32_t occlusionTexture = -1;
    int32_t emissiveTexture = -1;
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;
    UvTransform normalUv, occlusionUv, emissiveUv;

    // Alpha coverage (glTF 2.0 section 3.9.4, alphaMode and alphaCutoff): alpha is
    // baseColorAlpha (baseColorFactor's fourth component) times the base colour texel's
    // alpha. OPAQUE ignores it; MASK draws a point where alpha >= alphaCutoff and cuts it out
    // elsewhere, in the camera's view, the shadow map and the truth alike; BLEND is drawn as
    // MASK (the loader warns). scenes/material_alpha.h evaluates it.
    enum class AlphaMode { Opaque, Mask, Blend };
    AlphaMode alphaMode = AlphaMode::Opaque;
    float baseColorAlpha = 1.0f;
    float alphaCutoff = 0.5f;
    bool alphaTested() const { return alphaMode != AlphaMode::Opaque; }

    bool textured() const {
        return baseColorTexture >= 0 || metallicRoughnessTexture >= 0 || normalTexture >= 0 ||
               occlusionTexture >= 0 || emissiveTexture >= 0;
    }
    // Whether a texture of this material reads the second UV set.
    bool usesUvSet1() const {
        return (baseColorTexture >= 0 && baseColorUv.set == 1) ||
               (metallicRoughnessTexture >= 0 && metallicRoughnessUv.set == 1) ||
               (normalTexture >= 0 && normalUv.set == 1) ||
               (occlusionTexture >= 0 && occlusionUv.set == 1) ||
               (emissiveTexture >= 0 && emissiveUv.set == 1);
    }
};

// A mesh placed in the world; previousTransform gives rigid motion for motion vectors.
struct Instance {
    uint32_t mesh = 0;
    uint32_t material = 0;
    glm::mat4 transform{1.0f};
    glm::mat4 previousTransform{1.0f};
};

// translate(-origin) * m, formed in double: a transform whose points are measured from
// `origin` (Scene::origin()). Far from 0, a float product would round the translation to
// the float spacing there (about 1e-3 at 1e4) before anything cancels.
glm::mat4 transformFrom(const glm::mat4& m, glm::vec3 origin);

// An axis-aligned box (Scene::bounds) and the two facts the passes and the truth take from
// it, in one place so that every user derives them alike.
struct Bounds {
    glm::vec3 lo{0.0f}, hi{0.0f};
    // Where the renderer and the truth measure world positions from (Scene::origin()).
    glm::vec3 centre() const { return 0.5f * (lo + hi); }
    // The unit of the tracer's relative lengths; 1 where the box is a point (no length to
    // measure against).
    float diagonal() const;
};

struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // the way the light travels (unit)
    glm::vec3 color{1.0f};
    float intensity = 3.0f;  // irradiance on a surface facing the light
};

// An equirectangular (latitude-longitude) HDR image: linear RGB, interleaved, row-major,
// row 0 at +Y, u = 0.5 looking down -Z (the mapping of shading/environment.h). Loaded at the
// edge (io/image_io.h readSkyImage; renderer/sky_lighting.h makeSkyImage). Never changed once
// shared: the renderer caches what it derives from it (prefiltered levels, irradiance) by the
// image's identity.
struct SkyImage {
    std::string source;  // where it came from (a path), for messages
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 * width * height finite values >= 0
};

// Constant sky (zenith is its colour), an analytic gradient (ground below the horizon,
// horizon to zenith above), or an equirectangular image; each scaled by intensity.
struct Sky {
    enum class Kind { Constant, Gradient, Image };
    Kind kind = Kind::Gradient;
    glm::vec3 zenith{0.25f, 0.45f, 0.85f};
    glm::vec3 horizon{0.75f, 0.8f, 0.9f};
    glm::vec3 ground{0.3f, 0.27f, 0.25f};
    float intensity = 0.5f;
    std::shared_ptr<const SkyImage> image;  // Kind::Image only

    // Radiance arriving from direction `dir` (unit, world space, y up). An image is read at
    // its nearest texel here (the renderer filters bilinearly).
    glm::vec3 radiance(glm::vec3 dir) const;
};

// A pinhole camera looking from position to target. fovY in degrees.
struct Camera {
    glm::vec3 position{0.0f, 1.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 45.0f;
    float nearZ = 0.05f;
    float farZ = 100.0f;

    glm::mat4 view() const;
    // The view matrix of points measured from `origin` (Scene::origin()): the same camera,
    // its translation formed in double so that a scene far from 0 keeps its precision.
    glm::mat4 viewFrom(glm::vec3 origin) const;
    glm::mat4 projection(float aspect) const;  // OpenGL clip space: w = -z_view
};

struct Scene {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Instance> instances;
    std::vector<Texture> textures;
    DirectionalLight light;
    Sky sky;
    Camera camera;
    Camera previousCamera;  // the pose one frame earlier (equal to camera for a still frame)

    std::size_t triangleCount() const;
    // World-space bounds of every instance (finite vertices only; all 0 without any). One
    // pass over every vertex: callers that need several of the facts below take it once.
    Bounds bounds() const;
    void bounds(glm::vec3& lo, glm::vec3& hi) const;
    // Where the renderer and the truth measure world positions from: the bounds' centre.
    // Every pass works on positions relative to it (transformFrom, Camera::viewFrom), so a
    // scene 1e4 units from 0 is as precise as one at 0 (issue 16).
    glm::vec3 origin() const { return bounds().centre(); }
    // The bounds' diagonal: the unit of the tracer's relative lengths (Bounds::diagonal).
    float diagonal() const { return bounds().diagonal(); }
    // Throws std::invalid_argument naming the first broken reference (mesh, material, index,
    // texture).
    void validate() const;
};

}  // namespace ssrt
