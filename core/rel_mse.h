// relMSE, the image error every ssrt tool reports (ssrt compare and sweep against the Embree
// reference, ssrt diff against a golden image), defined once:
//   relMSE = mean over pixels and channels of (I - R)^2 / (R^2 + 0.01)
// with R the reference. The 0.01 keeps a dark reference from dividing by zero: below
// R = 0.1 the error becomes a plain squared error times 100.
#pragma once

namespace ssrt {

// relMSE's guard against division by a dark reference.
inline constexpr double kRelMseEpsilon = 0.01;

// One value's term of relMSE: (i - r)^2 / (r^2 + 0.01), r the reference. Callers sum it in
// double in a fixed order and divide by the count of values.
inline double relSquaredError(double i, double r) {
    const double d = i - r;
    return d * d / (r * r + kRelMseEpsilon);
}

}  // namespace ssrt
