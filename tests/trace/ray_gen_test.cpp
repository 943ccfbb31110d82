// Ray generation (trace/ray_gen.h) on real G-buffers: origins, unit directions above the
// surface, exact mirror reflections, the PDF written against the sampler's PDF function,
// the lobe against a quadrature of that PDF, rejections counted, no NaN anywhere, and the
// determinism contract (threads, ISAs, frames).
#include "trace/ray_gen.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/isa.h"
#include "core/rng.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "shading/brdf.h"
#include "shading/sampling.h"
#include "shading/sampling_stats.h"
#include "thread_counts.h"

using namespace ssrt;

namespace {

namespace sm = ssrt::sampling;
using V3f = ssrt::lanes::V3<float>;

// A rendered G-buffer and the trace camera of the same view.
struct GBufferFrame {
    Frame frame;
    TraceCamera camera;
    // The planes every lobe reads: viewZ, normal and roughness (not the diffuse colour).
    GBufferView g() const {
        const GBuffer& b = frame.gbuffer;
        return gbufferView("test", width(), height(),
                           {{kGViewZ, &b.viewZ},
                            {kGNormalX, &b.normal[0]},
                            {kGNormalY, &b.normal[1]},
                            {kGNormalZ, &b.normal[2]},
                            {kGRoughness, &b.roughness}});
    }
    int width() const { return camera.width; }
    int height() const { return camera.height; }
};

TraceCamera traceCamera(const Camera& c, int w, int h) {
    TraceCamera t;
    t.width = w;
    t.height = h;
    t.tanHalfY = std::tan(glm::radians(c.fovY) * 0.5f);
    t.tanHalfX = t.tanHalfY * (float(w) / float(h));
    t.nearZ = c.nearZ;
    t.farZ = c.farZ;
    const glm::mat3 viewToWorld = glm::mat3(glm::inverse(c.view()));
    std::copy_n(glm::value_ptr(viewToWorld), 9, t.viewToWorld);
    return t;
}

GBufferFrame renderScene(const Scene& scene, int w, int h) {
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.shadowMapSize = 256;
    rs.threads = 1;
    GBufferFrame f{Renderer(rs).renderWithoutHistory(scene), traceCamera(scene.camera, w, h)};
    return f;
}

GBufferFrame renderBuiltin(const std::string& name, int w = 160, int h = 96) {
    return renderScene(makeBuiltinScene(name), w, h);
}

// A flat floor (y = 0, normal +y) of one roughness, seen from height `eye` looking at a
// point `dist` ahead and `side` to the right (a yaw: the view-to-world rotation is then no
// rotation about x alone): the far pixels see it at grazing angles.
Scene floorScene(float roughness, float eye, float dist, float side = 0.0f) {
    Scene s;
    Mesh mesh;
    mesh.positions = {{-500, 0, 500}, {500, 0, 500}, {500, 0, -500}, {-500, 0, -500}};
    mesh.normals.assign(4, {0, 1, 0});
    mesh.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(mesh);
    Material m;
    m.roughness = roughness;
    s.materials.push_back(m);
    s.instances.push_back(Instance{});
    s.light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f));
    s.camera.position = {0, eye, 0};
    s.camera.target = {side, 0, -dist};
    s.camera.farZ = 2000.0f;
    s.previousCamera = s.camera;
    return s;
}

struct Vec {
    double x, y, z;
};
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec normalized(Vec v) {
    const double l = std::sqrt(dot(v, v));
    return {v.x / l, v.y / l, v.z / l};
}

// The pixel's shading normal in view space (double), and its view direction (to the camera).
Vec viewNormal(const GBufferFrame& f, int x, int y) {
    const float* r = f.camera.viewToWorld;
    const Vec nw{f.frame.gbuffer.normal[0].at(x, y), f.frame.gbuffer.normal[1].at(x, y),
                 f.frame.gbuffer.normal[2].at(x, y)};
    return normalized({r[0] * nw.x + r[1] * nw.y + r[2] * nw.z,
                       r[3] * nw.x + r[4] * nw.y + r[5] * nw.z,
                       r[6] * nw.x + r[7] * nw.y + r[8] * nw.z});
}
Vec viewRay(const TraceCamera& c, int x, int y) {
    return {(2.0 * (x + 0.5) / c.width - 1.0) * c.tanHalfX,
            (1.0 - 2.0 * (y + 0.5) / c.height) * c.tanHalfY, -1.0};
}
Vec toViewer(const TraceCamera& c, int x, int y) {
    const Vec r = normalized(viewRay(c, x, y));
    return {-r.x, -r.y, -r.z};
}

Vec dirAt(const RayBatch& r, int x, int y) { return {r.dx.at(x, y), r.dy.at(x, y), r.dz.at(x, y)}; }

