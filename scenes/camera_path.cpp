#include "scenes/camera_path.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

namespace ssrt {

namespace {

using Vec = glm::dvec3;
using Keys = std::span<const CameraKey>;  // one piece of the path: the keys between two cuts

// Tangent at key k (time units), one-sided at the piece's ends.
template <class Get>
auto tangent(Keys keys, std::size_t k, Get get) {
    const std::size_t lo = k == 0 ? 0 : k - 1, hi = std::min(k + 1, keys.size() - 1);
    return (get(keys[hi]) - get(keys[lo])) / (keys[hi].time - keys[lo].time);
}

// Hermite segment between keys k and k + 1 at s in [0, 1).
template <class T, class Get>
T hermite(Keys keys, std::size_t k, double s, Get get) {
    const double d = keys[k + 1].time - keys[k].time;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = (2.0 * s3 - 3.0 * s2) + 1.0, h10 = (s3 - 2.0 * s2) + s;
    const double h01 = 3.0 * s2 - 2.0 * s3, h11 = s3 - s2;
    const T m0 = tangent(keys, k, get) * d, m1 = tangent(keys, k + 1, get) * d;
    return ((get(keys[k]) * h00 + m0 * h10) + get(keys[k + 1]) * h01) + m1 * h11;
}

template <class T, class Get>
T linear(Keys keys, std::size_t k, double s, Get get) {
    return get(keys[k]) * (1.0 - s) + get(keys[k + 1]) * s;
}

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The piece that holds time t: from the last cut at or before t (else the first key) to the
// key before the next cut (else the last key). Without cuts, every key.
Keys pieceAt(const std::vector<CameraKey>& keys, double t) {
    std::size_t first = 0, end = keys.size();
    for (std::size_t k = 1; k < keys.size(); ++k) {
        if (!keys[k].cut) continue;
        if (keys[k].time <= t) first = k;
        else {
            end = k;
            break;
        }
    }
    return Keys(keys).subspan(first, end - first);
}

}  // namespace

Camera CameraPath::at(double t, const Camera& base) const {
    Camera c = base;
    if (keys.empty()) return c;
    const Keys piece = pieceAt(keys, t);
    const CameraKey* exact = nullptr;
    if (!(t > piece.front().time)) exact = &piece.front();  // before the path (or NaN)
    if (t >= piece.back().time) exact = &piece.back();
    if (exact) {
        c.position = exact->position;
        c.target = exact->target;
        c.fovY = exact->fovY;
        return c;
    }
    // The segment [t_k, t_k+1) holding t.
    const auto after = std::upper_bound(
        piece.begin(), piece.end(), t, [](double v, const CameraKey& key) { return v < key.time; });
    const std::size_t k = std::size_t(after - piece.begin()) - 1;
    const double s = (t - piece[k].time) / (piece[k + 1].time - piece[k].time);
    const auto pos = [](const CameraKey& key) { return Vec(key.position); };
    const auto tgt = [](const CameraKey& key) { return Vec(key.target); };
    const auto fov = [](const CameraKey& key) { return double(key.fovY); };
    double f;
    if (interpolation == PathInterpolation::Linear) {
        c.position = glm::vec3(linear<Vec>(piece, k, s, pos));
        c.target = glm::vec3(linear<Vec>(piece, k, s, tgt));
        f = linear<double>(piece, k, s, fov);
    } else {
        c.position = glm::vec3(hermite<Vec>(piece, k, s, pos));
        c.target = glm::vec3(hermite<Vec>(piece, k, s, tgt));
        f = hermite<double>(piece, k, s, fov);
    }
    const double lo = std::min(piece[k].fovY, piece[k + 1].fovY);
    const double hi = std::max(piece[k].fovY, piece[k + 1].fovY);
    c.fovY = float(std::clamp(f, lo, hi));
    return c;
}

bool CameraPath::cutBetween(double t0, double t1) const {
    for (const CameraKey& key : keys)
        if (key.cut && key.time > t0 && key.time <= t1) return true;
    return false;
}

double CameraPath::frameTime(int i, int n) const {
    if (keys.empty()) return 0.0;
    if (n <= 1) return keys.front().time;
    const double s = double(i) / double(n - 1);
    return keys.front().time * (1.0 - s) + keys.back().time * s;
}

void CameraPath::validate() const {
    for (std::size_t k = 0; k < keys.size(); ++k) {
        const CameraKey& key = keys[k];
        const std::string name = "camera path key " + std::to_string(k);
        if (!std::isfinite(key.time)) throw std::invalid_argument(name + ": time is not finite");
        if (k > 0 && !(key.time > keys[k - 1].time))
            throw std::invalid_argument(name + ": time must be greater than the previous key's");
        if (!finite3(key.position) || !finite3(key.target))
            throw std::invalid_argument(name + ": position and target must be finite");
        if (key.position == key.target)
            throw std::invalid_argument(name + ": position and target are the same point");
        if (!(key.fovY > 0.0f && key.fovY < 180.0f))
            throw std::invalid_argument(name + ": fovY must be in (0, 180)");
        if (k == 0 && key.cut)
            throw std::invalid_argument(name +
                                        ": the first key cannot be a cut (nothing comes "
                                        "before it to cut from)");
    }
}

}  // namespace ssrt
