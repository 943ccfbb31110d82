// trace/hit_stats.h: the SIMD hit statistics against the scalar loops they replaced (the
// renderer's accumulateHits / finishHits), bit for bit, on every ISA and thread count.
#include "trace/hit_stats.h"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/rng.h"
#include "plane_compare.h"
#include "thread_counts.h"

using namespace ssrt;
using test::sameBits;

namespace {

// The scalar oracle: the renderer's loops before the kernel, one sample at a time.
void oracle(const TraceCamera& cam, const RayBatch& rays, const MarchResult& m, PlaneF& hitP,
            PlaneF& stepsP, PlaneF* distP, bool first, bool last, int spp) {
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const float hit = m.hit.at(x, y);
            float d = 0.0f;
            if (distP && hit > 0.0f) {
                const float z = m.hitZ.at(x, y);
                const float px =
                    (2.0f * m.hitX.at(x, y) / float(cam.width) - 1.0f) * cam.tanHalfX * z;
                const float py =
                    (1.0f - 2.0f * m.hitY.at(x, y) / float(cam.height)) * cam.tanHalfY * z;
                const float dx = px - rays.ox.at(x, y), dy = py - rays.oy.at(x, y),
                            dz = -z - rays.oz.at(x, y);
                d = std::sqrt(dx * dx + dy * dy + dz * dz);
            }
            const float steps = m.steps.at(x, y);
            if (first) {
                hitP.at(x, y) = hit;
                stepsP.at(x, y) = steps;
                if (distP) distP->at(x, y) = d;
            } else {
                hitP.at(x, y) += hit;
                stepsP.at(x, y) += steps;
                if (distP) distP->at(x, y) += d;
            }
        }
    if (!last) return;
    const float inv = 1.0f / float(spp);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const float hits = hitP.at(x, y);
            if (distP) distP->at(x, y) = hits > 0.0f ? distP->at(x, y) / hits : 0.0f;
            hitP.at(x, y) = hits * inv;
            stepsP.at(x, y) *= inv;
        }
}

void randomSample(const TraceCamera& cam, uint32_t s, RayBatch& rays, MarchResult& m) {
    rays.ensureSize(cam.width, cam.height);
    m.ensureSize(cam.width, cam.height);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const uint32_t i = uint32_t(y * cam.width + x);
            auto u = [&](uint32_t d) { return randomFloat(i, 90 + s, 0, d); };
            const bool hit = u(0) < 0.6f;
            m.hit.at(x, y) = hit ? 1.0f : 0.0f;
            m.steps.at(x, y) = std::floor(100.0f * u(1));
            m.hitX.at(x, y) = hit ? float(cam.width) * u(2) : 0.0f;
            m.hitY.at(x, y) = hit ? float(cam.height) * u(3) : 0.0f;
            m.hitZ.at(x, y) = hit ? 0.5f + 20.0f * u(4) : 0.0f;
            rays.ox.at(x, y) = u(5) - 0.5f;
            rays.oy.at(x, y) = u(6) - 0.5f;
            rays.oz.at(x, y) = -1.0f - 5.0f * u(7);
        }
}

}  // namespace

TEST_CASE("hit statistics: the scalar loops' bits on every ISA and thread count") {
    TraceCamera cam;
    cam.width = 133;  // not a multiple of any lane width
    cam.height = 71;
    cam.tanHalfY = 0.45f;
    cam.tanHalfX = 0.45f * float(cam.width) / float(cam.height);
    for (int spp : {1, 3})
        for (bool withDistance : {true, false}) {
            // (steps are left out with the distance: each optional plane on its own)
            const bool withSteps = withDistance || spp == 1;
            CAPTURE(spp);
            CAPTURE(withDistance);
            CAPTURE(withSteps);
            PlaneF refHit(cam.width, cam.height), refSteps(cam.width, cam.height),
                refDist(cam.width, cam.height);
            RayBatch rays;
            MarchResult m;
            for (int s = 0; s < spp; ++s) {
                randomSample(cam, uint32_t(s), rays, m);
                oracle(cam, rays, m, refHit, refSteps, withDistance ? &refDist : nullptr, s == 0,
                       s == spp - 1, spp);
            }
            for (Isa isa : supportedIsas())
                for (int threads : testThreadCounts({1, 2, 8})) {
                    CAPTURE(isaName(isa));
                    CAPTURE(threads);
                    PlaneF hit(cam.width, cam.height), steps, dist;
                    if (withSteps) steps.ensureSize(cam.width, cam.height);
                    if (withDistance) dist.ensureSize(cam.width, cam.height);
                    const HitStatsArgs out{outputOf(hit, "hit"), outputOf(steps, "steps"),
                                           outputOf(dist, "distance")};
                    for (int s = 0; s < spp; ++s) {
                        randomSample(cam, uint32_t(s), rays, m);
                        accumulateHitStats(isa, cam, rays, m, out, s, spp, threads);
                    }
                    CHECK(sameBits(hit, refHit));
                    if (withSteps) CHECK(sameBits(steps, refSteps));
                    else CHECK(steps.empty());
                    if (withDistance) CHECK(sameBits(dist, refDist));
                }
        }
}

TEST_CASE("hit statistics: a missing or mis-sized plane is named") {
    TraceCamera cam;
    cam.width = 40;
    cam.height = 24;
    RayBatch rays;
    MarchResult m;
    randomSample(cam, 0, rays, m);
    PlaneF hit(40, 24), steps(40, 24), narrow(39, 24), none;
    const auto message = [&](const HitStatsArgs& out) -> std::string {
        try {
            accumulateHitStats(Isa::Scalar, cam, rays, m, out, 0, 1, 1);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    CHECK(message({outputOf(none, "ssrHit")}) == "accumulateHitStats: ssrHit is missing");
    CHECK(message({outputOf(hit, "ssrHit"), outputOf(narrow, "ssrSteps")}) ==
          "accumulateHitStats: ssrSteps is 39x24, not 40x24");
    m.steps = PlaneF();
    CHECK(message({outputOf(hit, "ssrHit"), outputOf(steps, "ssrSteps")}) ==
          "accumulateHitStats: march.steps is missing");
    CHECK(message({outputOf(hit, "ssrHit")}).empty());
}