// Float local frame around n (any tangent: the lobes are isotropic), for the samplers' PDFs.
struct Frame3 {
    V3f t, b, n;
    explicit Frame3(Vec nd) {
        n = {float(nd.x), float(nd.y), float(nd.z)};
        const Vec a = std::abs(nd.x) > 0.5 ? Vec{0, 1, 0} : Vec{1, 0, 0};
        const Vec td =
            normalized({a.y * nd.z - a.z * nd.y, a.z * nd.x - a.x * nd.z, a.x * nd.y - a.y * nd.x});
        const Vec bd{nd.y * td.z - nd.z * td.y, nd.z * td.x - nd.x * td.z,
                     nd.x * td.y - nd.y * td.x};
        t = {float(td.x), float(td.y), float(td.z)};
        b = {float(bd.x), float(bd.y), float(bd.z)};
    }
    V3f local(Vec v) const {
        const V3f w{float(v.x), float(v.y), float(v.z)};
        return {ssrt::lanes::dot(w, t), ssrt::lanes::dot(w, b), ssrt::lanes::dot(w, n)};
    }
};

// The sampler's own PDF of the reflected direction wo (local frame).
float methodPdf(SsrMethod m, V3f wi, V3f wo, float alpha) {
    switch (m) {
        case SsrMethod::Mirror: return 1.0f;
        case SsrMethod::GgxNdf: return sm::ggxNdfReflectionPdf(wi, wo, alpha, alpha);
        case SsrMethod::VndfEllipsoid:
        case SsrMethod::VndfSphericalCaps: return sm::vndfReflectionPdf(wi, wo, alpha, alpha);
        case SsrMethod::VndfBounded: return sm::vndfBoundedReflectionPdf(wi, wo, alpha, alpha);
    }
    return 0.0f;
}

bool finite(float v) { return std::isfinite(v); }

uint64_t batchHash(const RayBatch& r) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const PlaneF* p : {&r.ox, &r.oy, &r.oz, &r.dx, &r.dy, &r.dz, &r.pdf}) h = hashPlane(*p, h);
    return h;
}

// Specular for a method, or diffuse when `method` is null.
RayGenStats generate(const GBufferFrame& f, const SsrMethod* method, RayBatch& rays,
                     uint32_t frame = 0, uint32_t sample = 0, Isa isa = Isa::Scalar,
                     int threads = 1) {
    return method
               ? generateSpecularRays(isa, *method, frame, sample, f.camera, f.g(), rays, threads)
               : generateDiffuseRays(isa, frame, sample, f.camera, f.g(), rays, threads);
}

// Every invariant that holds pixel by pixel; returns the number of rays seen.
uint64_t checkBatch(const GBufferFrame& f, const SsrMethod* method, const RayBatch& rays,
                    const RayGenStats& stats) {
    const PlaneF& viewZ = f.frame.gbuffer.viewZ;
    const PlaneF& rough = f.frame.gbuffer.roughness;
    uint64_t surface = 0, background = 0, withRay = 0, bad = 0;
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) {
            const float z = viewZ.at(x, y);
            const float o[3] = {rays.ox.at(x, y), rays.oy.at(x, y), rays.oz.at(x, y)};
            const float d[3] = {rays.dx.at(x, y), rays.dy.at(x, y), rays.dz.at(x, y)};
            const float pdf = rays.pdf.at(x, y);
            bool ok = finite(o[0]) && finite(o[1]) && finite(o[2]) && finite(d[0]) &&
                      finite(d[1]) && finite(d[2]) && finite(pdf) && pdf >= 0.0f;
            if (!(z > 0.0f)) {
                // Background: no ray at all
                ++background;
                ok = ok && o[0] == 0.0f && o[1] == 0.0f && o[2] == 0.0f && d[0] == 0.0f &&
                     d[1] == 0.0f && d[2] == 0.0f && pdf == 0.0f;
            } else {
                ++surface;
                // The origin is the pixel's surface point
                const Vec ray = viewRay(f.camera, x, y);
                ok = ok && o[2] == -z && std::abs(o[0] - ray.x * z) <= 1e-5 * (1.0 + z) &&
                     std::abs(o[1] - ray.y * z) <= 1e-5 * (1.0 + z);
                if (pdf > 0.0f) {
                    ++withRay;
                    // Unit, above the surface, and the PDF of the sampler for it
                    const Vec dir{d[0], d[1], d[2]};
                    const Vec n = viewNormal(f, x, y);
                    ok = ok && std::abs(dot(dir, dir) - 1.0) < 1e-5 && dot(n, dir) > 0.0;
                    const Frame3 fr(n);
                    const V3f wo = fr.local(dir);
                    float expect;
                    if (method) {
                        // (specular: only where the shading normal faces the viewer)
                        ok = ok && dot(n, toViewer(f.camera, x, y)) > 0.0;
                        const V3f wi = fr.local(toViewer(f.camera, x, y));
                        const float alpha = brdf::roughnessToAlpha(rough.at(x, y));
                        expect = methodPdf(*method, wi, wo, alpha);
                    } else {
                        expect = sm::cosineHemispherePdf(wo);
                    }
                    // (the frames differ by roundings; the PDFs are smooth over them except
                    // at alpha near 1e-3, where D spans 10 decades in a milliradian)
                    const float tol =
                        method && *method != SsrMethod::Mirror && rough.at(x, y) < 0.1f ? 0.2f
                                                                                        : 2e-3f;
                    ok = ok && std::abs(pdf - expect) <= tol * expect + 1e-5f;
                } else {
                    ok = ok && d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f;
                }
            }
            if (!ok && ++bad <= 5) {
                std::printf("bad ray at (%d, %d): z %g o %g %g %g d %g %g %g pdf %g\n", x, y, z,
                            o[0], o[1], o[2], d[0], d[1], d[2], pdf);
            }
        }
    CHECK(bad == 0);
    CHECK(stats.pixels == surface);
    CHECK(stats.background == background);
    CHECK(stats.rays == withRay);
    CHECK(stats.belowSurface == surface - withRay);
    return withRay;
}

}  // namespace

