// The G-buffer against analytic answers: exact view Z of a plane, sphere normals, motion
// vectors of a known camera move and of a moving instance; and the shadow map's footprint.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "renderer/renderer.h"
#include "scenes/mesh_builders.h"

using namespace ssrt;

namespace {

// A rectangle at z = zWorld facing +z, built directly (no rotation: coordinates stay exact).
Mesh wall(float halfSize, float zWorld) {
    Mesh m;
    m.positions = {{-halfSize, -halfSize, zWorld},
                   {halfSize, -halfSize, zWorld},
                   {halfSize, halfSize, zWorld},
                   {-halfSize, halfSize, zWorld}};
    m.normals.assign(4, {0.0f, 0.0f, 1.0f});
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

Scene oneMeshScene(Mesh mesh, glm::mat4 transform = glm::mat4(1.0f)) {
    Scene s;
    s.meshes.push_back(std::move(mesh));
    s.materials.push_back(Material{});
    Instance inst;
    inst.transform = inst.previousTransform = transform;
    s.instances.push_back(inst);
    s.camera.position = {0.0f, 0.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    s.camera.fovY = 60.0f;
    s.previousCamera = s.camera;
    return s;
}

RenderSettings small(int w = 128, int h = 96) {
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.shadowMapSize = 256;
    return rs;
}

// World-space direction of the ray through the centre of pixel (x, y), in double.
glm::dvec3 pixelRay(const Camera& cam, int w, int h, int x, int y) {
    const double tanY = std::tan(glm::radians(double(cam.fovY)) * 0.5);
    const double ndcX = (x + 0.5) * 2.0 / w - 1.0, ndcY = 1.0 - (y + 0.5) * 2.0 / h;
    const glm::dvec3 f = glm::normalize(glm::dvec3(cam.target - cam.position));
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(cam.up)));
    const glm::dvec3 u = glm::cross(r, f);
    return r * (ndcX * tanY * w / h) + u * (ndcY * tanY) + f;  // view z component = 1
}

}  // namespace

TEST_CASE("a plane at known depth gives exact view Z") {
    for (glm::vec3 eye : {glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 3.0f)}) {
        Scene s = oneMeshScene(wall(100.0f, eye.z - 4.0f));
        s.camera.position = eye;
        s.camera.target = eye + glm::vec3(0.0f, 0.0f, -1.0f);
        s.previousCamera = s.camera;
        const Frame f = Renderer(small()).renderWithoutHistory(s);
        const PlaneF& z = f.gbuffer.viewZ;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) REQUIRE(z.at(x, y) == 4.0f);
        CHECK(f.gbuffer.normal[2].at(7, 9) == 1.0f);
        CHECK(f.gbuffer.instanceId.at(7, 9) == 0.0f);
    }
}

TEST_CASE("sphere normals match the analytic normal") {
    const glm::dvec3 centre(0.0, 0.0, -4.0);
    const Scene s = oneMeshScene(makeUvSphere(1.0f, 512, 256),
                                 glm::translate(glm::mat4(1.0f), glm::vec3(centre)));
    const Frame f = Renderer(small(160, 160)).renderWithoutHistory(s);
    double worstDeg = 0.0;
    int checked = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            if (f.gbuffer.viewZ.at(x, y) <= 0.0f) continue;
            // Ray-sphere in double from the camera at the origin.
            const glm::dvec3 d = glm::normalize(pixelRay(s.camera, f.width, f.height, x, y));
            const double b = glm::dot(d, centre), c = glm::dot(centre, centre) - 1.0;
            const double disc = b * b - c;
            if (disc <= 0.0) continue;
            const glm::dvec3 n = glm::normalize(d * (b - std::sqrt(disc)) - centre);
            if (glm::dot(n, -d) < 0.2) continue;  // the tessellated silhouette differs
            const glm::dvec3 got(f.gbuffer.normal[0].at(x, y), f.gbuffer.normal[1].at(x, y),
                                 f.gbuffer.normal[2].at(x, y));
            const double cosA = std::min(1.0, glm::dot(got, n) / glm::length(got));
            worstDeg = std::max(worstDeg, glm::degrees(std::acos(cosA)));
            ++checked;
        }
    MESSAGE("sphere normals: worst error " << worstDeg << " degrees over " << checked << " pixels");
    CHECK(checked > 3000);
    CHECK(worstDeg < 0.05);
}

