// Tangent frames (scenes/tangents.h): generated tangents on plain and mirrored UV layouts
// agree with the TANGENT attribute a file would carry, and a normal-map texel bends the
// normal the way glTF's convention says (+X along +u, +Y up the image, that is along -v).
#include "scenes/tangents.h"

#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

using namespace ssrt;

namespace {

// A unit quad in the xy plane facing +z, u along +x and v down the image (along -y), as
// glTF lays out an upright texture; `mirrorU` runs u the other way.
Mesh quad(bool mirrorU = false) {
    Mesh m;
    m.positions = {{0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    m.normals.assign(4, {0, 0, 1});
    for (const glm::vec3& p : m.positions)
        m.uvs.emplace_back(mirrorU ? 1.0f - p.x : p.x, 1.0f - p.y);
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

void closeTo(glm::vec3 a, glm::vec3 b) {
    for (int c = 0; c < 3; ++c) CHECK(a[c] == doctest::Approx(b[c]).epsilon(1e-6));
}

}  // namespace

TEST_CASE("tangents: a plain UV quad gets the tangent (1, 0, 0, +1), as its TANGENT would say") {
    const std::vector<glm::vec4> t = generateTangents(quad(), 0);
    REQUIRE(t.size() == 4);
    for (const glm::vec4& v : t) CHECK(v == glm::vec4(1, 0, 0, 1));
    // Mirrored in u: the tangent turns round and so does the handedness, which keeps the
    // bitangent w cross(n, t) pointing up the image (+y).
    for (const glm::vec4& v : generateTangents(quad(true), 0)) {
        CHECK(v == glm::vec4(-1, 0, 0, -1));
        closeTo(glm::cross(glm::vec3(0, 0, 1), glm::vec3(v)) * v.w, {0, 1, 0});
    }
}

TEST_CASE("tangents: the mesh's own are used when present -- without UVs any perpendicular") {
    Mesh m = quad();
    m.tangents.assign(4, glm::vec4(0, 1, 0, -1));
    CHECK(meshTangents(m, 0) == m.tangents);
    m.tangents.clear();
    CHECK(meshTangents(m, 0) == generateTangents(m, 0));
    m.uvs.clear();
    for (const glm::vec4& v : generateTangents(m, 0)) {
        CHECK(glm::dot(glm::vec3(v), glm::vec3(0, 0, 1)) == doctest::Approx(0.0));
        CHECK(glm::length(glm::vec3(v)) == doctest::Approx(1.0));
        CHECK(v.w == 1.0f);
    }
    // The second set is read when asked for: u1 = v, v1 = u swaps the axes.
    m = quad();
    for (const glm::vec2& uv : m.uvs) m.uvs1.emplace_back(uv.y, uv.x);
    for (const glm::vec4& v : generateTangents(m, 1)) {
        closeTo(glm::vec3(v), {0, -1, 0});
        // The bitangent is -dP/dv1 = -x, and cross(n, t) = +x: w = -1.
        CHECK(v.w == -1.0f);
        closeTo(glm::cross(glm::vec3(0, 0, 1), glm::vec3(v)) * v.w, {-1, 0, 0});
    }
}

TEST_CASE("tangents: a normal-map texel bends the normal along the tangent frame") {
    const glm::vec3 n(0, 0, 1);
    const glm::vec4 t(1, 0, 0, 1);
    // The flat texel (0.5, 0.5, 1) leaves the normal as it is, exactly.
    CHECK(perturbNormal(n, t, {0.5f, 0.5f, 1.0f}, 1.0f) == n);
    // +X leans along the tangent, +Y along the bitangent cross(n, t) w = +y.
    closeTo(perturbNormal(n, t, {1.0f, 0.5f, 0.5f}, 1.0f), {1, 0, 0});
    closeTo(perturbNormal(n, t, {0.5f, 1.0f, 1.0f}, 1.0f), glm::normalize(glm::vec3(0, 1, 1)));
    closeTo(perturbNormal(n, glm::vec4(1, 0, 0, -1), {0.5f, 1.0f, 1.0f}, 1.0f),
            glm::normalize(glm::vec3(0, -1, 1)));
    // scale multiplies X and Y before the normalisation (glTF 2.0 section 3.9.3).
    closeTo(perturbNormal(n, t, {1.0f, 0.5f, 1.0f}, 0.5f), glm::normalize(glm::vec3(0.5f, 0, 1)));
    // The tangent need not be unit nor orthogonal: Gram-Schmidt against n.
    closeTo(perturbNormal(n, glm::vec4(3, 0, 2, 1), {1.0f, 0.5f, 1.0f}, 1.0f),
            glm::normalize(glm::vec3(1, 0, 1)));
    // No frame (a tangent along n): the normal unchanged.
    CHECK(perturbNormal(n, glm::vec4(0, 0, 1, 1), {1.0f, 0.5f, 0.5f}, 1.0f) == n);
}

TEST_CASE("tangents: through a transform, w turns over when the transform mirrors") {
    const glm::vec4 t(1, 0, 0, 1);
    closeTo(glm::vec3(worldTangent(glm::scale(glm::mat4(1.0f), {3, 1, 1}), t)), {1, 0, 0});
    CHECK(worldTangent(glm::scale(glm::mat4(1.0f), {3, 1, 1}), t).w == 1.0f);
    const glm::vec4 m = worldTangent(glm::scale(glm::mat4(1.0f), {1, 1, -1}), t);
    CHECK(m.w == -1.0f);
    closeTo(glm::vec3(worldTangent(glm::rotate(glm::mat4(1.0f), 1.5707964f, {0, 0, 1}), t)),
            {0, 1, 0});
}