TEST_CASE("ray generation: method names round trip") {
    for (SsrMethod m : kAllSsrMethods) {
        const auto parsed = parseSsrMethod(ssrMethodName(m));
        REQUIRE(parsed.has_value());
        CHECK(*parsed == m);
    }
    CHECK(ssrMethodName(SsrMethod::VndfSphericalCaps) == "vndf_spherical_caps");
    CHECK_FALSE(parseSsrMethod("vndf").has_value());
    CHECK_FALSE(parseSsrMethod("").has_value());
}

TEST_CASE("ray generation: origins, unit directions above the surface, PDFs, no NaN") {
    // spheres: roughness 0 to 1, background sky, silhouettes; the grazing floor: views
    // down to the horizon at roughness 0 and 1
    struct Case {
        std::string name;
        GBufferFrame f;
    };
    std::vector<Case> cases;
    // (odd sizes: partial tiles and partial lane groups at the right and bottom edges)
    cases.push_back({"spheres", renderBuiltin("spheres", 157, 91)});
    cases.push_back({"cornell", renderBuiltin("cornell", 99, 71)});
    cases.push_back({"floor r0", renderScene(floorScene(0.0f, 0.3f, 20.0f, 8.0f), 96, 64)});
    cases.push_back({"floor r1", renderScene(floorScene(1.0f, 0.3f, 20.0f, -6.0f), 96, 64)});
    for (const Case& c : cases) {
        CAPTURE(c.name);
        for (Isa isa : {Isa::Scalar, supportedIsas().back()}) {
            CAPTURE(isaName(isa));
            for (SsrMethod m : kAllSsrMethods) {
                CAPTURE(ssrMethodName(m));
                RayBatch rays;
                const RayGenStats s = generate(c.f, &m, rays, 3, 1, isa, 2);
                CHECK(checkBatch(c.f, &m, rays, s) > 0);
            }
            RayBatch rays;
            const RayGenStats s = generate(c.f, nullptr, rays, 3, 1, isa, 2);
            CHECK(checkBatch(c.f, nullptr, rays, s) == s.pixels);
            CHECK(s.belowSurface == 0);
        }
    }
}

TEST_CASE("ray generation: background pixels have no ray") {
    const GBufferFrame f = renderBuiltin("spheres");
    for (SsrMethod m : kAllSsrMethods) {
        RayBatch rays;
        const RayGenStats s = generate(f, &m, rays);
        CHECK(s.background > 0);
        CHECK(s.pixels + s.background == uint64_t(f.width()) * uint64_t(f.height()));
        // (checkBatch holds every background pixel to zeros)
        checkBatch(f, &m, rays, s);
    }
}

