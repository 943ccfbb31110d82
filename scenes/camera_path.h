// A camera path: keyframes with times, for multi-frame sequences (ssrt render --frames).
#pragma once

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ssrt {

// One keyframe: where the camera is, what it looks at and its vertical field of view
// (degrees) at `time` (any unit: only the ratios between key times matter). `cut`: the
// camera jumps to this key (an edit between two shots): the path before it ends at the
// previous key and holds still there until this key's time, the path from it on starts here,
// and nothing is interpolated across (the first key cannot be one).
struct CameraKey {
    double time = 0.0;
    glm::vec3 position{0.0f, 1.0f, 5.0f};
    glm::vec3 target{0.0f};
    float fovY = 45.0f;
    bool cut = false;
};

enum class PathInterpolation {
    Linear,      // straight lines between keys: continuous, with corners at the keys
    CatmullRom,  // cubic through every key, continuous with a continuous first derivative
};

// Keys in strictly increasing time. Position, target and fovY are interpolated; up, near and
// far come from the base camera handed to at().
//
// Catmull-Rom on uneven times: on [t_k, t_k+1] the cubic Hermite curve
//   p(s) = h00(s) p_k + h10(s) d m_k + h01(s) p_k+1 + h11(s) d m_k+1,   d = t_k+1 - t_k,
//   s = (t - t_k) / d,  h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = 3s^2 - 2s^3,
//   h11 = s^3 - s^2,
// with tangents m_k = (p_k+1 - p_k-1) / (t_k+1 - t_k-1), one-sided at the first and last key.
// fovY is clamped to the range of the two keys around t (the cubic may overshoot).
// Evaluated in double from the float keys and rounded to float once, with no fused
// operations: the same bits on every machine. At a key's time the result is that key exactly
// (s = 0 zeroes every other term); before the first key and after the last it holds still.
// Cuts split the keys into pieces, each a path of its own as above (its end keys' tangents
// one-sided): a path without cuts is one piece.
struct CameraPath {
    std::vector<CameraKey> keys;
    PathInterpolation interpolation = PathInterpolation::CatmullRom;

    bool empty() const { return keys.empty(); }

    // The camera at time t: base with position, target and fovY from the path (base itself
    // if the path is empty).
    Camera at(double t, const Camera& base) const;

    // The time of frame i of n frames that sample the path evenly from its first key's time
    // to its last's: t_first (1 - i / (n - 1)) + t_last i / (n - 1); frame 0 is at the first
    // key, frame n - 1 at the last, and a single frame at the first.
    double frameTime(int i, int n) const;

    // Whether a cut lies in (t0, t1]: a frame at t1 whose previous frame was at t0 is the
    // first of a new shot (its history must not be read, its motion not taken from t0).
    bool cutBetween(double t0, double t1) const;

    // Throws std::invalid_argument naming the first bad key (times not finite or not
    // increasing, non-finite vectors, position equal to target, fovY outside (0, 180), a cut
    // on the first key).
    void validate() const;
};

}  // namespace ssrt
