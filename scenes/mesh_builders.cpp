#include "scenes/mesh_builders.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/lane_math.h"

namespace ssrt {
namespace {

constexpr float kTwoPi = 2.0f * lanes::kPi;

// The project's own sincos, not libm's: the meshes (and so every golden image) come out
// bit-identical on every machine, whatever its C library.
glm::vec2 cosSin(float angle) {
    float s = 0.0f, c = 0.0f;
    lanes::sincos(angle, s, c);
    return {c, s};
}

// Angle of step i of n around a full turn; step n reuses step 0's angle so that the seam
// vertices (duplicated for their UVs) sit exactly on the first ones: no cracks.
float turnAngle(int i, int n) { return kTwoPi * float(i % n) / float(n); }

void requireAtLeast(const char* what, int value, int least) {
    if (value < least)
        throw std::invalid_argument(std::string(what) + " must be at least " +
                                    std::to_string(least) + " (got " + std::to_string(value) + ")");
}

void requirePositive(const char* what, float value) {
    if (!(value > 0.0f))  // also rejects NaN
        throw std::invalid_argument(std::string(what) + " must be positive (got " +
                                    std::to_string(value) + ")");
}

void addVertex(Mesh& mesh, glm::vec3 position, glm::vec3 normal, glm::vec2 uv) {
    mesh.positions.push_back(position);
    mesh.normals.push_back(normal);
    mesh.uvs.push_back(uv);
}

void addTriangle(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// Two triangles per cell of a grid of (columns + 1) vertices per row, row-major. The
// front face is cross(step to the next column, step to the next row); every builder below
// lays its grid out so that this points outward.
void addGridTriangles(Mesh& mesh, uint32_t first, int rows, int columns, bool skipFirstRow,
                      bool skipLastRow) {
    const uint32_t stride = uint32_t(columns) + 1;
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            const uint32_t a = first + uint32_t(r) * stride + uint32_t(c);
            const uint32_t b = a + stride;  // next row
            const uint32_t d = a + 1;       // next column
            const uint32_t e = b + 1;
            // At a sphere's pole one edge of the cell has zero length: keep one triangle.
            if (!(skipFirstRow && r == 0)) addTriangle(mesh, a, d, b);
            if (!(skipLastRow && r == rows - 1)) addTriangle(mesh, d, e, b);
        }
    }
}

}  // namespace

Mesh makeBox(glm::vec3 halfExtents) {
    requirePositive("box half extent x", halfExtents.x);
    requirePositive("box half extent y", halfExtents.y);
    requirePositive("box half extent z", halfExtents.z);
    Mesh mesh;
    mesh.name = "box";
    // Each face: normal n and a tangent pair (u, v) with cross(u, v) = n, so the corners
    // -u-v, +u-v, +u+v, -u+v run counter-clockwise seen from outside.
    const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            const glm::vec3 n = sign * axes[axis];
            const glm::vec3 u = axes[(axis + 1) % 3];
            const glm::vec3 v = sign * axes[(axis + 2) % 3];
            const uint32_t first = uint32_t(mesh.positions.size());
            const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (glm::vec2 k : corners) {
                const glm::vec3 p = (n + k.x * u + k.y * v) * halfExtents;
                addVertex(mesh, p, n, 0.5f * (k + 1.0f));
            }
            addTriangle(mesh, first, first + 1, first + 2);
            addTriangle(mesh, first, first + 2, first + 3);
        }
    }
    return mesh;
}

Mesh makeQuad(glm::vec2 halfSize, int subdivisions) {
    requirePositive("quad half size x", halfSize.x);
    requirePositive("quad half size y", halfSize.y);
    requireAtLeast("quad subdivisions", subdivisions, 1);
    Mesh mesh;
    mesh.name = "quad";
    const int n = subdivisions;
    // Rows run along +X, columns along +Z: cross(+Z, +X) = +Y, the front.
    for (int r = 0; r <= n; ++r) {
        for (int c = 0; c <= n; ++c) {
            const glm::vec2 t(float(r) / float(n), float(c) / float(n));
            const glm::vec3 p(halfSize.x * (2.0f * t.x - 1.0f), 0.0f,
                              halfSize.y * (2.0f * t.y - 1.0f));
            addVertex(mesh, p, {0, 1, 0}, t);
        }
    }
    addGridTriangles(mesh, 0, n, n, false, false);
    return mesh;
}