TEST_CASE(
    "ray generation: a roughness cut leaves the rougher pixels without a ray, the rest as they "
    "were") {
    // Cornell: walls 0.9, box 0.6, floor 0.15, mirror 0.02; one wall pixel made NaN.
    GBufferFrame f = renderBuiltin("cornell", 203, 137);
    PlaneF& rough = f.frame.gbuffer.roughness;
    const PlaneF& viewZ = f.frame.gbuffer.viewZ;
    // Three smooth pixels edited: NaN, exactly the cut (no ray: the fade is 0 there) and the
    // float just below it (a ray).
    const float cut = 0.7f;
    std::vector<std::pair<int, int>> edited;
    for (int y = 0; y < f.height() && edited.size() < 3; ++y)
        for (int x = 0; x < f.width() && edited.size() < 3; x += 5)
            if (viewZ.at(x, y) > 0.0f && rough.at(x, y) < 0.5f) edited.emplace_back(x, y);
    REQUIRE(edited.size() == 3);
    const auto [nanX, nanY] = edited[0];
    const auto [atX, atY] = edited[1];
    const auto [belowX, belowY] = edited[2];
    rough.at(nanX, nanY) = std::nanf("");
    rough.at(atX, atY) = cut;
    rough.at(belowX, belowY) = std::nextafter(cut, 0.0f);
    for (SsrMethod m : kAllSsrMethods) {
        CAPTURE(ssrMethodName(m));
        for (Isa isa : supportedIsas()) {
            CAPTURE(isaName(isa));
            RayBatch all, some;
            const RayGenStats sa = generateSpecularRays(isa, m, 3, 1, f.camera, f.g(), all, 2);
            const RayGenStats ss =
                generateSpecularRays(isa, m, 3, 1, f.camera, f.g(), some, 2, cut);
            uint64_t rougher = 0, keptRays = 0;
            bool cutOnes = true, sameOthers = true;
            for (int y = 0; y < f.height(); ++y)
                for (int x = 0; x < f.width(); ++x) {
                    if (!(viewZ.at(x, y) > 0.0f)) continue;
                    const PlaneF* ps[7] = {&all.ox, &all.oy, &all.oz, &all.dx,
                                           &all.dy, &all.dz, &all.pdf};
                    const PlaneF* qs[7] = {&some.ox, &some.oy, &some.oz, &some.dx,
                                           &some.dy, &some.dz, &some.pdf};
                    if (!(rough.at(x, y) < cut)) {
                        ++rougher;
                        // No ray: pdf and direction 0; the origin is still the surface point.
                        cutOnes &= some.pdf.at(x, y) == 0.0f && some.dx.at(x, y) == 0.0f &&
                                   some.dy.at(x, y) == 0.0f && some.dz.at(x, y) == 0.0f &&
                                   some.oz.at(x, y) == all.oz.at(x, y);
                        continue;
                    }
                    keptRays += some.pdf.at(x, y) > 0.0f;
                    for (int p = 0; p < 7; ++p)
                        sameOthers &= std::memcmp(&ps[p]->at(x, y), &qs[p]->at(x, y), 4) == 0;
                }
            CHECK(rougher > 1000);  // the walls
            CHECK(ss.hidden == rougher);
            CHECK(sa.hidden == 0);
            CHECK(cutOnes);
            CHECK(sameOthers);
            CHECK(some.pdf.at(nanX, nanY) == 0.0f);  // NaN roughness is not below the cut
            CHECK(some.pdf.at(atX, atY) == 0.0f);
            // Just below the cut: the pixel's own ray (a mirror ray is never rejected there).
            CHECK(std::memcmp(&some.pdf.at(belowX, belowY), &all.pdf.at(belowX, belowY), 4) == 0);
            if (m == SsrMethod::Mirror) CHECK(some.pdf.at(belowX, belowY) > 0.0f);
            CHECK(ss.rays == keptRays);
            CHECK(ss.rays + ss.belowSurface + ss.hidden == ss.pixels);
            CHECK(ss.pixels == sa.pixels);
            CHECK(ss.background == sa.background);
        }
    }
    // Diffuse rays take no cut; a NaN cut is refused.
    RayBatch rays;
    CHECK(generateDiffuseRays(defaultIsa(), 0, 0, f.camera, f.g(), rays, 1).hidden == 0);
    CHECK_THROWS_AS(generateSpecularRays(defaultIsa(), SsrMethod::Mirror, 0, 0, f.camera, f.g(),
                                         rays, 1, std::nanf("")),
                    std::invalid_argument);
}

