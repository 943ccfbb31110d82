// The proof of a screen hit (trace/hit_proof.h) on a frame made by hand: a wall filling the
// view at depth 5 (two triangles) and a small card in front of it at depth 2, which hides part
// of the wall. Each test breaks one condition of the proof and sees the hit refused.
#include "trace/hit_proof.h"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/ray_triangle.h"
#include "raster/raster.h"

using namespace ssrt;

namespace {

constexpr int kSize = 64;

struct HandFrame {
    TraceCamera camera;
    std::vector<glm::vec3> positions = {
        {-20, -20, -5},
        {20, -20, -5},
        {20, 20, -5},
        {-20, 20, -5},  // the wall, facing +z
        {0.5f, 0.5f, -2},
        {1.5f, 0.5f, -2},
        {0.5f, 1.5f, -2},  // the card, facing +z
        // a pole 0.2 wide at depth 4 (1.6 pixels), drawn only when asked for
        {-2.1f, -2, -4},
        {-1.9f, -2, -4},
        {-1.9f, 2, -4},
        {-2.1f, 2, -4},
    };
    std::vector<ResolveTriangle> triangles;
    std::vector<uint8_t> cutOut = {0, 0, 0};  // by instance: the wall 0, the card 1, the pole 2
    PlaneU32 ids;
    PlaneF viewZ;

    explicit HandFrame(bool pole = false) {
        camera.width = camera.height = kSize;
        camera.tanHalfX = camera.tanHalfY = 1.0f;
        const auto tri = [&](uint32_t instance, uint32_t a, uint32_t b, uint32_t c) {
            ResolveTriangle t{};
            t.instance = instance;
            t.v[0] = a, t.v[1] = b, t.v[2] = c;
            triangles.push_back(t);
        };
        tri(0, 0, 1, 2);
        tri(0, 0, 2, 3);
        tri(1, 4, 5, 6);
        if (pole) tri(2, 7, 8, 9), tri(2, 7, 9, 10);
        // Rasterize by rays from the camera through the pixel centres: the nearest triangle.
        ids.ensureSize(kSize, kSize);
        viewZ.ensureSize(kSize, kSize);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const glm::vec3 d = pixelRay(float(x) + 0.5f, float(y) + 0.5f);
                float best = INFINITY;
                uint32_t id = kNoPrimitive;
                for (uint32_t i = 0; i < triangles.size(); ++i) {
                    const TriangleHit h = intersectTriangle({0, 0, 0}, d, corner(i, 0),
                                                            corner(i, 1), corner(i, 2), 0, best);
                    if (h.hit) best = h.t, id = i;
                }
                ids.at(x, y) = id;
                viewZ.at(x, y) = id == kNoPrimitive ? 0.0f : -(best * d.z);
            }
    }
    glm::vec3 corner(uint32_t tri, int c) const { return positions[triangles[tri].v[c]]; }
    // The view ray through a continuous pixel position (not unit).
    glm::vec3 pixelRay(float x, float y) const {
        return {(x * 2.0f / kSize - 1.0f) * camera.tanHalfX,
                (1.0f - y * 2.0f / kSize) * camera.tanHalfY, -1.0f};
    }
    // Where a view-space point lies on screen.
    glm::vec2 project(glm::vec3 p) const {
        const float z = -p.z;
        return {(p.x / z / camera.tanHalfX + 1.0f) * 0.5f * kSize,
                (1.0f - p.y / z / camera.tanHalfY) * 0.5f * kSize};
    }
    const ThinFeatures* thin = nullptr;  // the thin-feature check's pixels, when given
    ProofInputs inputs() const {
        return proofInputs(camera, viewOf(ids, "visibility.ids"), viewOf(viewZ, "viewZ"),
                           {triangles, positions, cutOut}, {}, thin);
    }
    // A ray from `from` to `to`, the march having hit where `marchAt` projects (the true hit
    // unless a test says otherwise).
    ProvenRay prove(glm::vec3 from, glm::vec3 to, glm::vec3 marchAt, bool marchHit = true) const {
        const glm::vec2 o = project(from), m = project(marchAt);
        return proveRay(inputs(), from, glm::normalize(to - from), o.x, o.y, marchHit, m.x, m.y);
    }
};

}  // namespace

TEST_CASE("hit proof: a ray that meets the visible triangle is a certain hit at its exact t") {
    const HandFrame f;
    const glm::vec3 from{-1.0f, -0.5f, -3.0f}, to{-3.0f, 0.5f, -5.0f};
    const ProvenRay r = f.prove(from, to, to);
    CHECK(r.proof == RayProof::CertainHit);
    CHECK(r.t == doctest::Approx(glm::length(to - from)).epsilon(1e-5));
    // The march's hit pixel only names the triangle: a neighbouring pixel of the same
    // triangle proves the same hit, at the same exact distance.
    const ProvenRay beside = f.prove(from, to, to + glm::vec3(0.1f, 0.0f, 0.0f));
    CHECK(beside.proof == RayProof::CertainHit);
    CHECK(beside.t == r.t);
}

TEST_CASE("hit proof: refused when the triangle at the march's hit is another") {
    const HandFrame f;
    // The march claims the card (its pixel shows the card), the ray passes beside it to the
    // wall: the card's triangle is not met.
    const glm::vec3 from{-1.0f, -0.5f, -3.0f}, to{-3.0f, 0.5f, -5.0f};
    const glm::vec3 card{0.7f, 0.7f, -2.0f};
    REQUIRE(f.ids.at(int(f.project(card).x), int(f.project(card).y)) == 2u);
    CHECK(f.prove(from, to, card).proof == RayProof::Uncertain);
}

