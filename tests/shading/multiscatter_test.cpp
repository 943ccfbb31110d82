// Kulla-Conty: the tables against an independent quadrature, single scattering losing energy
// at high roughness, and the white furnace with the multiple-scattering lobe: total albedo 1.
#include "shading/multiscatter.h"

#include <doctest/doctest.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "shading/energy_tables.h"

using namespace ssrt;
namespace ms = ssrt::multiscatter;

namespace {

// E(mu, alpha) by a different route than the tables: over the half vector, drawn from D cos
// on an n x n midpoint grid of the classic inversion: E = int D G2 (v.m) / v.z dm
//   = mean of G2 (v.m) / (v.z m.z) over m ~ D(m) m.z, counting only o = reflect(v, m) above.
double albedoByNdf(double mu, double alpha, int n) {
    const double vx = std::sqrt(1.0 - mu * mu), vz = mu, a2 = alpha * alpha;
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double u = (i + 0.5) / n, phi = 2 * M_PI * (j + 0.5) / n;
            const double c2 = (1 - u) / (u * (a2 - 1) + 1), ct = std::sqrt(c2),
                         st = std::sqrt(1 - c2);
            const double mx = st * std::cos(phi), my = st * std::sin(phi), mz = ct;
            const double vm = vx * mx + vz * mz;
            if (vm <= 0) continue;
            const double ox = 2 * vm * mx - vx, oy = 2 * vm * my, oz = 2 * vm * mz - vz;
            if (oz <= 0) continue;
            const double lv = 0.5 * (std::sqrt(1 + a2 * (1 - vz * vz) / (vz * vz)) - 1);
            const double lo = 0.5 * (std::sqrt(1 + a2 * (ox * ox + oy * oy) / (oz * oz)) - 1);
            sum += (1 / (1 + lv + lo)) * vm / (vz * mz);
        }
    return sum / (double(n) * n);
}

}  // namespace

TEST_CASE("shading: Kulla-Conty tables and the white furnace") {
    const EnergyTables& t = energyTables();

    const double mus[] = {0.03, 0.1, 0.25, 0.5, 0.75, 1.0};
    const double roughs[] = {0.0, 0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0};
    std::string table = "white furnace, F = 1: single scattering E / with Kulla-Conty\n  rough ";
    for (double mu : mus) {
        char b[32];
        std::snprintf(b, sizeof b, "  mu=%-4g         ", mu);
        table += b;
    }
    table += "\n";
    double worst = 0;
    for (double r : roughs) {
        char b[64];
        std::snprintf(b, sizeof b, "  %-5g", r);
        table += b;
        const double alpha = std::max(r * r, 1e-3);
        for (double mu : mus) {
            // Single scattering, by the independent route.
            // (its cut-offs at v.m = 0 and o.z = 0 converge slowly at grazing angles: a finer
            // grid there, n = 2500 puts it within 0.4% of the converged value at mu = 0.03)
            const double eTrue = albedoByNdf(mu, alpha, mu < 0.1 ? 2500 : 400);
            // The lobe integrated over wo: 2 pi int f_ms(mu, mu_o) mu_o dmu_o (it is isotropic).
            double msInt = 0;
            const int m = 2000;
            for (int k = 0; k < m; ++k) {
                const float muO = float((k + 0.5) / m);
                msInt += ms::fMs(t, float(mu), muO, float(r)) * muO;
            }
            msInt *= 2 * M_PI / m;
            const double total = eTrue + msInt;
            CAPTURE(mu);
            CAPTURE(r);
            CAPTURE(eTrue);
            CHECK(std::fabs(total - 1.0) < 0.01);
            // The table itself against the independent quadrature.
            CHECK(std::fabs(ms::albedo(t, float(mu), float(r)) - eTrue) < 0.01);
            worst = std::max(worst, std::fabs(total - 1.0));
            std::snprintf(b, sizeof b, "  %.4f / %.4f", eTrue, total);
            table += b;
        }
        table += "\n";
    }
    MESSAGE(table << "  largest |total - 1| = " << worst);

    // Single scattering loses energy at high roughness, hardly any when smooth.
    CHECK(albedoByNdf(1.0, 1.0, 400) < 0.85);
    CHECK(albedoByNdf(0.5, 1.0, 400) < 0.8);
    CHECK(albedoByNdf(1.0, 0.01, 400) > 0.995);
    // The switch, the Fresnel average and the tint.
    CHECK(ms::fMs(t, 0.5f, 0.5f, 1.0f, false) == 0.0f);
    CHECK(ms::fMs(t, 0.5f, 0.5f, 1.0f) > 0.0f);
    double favg = 0;
    for (int k = 0; k < 10000; ++k) {
        const double mu = (k + 0.5) / 10000;
        favg += (0.04 + (0.8 - 0.04) * std::pow(1 - mu, 5)) * mu;
    }
    CHECK(ms::fresnelAvg(0.04f, 0.8f) == doctest::Approx(2 * favg / 10000).epsilon(1e-4));
    CHECK(ms::fMsFresnelTint(1.0f, 0.7f) == doctest::Approx(1.0f));
    CHECK(ms::fMsFresnelTint(0.5f, 0.7f) < 0.5f);
}

TEST_CASE("shading: DFG table sums to E and matches the estimator") {
    const EnergyTables& t = energyTables();
    constexpr int N = kEnergyTableSize;
    for (int j = 0; j < N; j += 5)
        for (int i = 8; i < N; i += 5) {
            const float e = t.e[j * N + i], a = t.dfgA[j * N + i], b = t.dfgB[j * N + i];
            CHECK(a + b == doctest::Approx(e).epsilon(1e-5));
            const double x = double(i) / (N - 1), mu = x * x, r = double(j) / (N - 1);
            CHECK(std::fabs(e - albedoByNdf(mu, std::max(r * r, 1e-3), 600)) < 0.01);
        }
    // Smooth and head-on: all energy in dfgA (Fc = 0 at o.h = 1).
    CHECK(t.dfgA[N - 1] == doctest::Approx(1.0).epsilon(2e-3));
    CHECK(t.dfgB[N - 1] < 1e-3);
}

TEST_CASE("shading: the stored energy tables are what the estimator computes") {
    // The stored bits (shading/energy_tables_data.h) came from computeEnergyTables(); another
    // libm may round a double differently, so allow two float ulps, no more (the entries are
    // all non-negative, so ulps are the distance between the bit patterns).
    const EnergyTables& stored = energyTables();
    const EnergyTables fresh = computeEnergyTables();
    const auto agree = [](const char* name, const auto& a, const auto& b) {
        REQUIRE(a.size() == b.size());
        int bad = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            const int64_t ulps =
                int64_t(std::bit_cast<int32_t>(a[i])) - std::bit_cast<int32_t>(b[i]);
            if (std::abs(ulps) > 2 && bad++ < 3)
                FAIL_CHECK(name << "[" << i << "]: stored " << a[i] << ", computed " << b[i]);
        }
        CHECK_MESSAGE(bad == 0, name << ": " << bad << " entries more than 2 ulps apart");
    };
    agree("e", stored.e, fresh.e);
    agree("eAvg", stored.eAvg, fresh.eAvg);
    agree("dfgA", stored.dfgA, fresh.dfgA);
    agree("dfgB", stored.dfgB, fresh.dfgB);
    // And the tables are not trivially equal: they vary over the grid.
    CHECK(stored.e[0] != stored.e[kEnergyTableSize * kEnergyTableSize - 1]);
}