TEST_CASE("ray generation: NoDiffuseColour leaves pixels without a diffuse colour without a ray") {
    // Cornell has a mirror (metallic 1); four more pixels are edited: black albedo (no ray),
    // one channel of albedo left at half metallic (a ray), NaN metallic (a ray: the
    // composite's colour is NaN there, not 0), metallic 1 on a wall (no ray).
    GBufferFrame f = renderBuiltin("cornell", 203, 137);
    PlaneF& r = f.frame.gbuffer.albedo[0];
    PlaneF& g = f.frame.gbuffer.albedo[1];
    PlaneF& b = f.frame.gbuffer.albedo[2];
    PlaneF& metallic = f.frame.gbuffer.metallic;
    const PlaneF& viewZ = f.frame.gbuffer.viewZ;
    const int y = f.height() / 2;
    std::vector<int> xs;
    for (int x = 0; x < f.width() && xs.size() < 4; x += 7)
        if (viewZ.at(x, y) > 0.0f && metallic.at(x, y) == 0.0f) xs.push_back(x);
    REQUIRE(xs.size() == 4);
    r.at(xs[0], y) = g.at(xs[0], y) = b.at(xs[0], y) = 0.0f;
    r.at(xs[1], y) = g.at(xs[1], y) = 0.0f, b.at(xs[1], y) = 0.1f, metallic.at(xs[1], y) = 0.5f;
    metallic.at(xs[2], y) = std::nanf("");
    metallic.at(xs[3], y) = 1.0f;
    const GBufferView gb = f.frame.gbuffer.view();
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        RayBatch all, some;
        const RayGenStats sa = generateDiffuseRays(isa, 4, 2, f.camera, gb, all, 2);
        const RayGenStats ss =
            generateDiffuseRays(isa, 4, 2, f.camera, gb, some, 2, DiffuseCut::NoDiffuseColour);
        uint64_t none = 0;
        bool cut = true, kept = true;
        for (int v = 0; v < f.height(); ++v)
            for (int x = 0; x < f.width(); ++x) {
                if (!(viewZ.at(x, v) > 0.0f)) continue;
                const float keep = 1.0f - metallic.at(x, v);
                const bool dark = r.at(x, v) * keep == 0.0f && g.at(x, v) * keep == 0.0f &&
                                  b.at(x, v) * keep == 0.0f;
                if (dark) {
                    ++none;
                    cut &= some.pdf.at(x, v) == 0.0f && some.dx.at(x, v) == 0.0f;
                } else {
                    for (const auto m :
                         {&RayBatch::dx, &RayBatch::dy, &RayBatch::dz, &RayBatch::pdf})
                        kept &= std::memcmp(&(all.*m).at(x, v), &(some.*m).at(x, v), 4) == 0;
                }
            }
        CHECK(none > 100);  // the mirror, and two edited pixels
        CHECK(ss.hidden == none);
        CHECK(sa.hidden == 0);
        CHECK(cut);
        CHECK(kept);
        CHECK(some.pdf.at(xs[0], y) == 0.0f);
        CHECK(some.pdf.at(xs[1], y) > 0.0f);
        CHECK(some.pdf.at(xs[2], y) > 0.0f);
        CHECK(some.pdf.at(xs[3], y) == 0.0f);
        CHECK(ss.rays + ss.belowSurface + ss.hidden == ss.pixels);
    }
    // It needs the planes it reads.
    RayBatch rays;
    CHECK_THROWS_AS(generateDiffuseRays(defaultIsa(), 0, 0, f.camera, f.g(), rays, 1,
                                        DiffuseCut::NoDiffuseColour),
                    std::invalid_argument);
}

TEST_CASE("ray generation: mirror rays are exact reflections") {
    for (const GBufferFrame& f :
         {renderBuiltin("spheres"), renderScene(floorScene(0.5f, 1.0f, 6.0f, 2.0f), 96, 64)}) {
        const SsrMethod m = SsrMethod::Mirror;
        RayBatch rays;
        const RayGenStats s = generate(f, &m, rays, 0, 0, supportedIsas().back(), 2);
        double worst = 0.0;
        int facing = 0;
        for (int y = 0; y < f.height(); ++y)
            for (int x = 0; x < f.width(); ++x) {
                if (!(f.frame.gbuffer.viewZ.at(x, y) > 0.0f)) continue;
                const Vec n = viewNormal(f, x, y), v = toViewer(f.camera, x, y);
                const double nv = dot(n, v);
                if (nv <= 0.0) {
                    CHECK(rays.pdf.at(x, y) == 0.0f);
                    continue;
                }
                ++facing;
                // r = 2 (n.v) n - v, in double
                const Vec r{2 * nv * n.x - v.x, 2 * nv * n.y - v.y, 2 * nv * n.z - v.z};
                const Vec d = dirAt(rays, x, y);
                if (nv > 1e-3) CHECK(rays.pdf.at(x, y) == 1.0f);
                if (rays.pdf.at(x, y) == 0.0f) continue;
                worst = std::max(
                    {worst, std::abs(d.x - r.x), std::abs(d.y - r.y), std::abs(d.z - r.z)});
            }
        CHECK(facing > 0);
        CHECK(worst < 2e-6);
        (void)s;
    }
}

