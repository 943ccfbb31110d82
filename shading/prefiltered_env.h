// The prefiltered environment of the split-sum image-based light, and the split sum itself.
//
// Karis 2013, "Real Shading in Unreal Engine 4": the specular integral of an environment is
// split into two factors,
//   int L(l) f(l, v) cos(theta_l) dl ~ LD(R, r) * int f(l, v) cos(theta_l) dl,
// the second being the DFG table of shading/energy_tables.h (F0 * A + F90 * B with Schlick's
// F), the first the environment convolved with the GGX lobe under the assumption N = V = R:
//   LD(R, r) = sum_k L(l_k) (N.l_k) / sum_k (N.l_k),  h_k ~ D(h) (N.h),  l_k = reflect(V, h_k).
// LD is precomputed per roughness level, r_i = i / (levels - 1), each level an equirect image
// (mapping of shading/environment.h) smaller than the one before, and looked up trilinearly.
#pragma once

#include <vector>

#include "shading/environment.h"

namespace ssrt {

struct PrefilterSettings {
    int levels = 7;        // roughness levels r_i = i / (levels - 1), at least 2
    int samples = 256;     // GGX samples per texel (Hammersley points)
    int maxWidth = 256;    // width of level 1 is min(source, maxWidth) / 2, halving per level
    int minWidth = 8;      // no level narrower than this (height is always width / 2)
    int threads = 0;       // 0 = all cores; the result does not depend on it
    bool filtered = true;  // filtered importance sampling; false reads the source's level 0
};

class PrefilteredEnvironment {
public:
    PrefilteredEnvironment() = default;  // black
    explicit PrefilteredEnvironment(const Environment& env, const PrefilterSettings& s = {});

    // LD(R, roughness): R the reflection vector (any length), roughness perceptual in [0, 1]
    // (clamped). Bilinear within a level, linear between the two nearest levels.
    Rgb lookup(lanes::V3<float> r, float roughness) const;

    bool isConstant() const { return levels_.empty(); }
    int levelCount() const { return int(levels_.size()); }
    const EquirectImage& level(int i) const { return levels_[i]; }
    float levelRoughness(int i) const { return float(i) / float(levelCount() - 1); }

private:
    Rgb color_{};
    std::vector<EquirectImage> levels_;
};

// Prefilters one level: every texel of a width x height image gets LD at its centre's
// direction for the given perceptual roughness, by GGX importance sampling with filtered
// importance sampling over env's mip chain (settings: samples, threads, filtered). Exposed
// for the tests.
EquirectImage prefilterLevel(const Environment& env, float roughness, int width, int height,
                             const PrefilterSettings& s);

// The DFG terms of the split sum at (N.V, roughness): specular albedo = F0 * a + F90 * b.
struct DfgTerms {
    float a, b;
};
DfgTerms dfgTerms(float NoV, float roughness);

// Split sum: specular = LD * (F0 * A + F90 * B), per channel.
Rgb splitSum(Rgb ld, Rgb f0, Rgb f90, DfgTerms dfg);
Rgb splitSumSpecular(const PrefilteredEnvironment& env, lanes::V3<float> r, float NoV,
                     float roughness, Rgb f0, Rgb f90 = {1.0f, 1.0f, 1.0f});

}  // namespace ssrt
