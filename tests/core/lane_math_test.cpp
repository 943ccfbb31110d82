// The project's transcendentals: accurate against libm (double), and every ISA the machine
// runs returns the scalar copy's bits.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/lane_math_kernels.h"
#include "core/rng.h"

using namespace ssrt;

namespace {

struct Case {
    MathFn fn;
    const char* name;
    float lo, hi;    // input range of a
    float blo, bhi;  // input range of b (two-argument functions)
    double (*reference)(double, double);
    double absTol, relTol;  // |got - ref| <= absTol + relTol |ref|
};

const Case kCases[] = {
    {MathFn::Floor, "floor", -1e6f, 1e6f, 0, 0, [](double a, double) { return std::floor(a); }, 0,
     0},
    {MathFn::Sqrt, "sqrt", 0.0f, 1e4f, 0, 0, [](double a, double) { return std::sqrt(a); }, 0,
     1e-7},
    // Division and sqrt are the hardware's, correctly rounded: within half an ulp (2^-24).
    {MathFn::Div, "division", -100.0f, 100.0f, 0.001f, 100.0f,
     [](double a, double b) { return a / b; }, 0, 6e-8},
    {MathFn::Exp2, "exp2", -30.0f, 30.0f, 0, 0, [](double a, double) { return std::exp2(a); }, 0,
     3e-7},
    {MathFn::Log2, "log2", 1e-6f, 1e6f, 0, 0, [](double a, double) { return std::log2(a); }, 3e-7,
     3e-7},
    {MathFn::Exp, "exp", -20.0f, 20.0f, 0, 0, [](double a, double) { return std::exp(a); }, 0,
     1e-6},
    {MathFn::Log, "log", 1e-6f, 1e6f, 0, 0, [](double a, double) { return std::log(a); }, 3e-7,
     3e-7},
    {MathFn::Pow, "pow", 0.0f, 4.0f, 0.05f, 4.0f, [](double a, double b) { return std::pow(a, b); },
     1e-6, 2e-6},
    {MathFn::Sin, "sin", -100.0f, 100.0f, 0, 0, [](double a, double) { return std::sin(a); }, 3e-7,
     0},
    {MathFn::Cos, "cos", -100.0f, 100.0f, 0, 0, [](double a, double) { return std::cos(a); }, 3e-7,
     0},
    {MathFn::Asin, "asin", -1.0f, 1.0f, 0, 0, [](double a, double) { return std::asin(a); }, 3e-7,
     3e-7},
    {MathFn::Acos, "acos", -1.0f, 1.0f, 0, 0, [](double a, double) { return std::acos(a); }, 3e-7,
     3e-7},
    {MathFn::Atan, "atan", -100.0f, 100.0f, 0, 0, [](double a, double) { return std::atan(a); },
     3e-7, 3e-7},
    {MathFn::Atan2, "atan2", -10.0f, 10.0f, -10.0f, 10.0f,
     [](double a, double b) { return std::atan2(a, b == 0 ? 0.0 : b); }, 5e-7, 3e-7},
};

// Inputs: a uniform sweep plus the edges where reductions change branch.
std::vector<float> inputs(float lo, float hi, uint32_t salt) {
    std::vector<float> v;
    for (uint32_t i = 0; i < 20000; ++i) v.push_back(lo + (hi - lo) * randomFloat(i, salt, 0, 0));
    for (float x : {0.0f, -0.0f, 0.5f, -0.5f, 1.0f, -1.0f, 0.70710678f, 2.414213562f, 0.41421356f,
                    1.5707963f, 3.1415927f, -3.1415927f, 0.78539816f, 1e-8f})
        if (x >= lo && x <= hi) v.push_back(x);
    v.push_back(lo);
    v.push_back(hi);
    return v;
}

}  // namespace

TEST_CASE("lane math is accurate against libm") {
    for (const Case& c : kCases) {
        const std::string fnName = c.name;
        CAPTURE(fnName);
        const auto a = inputs(c.lo, c.hi, 1);
        auto b = inputs(c.blo, c.bhi, 2);
        b.resize(a.size(), 1.0f);
        std::vector<float> out(a.size());
        evalMath(Isa::Scalar, c.fn, a.data(), b.data(), out.data(), a.size());
        double worst = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            const double ref = c.reference(a[i], b[i]);
            const double err =
                std::fabs(out[i] - ref) / (c.absTol + c.relTol * std::fabs(ref) + 1e-30);
            if (c.absTol == 0 && c.relTol == 0) {
                CAPTURE(a[i]);
                REQUIRE(out[i] == ref);
            }
            worst = std::max(worst, err);
            REQUIRE(std::isfinite(out[i]));
        }
        MESSAGE(fnName << " worst error " << worst << " of tolerance");
        if (c.absTol > 0 || c.relTol > 0) CHECK(worst <= 1.0);
    }
}

TEST_CASE("lane math: every ISA returns the scalar bits") {
    for (const Case& c : kCases) {
        const std::string fnName = c.name;
        CAPTURE(fnName);
        // Wider ranges than the accuracy test: out-of-domain inputs must agree too.
        const auto a = inputs(c.lo * 4 - 3, c.hi * 4 + 3, 3);
        auto b = inputs(c.blo * 4 - 1, c.bhi * 4 + 1, 4);
        b.resize(a.size(), 1.0f);
        std::vector<float> ref(a.size()), got(a.size());
        evalMath(Isa::Scalar, c.fn, a.data(), b.data(), ref.data(), a.size());
        for (Isa isa : supportedIsas()) {
            const std::string isaStr(isaName(isa));
            CAPTURE(isaStr);
            evalMath(isa, c.fn, a.data(), b.data(), got.data(), a.size());
            REQUIRE(std::memcmp(ref.data(), got.data(), ref.size() * sizeof(float)) == 0);
        }
    }
}

TEST_CASE("lane RNG: every ISA draws randomFloat's bits, lane by lane") {
    // Counters across the hash's range: pixel counts past 2^31 wrap as in the scalar hash.
    const uint32_t counters[][4] = {{0, 0, 0, 0},
                                    {1920 * 7 + 13, 3, 0, 2},
                                    {0x7ffffff0u, 1, 2, 3},
                                    {0xfffffff8u, 0xffffffffu, 65, 9},
                                    {123457, 30, 0x10004, 0}};
    std::vector<float> ref(1000), got(ref.size());
    for (const auto& c : counters) {
        CAPTURE(c[0]);
        for (std::size_t i = 0; i < ref.size(); ++i)
            ref[i] = randomFloat(c[0] + uint32_t(i), c[1], c[2], c[3]);
        for (Isa isa : supportedIsas()) {
            const std::string isaStr(isaName(isa));
            CAPTURE(isaStr);
            evalRandom(isa, c[0], c[1], c[2], c[3], got.data(), got.size());
            REQUIRE(std::memcmp(ref.data(), got.data(), ref.size() * sizeof(float)) == 0);
        }
    }
}