TEST_CASE("ray generation: rejections below the surface are counted per method") {
    // A flat floor seen from above: every mirror ray leaves it
    {
        const GBufferFrame f = renderScene(floorScene(0.5f, 1.0f, 6.0f), 96, 64);
        const SsrMethod m = SsrMethod::Mirror;
        RayBatch rays;
        const RayGenStats s = generate(f, &m, rays);
        CHECK(s.pixels > 0);
        CHECK(s.belowSurface == 0);
        CHECK(s.rays == s.pixels);
    }
    // Roughness 1 at grazing views: NDF samples reflect into the floor; the bounded VNDF
    // rejects fewer than the unbounded caps, which reject fewer than NDF sampling
    const GBufferFrame f = renderScene(floorScene(1.0f, 0.2f, 30.0f), 96, 64);
    RayGenStats st[5];
    for (SsrMethod m : kAllSsrMethods) {
        RayBatch rays;
        for (uint32_t sample = 0; sample < 4; ++sample)
            st[int(m)].add(generate(f, &m, rays, 0, sample));
    }
    CHECK(st[int(SsrMethod::Mirror)].belowSurface == 0);
    CHECK(st[int(SsrMethod::GgxNdf)].belowSurface > 0);
    CHECK(st[int(SsrMethod::VndfSphericalCaps)].belowSurface > 0);
    CHECK(st[int(SsrMethod::VndfBounded)].belowSurface <
          st[int(SsrMethod::VndfSphericalCaps)].belowSurface);
    CHECK(st[int(SsrMethod::VndfSphericalCaps)].belowSurface <
          st[int(SsrMethod::GgxNdf)].belowSurface);
    for (const RayGenStats& s : st) CHECK(s.rays + s.belowSurface == s.pixels);
}

namespace {

// The lobe of pixel (px, py) for every method but Mirror, and the cosine lobe.
void checkLobe(const GBufferFrame& f, int px, int py) {
    REQUIRE(f.frame.gbuffer.viewZ.at(px, py) > 0.0f);
    const Vec n = viewNormal(f, px, py);
    const Frame3 fr(n);
    const V3f wi = fr.local(toViewer(f.camera, px, py));
    CAPTURE(wi.z);
    const float alpha = brdf::roughnessToAlpha(f.frame.gbuffer.roughness.at(px, py));
    // Chi-square cells: cos(theta) in (0, 1] x phi about the normal, and one for rejections
    constexpr int kBinsZ = 16, kBinsPhi = 16, kCells = kBinsZ * kBinsPhi + 1;
    auto cellOf = [&](double z, double phi) {
        const int iz = std::clamp(int(z * kBinsZ), 0, kBinsZ - 1);
        const int ip = std::clamp(int(phi * (kBinsPhi / (2.0 * M_PI))), 0, kBinsPhi - 1);
        return iz * kBinsPhi + ip;
    };
    const SsrMethod methods[] = {SsrMethod::GgxNdf, SsrMethod::VndfEllipsoid,
                                 SsrMethod::VndfSphericalCaps, SsrMethod::VndfBounded};
    for (int mi = 0; mi <= 4; ++mi) {
        const bool diffuse = mi == 4;
        const SsrMethod m = diffuse ? SsrMethod::Mirror : methods[mi];
        CAPTURE(diffuse ? std::string("diffuse") : std::string(ssrMethodName(m)));
        auto pdfOf = [&](V3f wo) {
            return diffuse ? sm::cosineHemispherePdf(wo) : methodPdf(m, wi, wo, alpha);
        };
        // Quadrature over the upper hemisphere, equal-area cells in (cos theta, phi):
        // accepted mass, mean direction, mass per chi-square cell
        constexpr int kNz = 2048, kNphi = 1024;
        double mass = 0.0, mean[3] = {0, 0, 0};
        std::vector<double> cellMass(kCells, 0.0);
        const double cell = (1.0 / kNz) * (2.0 * M_PI / kNphi);
        for (int i = 0; i < kNz; ++i) {
            const double z = (i + 0.5) / kNz, s = std::sqrt(1.0 - z * z);
            for (int j = 0; j < kNphi; ++j) {
                const double phi = (j + 0.5) * (2.0 * M_PI / kNphi);
                const V3f wo{float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)};
                const double p = pdfOf(wo) * cell;
                mass += p;
                mean[0] += p * wo.x;
                mean[1] += p * wo.y;
                mean[2] += p * wo.z;
                cellMass[std::size_t(cellOf(z, phi))] += p;
            }
        }
        // The same from the generator: many sample indices of one frame
        constexpr int kSamples = 40000;
        double hits = 0.0, sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
        std::vector<uint64_t> count(kCells, 0);
        // (only this pixel is a surface, so the rest of the frame costs little)
        PlaneF lone = f.frame.gbuffer.viewZ.clone();
        lone.fill(0.0f);
        lone.at(px, py) = f.frame.gbuffer.viewZ.at(px, py);
        GBufferView g = f.g();
        g.viewZ = lone.row(0);  // (a clone: the same size and stride)
        const Isa isa = supportedIsas().back();
        RayBatch rays;
        for (int k = 0; k < kSamples; ++k) {
            if (diffuse) generateDiffuseRays(isa, 7, uint32_t(k), f.camera, g, rays, 1);
            else generateSpecularRays(isa, m, 7, uint32_t(k), f.camera, g, rays, 1);
            if (rays.pdf.at(px, py) <= 0.0f) {
                ++count[kCells - 1];
                continue;
            }
            hits += 1.0;
            const V3f wo = fr.local(dirAt(rays, px, py));
            const double w[3] = {wo.x, wo.y, wo.z};
            for (int c = 0; c < 3; ++c) {
                sum[c] += w[c];
                sum2[c] += w[c] * w[c];
            }
            const double phi = std::atan2(double(wo.y), double(wo.x));
            ++count[std::size_t(cellOf(wo.z, phi < 0.0 ? phi + 2.0 * M_PI : phi))];
        }
        // Acceptance: binomial, 5 sigma
        const double acc = hits / kSamples;
        CHECK(std::abs(acc - mass) < 5.0 * std::sqrt(mass * (1.0 - mass) / kSamples) + 2e-3);
        // Mean direction (over all samples, rejected ones count 0), 5 sigma
        for (int c = 0; c < 3; ++c) {
            const double mu = sum[c] / kSamples;
            const double var = std::max(sum2[c] / kSamples - mu * mu, 1e-8);
            CAPTURE(c);
            CHECK(std::abs(mu - mean[c]) < 5.0 * std::sqrt(var / kSamples) + 2e-3);
        }
        // Pearson's chi-square over the cells (tests/shading/sampling_stats.h); the samples
        // are fixed, so this either always passes or always fails
        std::vector<double> expected(kCells);
        for (int i = 0; i < kCells - 1; ++i)
            expected[std::size_t(i)] = cellMass[std::size_t(i)] * kSamples;
        expected[kCells - 1] = std::max(1.0 - mass, 0.0) * kSamples;
        const test::Chi2Result chi = test::chiSquare(count, expected);
        CAPTURE(chi.chi2);
        CAPTURE(chi.dof);
        CHECK(chi.pValue > 1e-4);
    }
}

}  // namespace