TEST_CASE("motion vectors of a known camera move and of a moving instance") {
    SUBCASE("camera translation over a wall") {
        Scene s = oneMeshScene(wall(100.0f, -4.0f));
        s.previousCamera.position = {0.3f, -0.2f, 0.5f};
        s.previousCamera.target = s.previousCamera.position + glm::vec3(0.0f, 0.0f, -1.0f);
        const Frame f = Renderer(small()).renderWithoutHistory(s);
        const glm::dmat4 prevVp =
            glm::dmat4(s.previousCamera.projection(float(f.width) / f.height)) *
            glm::dmat4(s.previousCamera.view());
        double worst = 0.0;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const glm::dvec3 p = pixelRay(s.camera, f.width, f.height, x, y) * 4.0;
                const glm::dvec4 c = prevVp * glm::dvec4(p, 1.0);
                const double px = (c.x / c.w * 0.5 + 0.5) * f.width;
                const double py = (0.5 - c.y / c.w * 0.5) * f.height;
                worst = std::max(
                    {worst, std::fabs(px - (x + 0.5) - double(f.gbuffer.motion[0].at(x, y))),
                     std::fabs(py - (y + 0.5) - double(f.gbuffer.motion[1].at(x, y)))});
            }
        MESSAGE("camera motion: worst error " << worst << " px");
        CHECK(worst < 1e-3);
        // Sanity: the expected motion is large, so the bound above means something.
        CHECK(std::fabs(f.gbuffer.motion[0].at(64, 48)) > 2.0f);
    }
    SUBCASE("instance translation under a still camera") {
        Scene s = oneMeshScene(wall(1.0f, -4.0f));
        s.instances[0].previousTransform = glm::translate(glm::mat4(1.0f), {0.5f, 0.0f, 0.0f});
        const Frame f = Renderer(small()).renderWithoutHistory(s);
        // 0.5 world units at depth 4: 0.5 / (4 tan(30 deg) aspect) of half the width.
        const double expected = 0.5 / (4.0 * std::tan(glm::radians(30.0)) * (128.0 / 96.0)) * 64.0;
        CHECK(f.gbuffer.motion[0].at(64, 48) == doctest::Approx(expected).epsilon(1e-4));
        CHECK(f.gbuffer.motion[1].at(64, 48) == doctest::Approx(0.0).epsilon(1e-4));
        CHECK(f.gbuffer.motion[0].at(2, 2) == 0.0f);  // background
    }
}

TEST_CASE("a known occluder shadows exactly its footprint, up to the PCF border") {
    Scene s;
    s.meshes.push_back(makeQuad({10.0f, 10.0f}, 1));  // ground, y = 0, facing +y
    s.meshes.push_back(makeQuad({1.0f, 1.0f}, 1));    // occluder, 1 above
    Material m;
    m.doubleSided = true;
    s.materials.push_back(m);
    Instance ground, occluder;
    ground.mesh = 0;
    occluder.mesh = 1;
    occluder.transform = occluder.previousTransform =
        glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f});
    s.instances = {ground, occluder};
    s.light.direction = {0.0f, -1.0f, 0.0f};
    s.camera.position = {0.0f, 6.0f, 5.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.previousCamera = s.camera;
    RenderSettings rs = small(200, 160);
    rs.shadowMapSize = 512;
    const Frame f = Renderer(rs).renderWithoutHistory(s);
    // World units per texel: the map spans the scene's bounds (20 units plus a margin).
    const double border = (rs.pcfRadius + 1.5) * 20.5 / rs.shadowMapSize;
    int inside = 0, outside = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            if (f.gbuffer.instanceId.at(x, y) != 0.0f) continue;
            const glm::dvec3 p =
                glm::dvec3(s.camera.position) +
                pixelRay(s.camera, f.width, f.height, x, y) * double(f.gbuffer.viewZ.at(x, y));
            const double edge = std::max(std::fabs(p.x), std::fabs(p.z));
            const float v = f.plane(Res::Shadow).at(x, y);
            CAPTURE(x);
            CAPTURE(y);
            if (edge < 1.0 - border) {
                REQUIRE(v == 0.0f);
                ++inside;
            } else if (edge > 1.0 + border) {
                REQUIRE(v == 1.0f);
                ++outside;
            }
        }
    CHECK(inside > 500);
    CHECK(outside > 5000);
    // The occluder's own top is lit: the bias keeps it free of acne.
    int lit = 0, top = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            if (f.gbuffer.instanceId.at(x, y) == 1.0f) {
                ++top;
                lit += f.plane(Res::Shadow).at(x, y) == 1.0f;
            }
    CHECK(top > 100);
    CHECK(lit == top);
}
