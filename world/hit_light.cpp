#include "world/hit_light.h"

#include <limits>

namespace ssrt::worldhit {

namespace ln = ssrt::lanes;

namespace {

using V3f = ln::V3<float>;

V3f toV3(glm::vec3 v) { return {v.x, v.y, v.z}; }
glm::vec3 toGlm(const V3f& v) { return {v.x, v.y, v.z}; }

}  // namespace

PointSurface pixelSurface(const DirectArgs& a, int x, int y) {
    // The direct kernel's camera ray and point, operation for operation (shadeChunk).
    const std::size_t go = std::size_t(y) * a.g.stride + x;
    const float viewZ = a.g.viewZ[go];
    const float px = (float(x) + 0.0f) + 0.5f;
    const float ndcX = px * (2.0f / float(a.width)) - 1.0f;
    const float ndcY = 1.0f - (float(y) + 0.5f) * (2.0f / float(a.height));
    const V3f dirView{ndcX * a.tanHalfX, ndcY * a.tanHalfY, -1.0f};
    const float* r = a.viewToWorld;
    const V3f dirWorld{(r[0] * dirView.x + r[3] * dirView.y) + r[6] * dirView.z,
                       (r[1] * dirView.x + r[4] * dirView.y) + r[7] * dirView.z,
                       (r[2] * dirView.x + r[5] * dirView.y) + r[8] * dirView.z};
    PointSurface s;
    s.p = shade::splat3<float>(a.camPos) + dirWorld * viewZ;
    s.n = {a.g.normal[0][go], a.g.normal[1][go], a.g.normal[2][go]};
    s.albedo = {a.g.albedo[0][go], a.g.albedo[1][go], a.g.albedo[2][go]};
    s.metallic = a.g.metallic[go];
    s.roughness = a.g.roughness[go];
    const V3f toCam = ln::normalize(dirWorld);
    s.view = {0.0f - toCam.x, 0.0f - toCam.y, 0.0f - toCam.z};
    return s;
}

float embreeSunVisibility(const ShadingContext& c, glm::vec3 origin) {
    const float* l = c.lighting->toLight;
    return c.embree->occluded(origin, {l[0], l[1], l[2]}, c.embree->epsilon(),
                              std::numeric_limits<float>::infinity())
               ? 0.0f
               : 1.0f;
}

float sunVisibility(const ShadingContext& c, const PointSurface& s, glm::vec3 offsetOrigin) {
    if (c.visibility == SunVisibility::ShadowMap) return shade::shadowMapVisibility(*c.lighting, s);
    if (!(ln::dot(s.n, shade::splat3<float>(c.lighting->toLight)) > 0.0f)) return 0.0f;
    return embreeSunVisibility(c, offsetOrigin);
}

namespace {

// A traced hit as the shading sees it: the surface point turned towards the ray.
struct FacingHit {
    SurfacePoint sp;
    glm::vec3 ng{0.0f}, n{0.0f};
    bool lit = false;  // false: the back face of a single-sided material (black)
};

FacingHit facingHit(const ShadingContext& c, glm::vec3 origin, glm::vec3 dir,
                    const EmbreeHit& hit) {
    FacingHit f;
    f.sp = c.embree->surface(origin, dir, hit);
    f.ng = f.sp.geometricNormal;
    f.n = f.sp.shadingNormal;
    // Seen from behind: a double-sided surface turns its normals towards the ray.
    if (glm::dot(f.ng, dir) > 0.0f) {
        if (!f.sp.doubleSided) return f;
        f.ng = -f.ng;
        f.n = -f.n;
    }
    f.lit = true;
    return f;
}

PointSurface pointSurface(const FacingHit& f, glm::vec3 dir) {
    PointSurface s;
    s.p = toV3(f.sp.position);
    s.n = toV3(f.n);
    s.albedo = toV3(f.sp.baseColor);
    s.view = toV3(-dir);
    s.metallic = f.sp.metallic;
    s.roughness = f.sp.roughness;
    return s;
}

// The SSGI kernel's Lambert part: albedo (1 - metallic) / pi E_sun n.l visibility, plus
// emission.
glm::vec3 lambertHitLight(const ShadingContext& c, const PointSurface& s, const SurfacePoint& sp,
                          float vis) {
    const DirectArgs& a = *c.lighting;
    const float NoL = ln::saturate(ln::dot(s.n, shade::splat3<float>(a.toLight)));
    const V3f diffuse = s.albedo * ((1.0f - s.metallic) * ln::kInvPi);
    const V3f lit = diffuse * shade::splat3<float>(a.lightRadiance) * (NoL * vis);
    return toGlm(lit) + sp.emissive;
}

}  // namespace

glm::vec3 hitRadiance(const ShadingContext& c, glm::vec3 origin, glm::vec3 dir,
                      const EmbreeHit& hit, bool full) {
    const FacingHit f = facingHit(c, origin, dir, hit);
    if (!f.lit) return glm::vec3(0.0f);
    const SurfacePoint& sp = f.sp;
    const PointSurface s = pointSurface(f, dir);
    const float vis = sunVisibility(c, s, sp.position + f.ng * c.embree->epsilon());
    if (full) {
        shade::Parts<float> p = shade::shadeSurface(*c.lighting, s, vis);
        if (sp.occlusion != 1.0f) shade::occludeIndirect(p, sp.occlusion);
        // The direct pass's `color` order: ((sun + envDiffuse) + specWeight envSpecular) +
        // emission.
        const V3f lit = (p.sun + p.envDiffuse) + p.specWeight * p.envSpecular;
        return toGlm(lit) + sp.emissive;
    }
    return lambertHitLight(c, s, sp, vis);
}

DiffuseVertex diffuseVertex(const ShadingContext& c, glm::vec3 origin, glm::vec3 dir,
                            const EmbreeHit& hit) {
    const FacingHit f = facingHit(c, origin, dir, hit);
    DiffuseVertex v;
    if (!f.lit) return v;
    const PointSurface s = pointSurface(f, dir);
    v.origin = f.sp.position + f.ng * c.embree->epsilon();
    v.radiance = lambertHitLight(c, s, f.sp, sunVisibility(c, s, v.origin));
    v.reflectance = f.sp.baseColor * ((1.0f - f.sp.metallic) * f.sp.occlusion);
    v.normal = f.n;
    v.geometricNormal = f.ng;
    return v;
}

glm::vec3 missRadiance(const ShadingContext& c, glm::vec3 dir) {
    return toGlm(shade::skyRadiance(*c.lighting, toV3(dir)));
}

}  // namespace ssrt::worldhit