TEST_CASE("ray generation: the lobe of one pixel matches a quadrature of its PDF") {
    SUBCASE("roughness 0.5, view 66 degrees from the normal") {
        checkLobe(renderScene(floorScene(0.5f, 1.0f, 3.0f, 1.0f), 48, 32), 24, 20);
    }
    SUBCASE("roughness 1, view 80 degrees from the normal: up to half the samples rejected") {
        checkLobe(renderScene(floorScene(1.0f, 0.3f, 5.0f, -1.0f), 48, 32), 24, 20);
    }
}

TEST_CASE("ray generation: rays are the samplers' maps of randomFloat(pixel, frame, sample, dim)") {
    // An independent oracle in double (but the sampler itself): the Duff et al. basis around
    // the view-space normal, the uniforms of the documented dimensions, the cosine map for
    // diffuse rays and the reflection about sampleGgxNdf's half vector for GgxNdf.
    const GBufferFrame f = renderBuiltin("spheres", 96, 64);
    const uint32_t frame = 9, sample = 4;
    for (const bool diffuse : {true, false}) {
        CAPTURE(diffuse);
        const SsrMethod m = SsrMethod::GgxNdf;
        RayBatch rays;
        generate(f, diffuse ? nullptr : &m, rays, frame, sample, supportedIsas().back(), 2);
        const uint32_t dim = diffuse ? kRayGenDiffuseDim : kRayGenSpecularDim;
        double worst = 0.0;
        int checked = 0;
        for (int y = 0; y < f.height(); ++y)
            for (int x = 0; x < f.width(); ++x) {
                if (rays.pdf.at(x, y) <= 0.0f) continue;
                const Vec n = viewNormal(f, x, y);
                const double sg = n.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sg + n.z);
                const double c = n.x * n.y * a;
                const Vec t{1.0 + sg * n.x * n.x * a, sg * c, -sg * n.x};
                const Vec b{c, sg + n.y * n.y * a, -n.y};
                const uint32_t pixel = uint32_t(y * f.width() + x);
                const float u1 = randomFloat(pixel, frame, sample, dim);
                const float u2 = randomFloat(pixel, frame, sample, dim + 1);
                Vec w;
                if (diffuse) {
                    const double r = std::sqrt(double(u1)), phi = 2.0 * M_PI * u2;
                    w = {r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - u1)};
                } else {
                    const Vec v = toViewer(f.camera, x, y);
                    const Vec wi{dot(v, t), dot(v, b), dot(v, n)};
                    const float alpha = brdf::roughnessToAlpha(f.frame.gbuffer.roughness.at(x, y));
                    const V3f wmf = sm::sampleGgxNdf(alpha, alpha, u1, u2);
                    const Vec wm = normalized({wmf.x, wmf.y, wmf.z});
                    const double d = 2.0 * dot(wi, wm);
                    w = {d * wm.x - wi.x, d * wm.y - wi.y, d * wm.z - wi.z};
                }
                const Vec e{t.x * w.x + b.x * w.y + n.x * w.z, t.y * w.x + b.y * w.y + n.y * w.z,
                            t.z * w.x + b.z * w.y + n.z * w.z};
                const Vec got = dirAt(rays, x, y);
                worst = std::max(
                    {worst, std::abs(got.x - e.x), std::abs(got.y - e.y), std::abs(got.z - e.z)});
                ++checked;
            }
        CHECK(checked > 1000);
        CHECK(worst < 1e-4);
    }
}

