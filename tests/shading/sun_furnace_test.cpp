// The sun's half of the white furnace, at the level of shade::shadeSurface: for a white metal
// (F0 = 1, so F = 1) lit by a unit sun along l, the radiance leaving towards v is
// f(l, v) n.l, and by reciprocity int f(l, v) cos(theta_v) dv = E(n.l) + (1 - E(n.l)) = 1 with
// Kulla-Conty's lobe (shading/direct_lanes.h), E(n.l) < 1 without it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include "shading/direct_lanes.h"
#include "shading/multiscatter.h"

using namespace ssrt;

namespace {

// pi * the mean of f(l, v) over cosine-distributed v on an n x n stratified grid.
double sunAlbedo(float roughness, float cosL, int n) {
    DirectArgs a{};
    a.energy = &energyTables();
    const float sinL = std::sqrt(1.0f - cosL * cosL);
    const float l[3] = {sinL, 0.0f, cosL};
    std::copy_n(l, 3, a.toLight);
    const float one[3] = {1.0f, 1.0f, 1.0f};
    std::copy_n(one, 3, a.lightRadiance);
    shade::Surface<float> s;
    s.p = {0.0f, 0.0f, 0.0f};
    s.n = {0.0f, 0.0f, 1.0f};
    s.albedo = {1.0f, 1.0f, 1.0f};
    s.metallic = 1.0f;
    s.roughness = roughness;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double u1 = (i + 0.5) / n, u2 = (j + 0.5) / n;
            const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
            s.view = {float(r * std::cos(phi)), float(r * std::sin(phi)),
                      float(std::sqrt(1.0 - u1))};
            const shade::Parts<float> p = shade::shadeSurface(a, s, 1.0f);
            sum += double(p.sun.x) / double(cosL);
        }
    return M_PI * sum / (double(n) * n);
}

}  // namespace

TEST_CASE("shading: the sun's specular on a white metal integrates to one (Kulla-Conty lobe)") {
    const EnergyTables& t = energyTables();
    for (float roughness : {0.25f, 0.5f, 0.75f, 1.0f})
        for (float cosL : {0.3f, 0.7f, 1.0f}) {
            CAPTURE(roughness);
            CAPTURE(cosL);
            const double total = sunAlbedo(roughness, cosL, 512);
            const float single = multiscatter::albedo(t, cosL, roughness);
            std::printf("sun furnace roughness %.2f n.l %.1f: %.4f (single scattering E %.4f)\n",
                        roughness, cosL, total, single);
            CHECK(total == doctest::Approx(1.0).epsilon(0.01));
        }
}