TEST_CASE("hit proof: refused where the point met is hidden, or met from behind") {
    const HandFrame f;
    SUBCASE("hidden: the wall's point lies behind the card on screen") {
        // The march names a wall pixel beside the card; the ray meets the same wall triangle
        // at a point the card hides from the camera.
        const glm::vec3 hidden = glm::vec3(0.9f, 0.7f, -2.0f) * 2.5f;  // on the wall, z = -5
        const glm::vec3 marchAt{1.0f, 0.75f, -5.0f};
        const glm::vec2 s = f.project(hidden), m = f.project(marchAt);
        REQUIRE(f.ids.at(int(s.x), int(s.y)) == 2u);
        REQUIRE(f.ids.at(int(m.x), int(m.y)) == 0u);
        const glm::vec3 from{-3.0f, -2.0f, -4.0f};
        CHECK(f.prove(from, hidden, marchAt).proof == RayProof::Uncertain);
        // The same ray to a visible point of that triangle is proven.
        CHECK(f.prove(from, marchAt, marchAt).proof == RayProof::CertainHit);
    }
    SUBCASE("from behind: a ray from beyond the wall meets its back") {
        const glm::vec3 from{1.0f, 1.0f, -7.0f}, to{-3.0f, 0.5f, -5.0f};
        CHECK(f.prove(from, to, to).proof == RayProof::Uncertain);
    }
}

TEST_CASE("hit proof: refused next to its own pixel, through a cut-out, and without a hit") {
    HandFrame f;
    const glm::vec3 from{-1.0f, -0.5f, -3.0f}, to{-3.0f, 0.5f, -5.0f};
    SUBCASE("within 2 pixels of the ray's own pixel") {
        const glm::vec3 near = from * (5.0f / 3.0f);  // on the wall behind it: 0 px apart
        REQUIRE(f.ids.at(int(f.project(near).x), int(f.project(near).y)) == 1u);
        CHECK(f.prove(from, near, near).proof == RayProof::Uncertain);
    }
    SUBCASE("the wall's material cuts holes") {
        f.cutOut[0] = 1;
        CHECK(f.prove(from, to, to).proof == RayProof::Uncertain);
    }
    SUBCASE("the march missed, or hit off the frame") {
        CHECK(f.prove(from, to, to, false).proof == RayProof::Uncertain);
        const glm::vec2 o = f.project(from);
        CHECK(proveRay(f.inputs(), from, glm::normalize(to - from), o.x, o.y, true, -1.0f, 3.0f)
                  .proof == RayProof::Uncertain);
    }
    SUBCASE("the depth of the pixel is not the point's") {
        const glm::vec2 s = f.project(to);
        f.viewZ.at(int(s.x), int(s.y)) = 5.2f;  // 4 % off: another surface's depth
        CHECK(f.prove(from, to, to).proof == RayProof::Uncertain);
    }
}

TEST_CASE("hit proof: its views are checked where its inputs are made") {
    const HandFrame f;
    PlaneF small(kSize / 2, kSize);
    CHECK_THROWS_WITH_AS(proofInputs(f.camera, viewOf(f.ids, "visibility.ids"),
                                     viewOf(small, "viewZ"), {f.triangles, f.positions, f.cutOut}),
                         doctest::Contains("viewZ"), std::invalid_argument);
    CHECK_THROWS_AS(proofInputs(f.camera, viewOf(PlaneU32(), "visibility.ids"),
                                viewOf(f.viewZ, "viewZ"), {f.triangles, f.positions, f.cutOut}),
                    std::invalid_argument);
}

TEST_CASE("hit proof: refused where the ray crosses a thin surface the screen shows on its way") {
    // The march stepped over the pole (it is thinner than its steps) and hit the wall behind:
    // the pole is drawn in a column of pixels beside the ray's path, and the ray meets it.
    const glm::vec3 from{-1.0f, -0.5f, -3.0f}, to{-3.0f, 0.5f, -5.0f};
    HandFrame f(true);
    const glm::vec3 crossing = from + 0.5f * (to - from);  // (-2, 0, -4): on the pole
    REQUIRE(f.ids.at(int(f.project(crossing).x) - 1, int(f.project(crossing).y)) >= 4u);
    REQUIRE(f.ids.at(int(f.project(to).x), int(f.project(to).y)) <= 1u);  // the hit is shown
    CHECK(f.prove(from, to, to).proof == RayProof::Uncertain);
    // Looking only at the thin features, through their cells (8 and 64 pixels), finds it too:
    // the pole's pixels are in front of the wall beside them, the wall's inside are not.
    ThinFeatures thin;
    findThinFeatures(viewOf(f.viewZ, "viewZ"), thin, 1);
    const int poleX = int(f.project(crossing).x) - 1, poleY = int(f.project(crossing).y);
    CHECK(thin.levels[0].at(poleX, poleY) == f.viewZ.at(poleX, poleY));
    CHECK(thin.levels[0].at(poleX - 3, poleY) == INFINITY);
    CHECK(thin.levels[1].at(poleX / 8, poleY / 8) == f.viewZ.at(poleX, poleY));
    f.thin = &thin;
    CHECK(f.prove(from, to, to).proof == RayProof::Uncertain);
    // A ray that passes in front of the pole (nearer the camera than it) is proven.
    const glm::vec3 nearFrom{-1.0f, -0.5f, -2.0f}, nearTo = glm::vec3(-2.6f, 0.3f, -3.2f) * 1.5625f;
    REQUIRE(f.ids.at(int(f.project(nearTo).x), int(f.project(nearTo).y)) <= 1u);
    CHECK(f.prove(nearFrom, nearTo, nearTo).proof == RayProof::CertainHit);
    // Without the pole the crossing ray is proven.
    CHECK(HandFrame().prove(from, to, to).proof == RayProof::CertainHit);
}