TEST_CASE("ray generation: the same bits for every ISA and thread count") {
    for (const std::string scene : {"cornell", "spheres"}) {
        const GBufferFrame f = renderBuiltin(scene, 203, 137);
        for (int mi = 0; mi <= 5; ++mi) {
            const SsrMethod m = SsrMethod(std::min(mi, 4));
            const SsrMethod* mp = mi == 5 ? nullptr : &m;
            CAPTURE(scene);
            CAPTURE(mi);
            RayBatch ref;
            const RayGenStats refStats = generate(f, mp, ref, 2, 5, Isa::Scalar, 1);
            const uint64_t refHash = batchHash(ref);
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    CAPTURE(isaName(isa));
                    CAPTURE(threads);
                    RayBatch rays;
                    const RayGenStats s = generate(f, mp, rays, 2, 5, isa, threads);
                    CHECK(batchHash(rays) == refHash);
                    CHECK(s.rays == refStats.rays);
                    CHECK(s.belowSurface == refStats.belowSurface);
                    CHECK(s.pixels == refStats.pixels);
                    CHECK(s.background == refStats.background);
                }
        }
    }
}

TEST_CASE("ray generation: frames and samples differ, runs do not") {
    const GBufferFrame f = renderBuiltin("spheres");
    const Isa isa = supportedIsas().back();
    for (int mi = 0; mi <= 5; ++mi) {
        const SsrMethod m = SsrMethod(std::min(mi, 4));
        const SsrMethod* mp = mi == 5 ? nullptr : &m;
        CAPTURE(mi);
        RayBatch a, b, c, d;
        generate(f, mp, a, 1, 0, isa, 2);
        generate(f, mp, b, 1, 0, isa, 2);
        generate(f, mp, c, 2, 0, isa, 2);
        generate(f, mp, d, 1, 1, isa, 2);
        CHECK(batchHash(a) == batchHash(b));
        if (mi == 0) {
            // Mirror draws no random numbers
            CHECK(batchHash(a) == batchHash(c));
            CHECK(batchHash(a) == batchHash(d));
        } else {
            CHECK(batchHash(a) != batchHash(c));
            CHECK(batchHash(a) != batchHash(d));
        }
    }
    // Specular and diffuse draw different numbers (distinct dimensions): their first
    // uniform differs, so the diffuse azimuth is not the specular one
    CHECK(kRayGenSpecularDim + 1 < kRayGenDiffuseDim);
}

TEST_CASE("ray generation: a G-buffer of the wrong size is refused") {
    const GBufferFrame f = renderBuiltin("cornell", 64, 48);
    TraceCamera cam = f.camera;
    cam.width = 65;
    RayBatch rays;
    CHECK_THROWS_AS(generateSpecularRays(Isa::Scalar, SsrMethod::Mirror, 0, 0, cam, f.g(), rays, 1),
                    std::invalid_argument);
    GBufferView g = f.g();
    g.roughness = nullptr;
    CHECK_THROWS_AS(
        generateSpecularRays(Isa::Scalar, SsrMethod::GgxNdf, 0, 0, f.camera, g, rays, 1),
        std::invalid_argument);
    // (diffuse rays need no roughness)
    CHECK_NOTHROW(generateDiffuseRays(Isa::Scalar, 0, 0, f.camera, g, rays, 1));
    // A plane of another size never makes a view.
    const PlaneF wide(65, 48, 0.5f);
    CHECK_THROWS_AS(
        gbufferView("test", 64, 48, {{kGViewZ, &f.frame.gbuffer.viewZ}, {kGRoughness, &wide}}),
        std::invalid_argument);
}
