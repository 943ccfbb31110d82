// Colour encodings, pure functions of a value.
#pragma once

namespace ssrt {

// The sRGB transfer function's inverse (IEC 61966-2-1), with the project's own pow: an
// encoded value in [0, 1] to linear; 0 for NaN and values <= 0.
float srgbToLinear(float encoded);

}  // namespace ssrt