Mesh makeUvSphere(float radius, int segments, int rings) {
    requirePositive("sphere radius", radius);
    requireAtLeast("sphere segments", segments, 3);
    requireAtLeast("sphere rings", rings, 2);
    Mesh mesh;
    mesh.name = "uv_sphere";
    // Rows run from the north pole (+Y) down, columns by azimuth phi (x = cos phi,
    // z = sin phi): cross(column step, row step) points outward, see addGridTriangles.
    for (int r = 0; r <= rings; ++r) {
        // Exact poles: sin(pi) in float is not 0, and the poles must close the sphere.
        glm::vec2 theta = cosSin(lanes::kPi * float(r) / float(rings));
        if (r == 0) theta = {1.0f, 0.0f};
        if (r == rings) theta = {-1.0f, 0.0f};
        for (int c = 0; c <= segments; ++c) {
            const glm::vec2 phi = cosSin(turnAngle(c, segments));
            const glm::vec3 n =
                glm::normalize(glm::vec3(theta.y * phi.x, theta.x, theta.y * phi.y));
            const glm::vec2 uv(float(c) / float(segments), float(r) / float(rings));
            addVertex(mesh, radius * n, n, uv);
        }
    }
    addGridTriangles(mesh, 0, rings, segments, true, true);
    return mesh;
}

namespace {

// Point on the (p, q) torus knot at parameter t in [0, 2 pi): p turns about Y while the
// curve circles the torus core q times, at distance radius / 2 from the core.
glm::vec3 knotPoint(int p, int q, float radius, float t) {
    const glm::vec2 around = cosSin(float(p) * t);
    const glm::vec2 through = cosSin(float(q) * t);
    const float r = radius * (1.0f + 0.5f * through.x);
    return {r * around.x, 0.5f * radius * through.y, r * around.y};
}

// Analytic derivative of knotPoint with respect to t.
glm::vec3 knotTangent(int p, int q, float radius, float t) {
    const glm::vec2 around = cosSin(float(p) * t);
    const glm::vec2 through = cosSin(float(q) * t);
    const float r = radius * (1.0f + 0.5f * through.x);
    const float dr = -0.5f * radius * float(q) * through.y;
    return {dr * around.x - r * float(p) * around.y, 0.5f * radius * float(q) * through.x,
            dr * around.y + r * float(p) * around.x};
}

}  // namespace

Mesh makeTorusKnot(int p, int q, float radius, float tube, int segments, int sides) {
    requireAtLeast("torus knot p", p, 1);
    requireAtLeast("torus knot q", q, 1);
    requirePositive("torus knot radius", radius);
    requirePositive("torus knot tube", tube);
    requireAtLeast("torus knot segments", segments, 3);
    requireAtLeast("torus knot sides", sides, 3);
    Mesh mesh;
    mesh.name = "torus_knot";
    for (int s = 0; s <= segments; ++s) {
        const float t = turnAngle(s, segments);
        const glm::vec3 centre = knotPoint(p, q, radius, t);
        const glm::vec3 tangent = glm::normalize(knotTangent(p, q, radius, t));
        // Frame from the tangent and the direction to the curve point; never parallel (the
        // tangent always turns about Y, the point has no such component), and a function
        // of t alone, so the tube closes on itself without a twist seam.
        const glm::vec3 binormal = glm::normalize(glm::cross(tangent, centre));
        const glm::vec3 normal = glm::cross(binormal, tangent);
        // Rows run along the curve (tangent), columns around the tube (toward binormal at
        // angle 0): cross(binormal, tangent) = normal, outward.
        for (int k = 0; k <= sides; ++k) {
            const glm::vec2 a = cosSin(turnAngle(k, sides));
            const glm::vec3 n = glm::normalize(a.x * normal + a.y * binormal);
            const glm::vec2 uv(float(s) / float(segments), float(k) / float(sides));
            addVertex(mesh, centre + tube * n, n, uv);
        }
    }
    addGridTriangles(mesh, 0, segments, sides, false, false);
    return mesh;
}

// The cross product's length is twice the triangle's area: summing them unnormalized weights
// each face by its area.
std::vector<glm::vec3> smoothNormals(const Mesh& mesh) {
    std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a],
                                       mesh.positions[c] - mesh.positions[a]);
        sum[a] += n;
        sum[b] += n;
        sum[c] += n;
    }
    for (glm::vec3& n : sum) {
        const float len = glm::length(n);
        // Unreferenced or degenerate-only vertices still need a unit normal.
        n = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return sum;
}

}  // namespace ssrt
