// Image error against a reference. Conventions (relMSE's term is core/rel_mse.h's):
//   relMSE = mean over pixels and the three channels of (I - R)^2 / (R^2 + 0.01)
//   RMSE   = sqrt(mean over pixels and channels of (I - R)^2)
// on scene-linear or exposed values as the caller passes them (ssrt compare: the exposed
// linear colour, and the parts before exposure). Non-finite pixels of I count as an error of
// 1e10 each (so a NaN cannot hide); a reference must be finite.
#pragma once

#include "core/image.h"

namespace ssrt {

struct ImageError {
    double relMse = 0.0;
    double rmse = 0.0;
    uint64_t nonFinite = 0;  // pixels of I with a NaN or an infinity
};

// Throws std::invalid_argument when the planes' sizes differ or a pointer is null.
ImageError imageError(const PlaneF* const image[3], const PlaneF* const reference[3]);

}  // namespace ssrt
