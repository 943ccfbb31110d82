#include "core/color.h"

#include "core/lane_math.h"

namespace ssrt {

float srgbToLinear(float c) {
    if (!(c > 0.04045f)) return c > 0.0f ? c / 12.92f : 0.0f;
    return lanes::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace ssrt
