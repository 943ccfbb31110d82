// Diffuse light from an environment image through spherical harmonics.
//
// Ramamoorthi and Hanrahan 2001, "An Efficient Representation for Irradiance Environment
// Maps": the irradiance E(n) = int L(w) max(n.w, 0) dw is smooth enough that the first nine
// real spherical harmonics (bands 0 to 2) hold it to within a few percent.
//   1. Project the radiance:   L_lm = sum over texels of L(w_t) Y_lm(w_t) dOmega_t
//      (w_t the texel centre's direction, dOmega_t its exact solid angle,
//       (2 pi / w) (cos(pi y / h) - cos(pi (y + 1) / h)) for row y of h).
//   2. Convolve with the clamped cosine: E_lm = A_l L_lm, A_0 = pi, A_1 = 2 pi / 3,
//      A_2 = pi / 4.
//   3. E(n) / pi = sum_lm (A_l / pi) L_lm Y_lm(n): the cosine-weighted mean radiance around
//      n, what a Lambert surface of albedo a reflects as a E / pi.
// The Y_lm are polynomials in the unit direction (x, y, z), so step 3 is one polynomial per
// channel whose nine coefficients fold the basis constants, A_l / pi and L_lm together:
//   E / pi = k0 + k1 y + k2 z + k3 x + k4 xy + k5 yz + k6 (3 z^2 - 1) + k7 xz + k8 (x^2 - y^2).
// Any orthonormal frame serves (each band is closed under rotation), so the world frame is
// used as it is. Nine terms ring a little around a very bright, small source; the evaluation
// clamps at zero.
#pragma once

#include "core/lane_vec.h"
#include "shading/environment.h"

namespace ssrt {

inline constexpr int kShTerms = 9;

// The polynomial above, per channel: coeffs[c * kShTerms + j] is k_j of channel c.
struct ShIrradiance {
    float coeffs[3 * kShTerms] = {};
};

// Projects an equirect image (steps 1 and 2 above). Sums in double in a fixed order over the
// texels, with the project's own sin and cos for the directions, so every machine gets the
// same coefficients.
ShIrradiance projectIrradianceSh(const EquirectView& image);

// E(n) / pi for a unit normal n (scalar, for set-up code and tests).
Rgb irradianceSh(const ShIrradiance& sh, lanes::V3<float> n);

namespace env {

// E(n) / pi per lane from the 27 coefficients of ShIrradiance, clamped at zero.
template <class L>
SSRT_INLINE ln::V3<L> irradianceSh(const float* k, ln::V3<L> n) {
    const L x = n.x, y = n.y, z = n.z;
    const L basis[kShTerms] = {
        L(1.0f), y, z, x, x * y, y * z, L(3.0f) * z * z - L(1.0f), x * z, x * x - y * y};
    L out[3];
    for (int c = 0; c < 3; ++c) {
        L sum = L(k[c * kShTerms]);
        for (int j = 1; j < kShTerms; ++j) sum = sum + L(k[c * kShTerms + j]) * basis[j];
        out[c] = ln::max(sum, L(0.0f));
    }
    return {out[0], out[1], out[2]};
}

}  // namespace env

}  // namespace ssrt
