#include "io/flip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/color.h"
#include "core/lane_math.h"
#include "core/tiles.h"
#include "io/image_decode.h"
#include "io/image_io.h"
#include "io/io_errors.h"

namespace ssrt {

namespace ln = lanes;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------
// Colour spaces

// sRGB's linear RGB -> XYZ (IEC 61966-2-1), derived from its primaries and D65 white point
// (CIE xy): the columns are the primaries' XYZ (x/y, 1, z/y) scaled so that RGB (1, 1, 1)
// lands on the white's XYZ. In double, once, with + - * / only.
struct Matrix3 {
    double m[3][3];
};

Matrix3 inverse(const Matrix3& a) {
    const auto& m = a.m;
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    Matrix3 r;
    r.m[0][0] = c00 / det;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r.m[1][0] = c01 / det;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r.m[2][0] = c02 / det;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    return r;
}

struct ColourSpaces {
    float toXyz[3][3], fromXyz[3][3];
    float white[3], invWhite[3];  // XYZ of linear RGB (1, 1, 1), and its reciprocals
};

const ColourSpaces& colourSpaces() {
    static const ColourSpaces spaces = [] {
        const double xy[4][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
        Matrix3 p;  // the primaries' XYZ with Y = 1, as columns
        for (int c = 0; c < 3; ++c) {
            p.m[0][c] = xy[c][0] / xy[c][1];
            p.m[1][c] = 1.0;
            p.m[2][c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
        }
        const double w[3] = {xy[3][0] / xy[3][1], 1.0, (1.0 - xy[3][0] - xy[3][1]) / xy[3][1]};
        const Matrix3 pInv = inverse(p);
        double s[3];  // each primary's scale: p * s = white
        for (int r = 0; r < 3; ++r)
            s[r] = pInv.m[r][0] * w[0] + pInv.m[r][1] * w[1] + pInv.m[r][2] * w[2];
        Matrix3 m;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) m.m[r][c] = p.m[r][c] * s[c];
        const Matrix3 mInv = inverse(m);
        ColourSpaces out;
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) {
                out.toXyz[r][c] = float(m.m[r][c]);
                out.fromXyz[r][c] = float(mInv.m[r][c]);
            }
            const double white = m.m[r][0] + m.m[r][1] + m.m[r][2];
            out.white[r] = float(white);
            out.invWhite[r] = float(1.0 / white);
        }
        return out;
    }();
    return spaces;
}

void multiply(const float m[3][3], const float v[3], float out[3]) {
    for (int r = 0; r < 3; ++r) out[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
}

// CIELAB's f(t): the cube root above (6/29)^3, a line below.
float labF(float t) {
    constexpr float kDelta = 6.0f / 29.0f;
    if (t > kDelta * kDelta * kDelta) return ln::pow(t, 1.0f / 3.0f);
    return t / (3.0f * kDelta * kDelta) + 4.0f / 29.0f;
}

float hyab(const float a[3], const float b[3]) {
    const float da = a[1] - b[1], db = a[2] - b[2];
    return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

// ---------------------------------------------------------------------------------------
// Filters: separable, taps summed from -radius to +radius, the image's edge repeated.

int clampIndex(int i, int n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); }

// out(x, y) = sum_k taps[k] in(x + k - r, y), per row, on `threads`.
void filterRows(const PlaneF& in, const std::vector<float>& taps, PlaneF& out, int threads) {
    const int w = in.width(), h = in.height(), r = int(taps.size() / 2);
    out.ensureSize(w, h);
    parallelFor(h, threads, [&](int y) {
        const float* src = in.row(y);
        float* dst = out.row(y);
        for (int x = 0; x < w; ++x) {
            float sum = 0.0f;
            for (int k = -r; k <= r; ++k)
                sum += taps[std::size_t(k + r)] * src[clampIndex(x + k, w)];
            dst[x] = sum;
        }
    });
}

// out(x, y) = sum_k taps[k] in(x, y + k - r), per row, on `threads`.
void filterColumns(const PlaneF& in, const std::vector<float>& taps, PlaneF& out, int threads) {
    const int w = in.width(), h = in.height(), r = int(taps.size() / 2);
    out.ensureSize(w, h);
    parallelFor(h, threads, [&](int y) {
        float* dst = out.row(y);
        std::fill(dst, dst + w, 0.0f);
        for (int k = -r; k <= r; ++k) {
            const float t = taps[std::size_t(k + r)];
            const float* src = in.row(clampIndex(y + k, h));
            for (int x = 0; x < w; ++x) dst[x] += t * src[x];
        }
    });
}

// ---------------------------------------------------------------------------------------
// One image as the observer sees it: Hunt-adjusted L*a*b* after the contrast sensitivity
// filters, and the magnitudes of its edges and points.

struct Seen {
    PlaneF lab[3];
    PlaneF edges, points;
};

Seen see(const RgbImage& rgb, double ppd, int threads) {
    const int w = rgb.width(), h = rgb.height();
    // Linear RGB (clamped to [0, 1]) to YCxCz, and Y/Yw for the feature detectors.
    PlaneF opp[3] = {PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)};
    PlaneF lum(w, h);
    parallelFor(h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float c[3] = {std::clamp(rgb.r.at(x, y), 0.0f, 1.0f),
                                std::clamp(rgb.g.at(x, y), 0.0f, 1.0f),
                                std::clamp(rgb.b.at(x, y), 0.0f, 1.0f)};
            float o[3];
            flip_detail::linearRgbToYCxCz(c, o);
            for (int i = 0; i < 3; ++i) opp[i].at(x, y) = o[i];
            lum.at(x, y) = (o[0] + 16.0f) / 116.0f;
        }
    });

    // Colour: each opponent channel through its filter, back to linear RGB clamped to the
    // unit cube, then to Hunt-adjusted L*a*b*.
    Seen seen;
    PlaneF filtered[3], across, part;
    for (int c = 0; c < 3; ++c) {
        const flip_detail::SpatialFilter f = flip_detail::spatialFilter(c, ppd);
        filterRows(opp[c], f.taps[0], across, threads);
        filterColumns(across, f.taps[0], filtered[c], threads);
        if (f.share[1] == 0.0f) continue;
        filterRows(opp[c], f.taps[1], across, threads);
        filterColumns(across, f.taps[1], part, threads);
        const float s0 = f.share[0], s1 = f.share[1];
        parallelFor(h, threads, [&](int y) {
            float* a = filtered[c].row(y);
            const float* b = part.row(y);
            for (int x = 0; x < w; ++x) a[x] = s0 * a[x] + s1 * b[x];
        });
    }
    for (PlaneF& p : seen.lab) p = PlaneF(w, h);
    parallelFor(h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float o[3] = {filtered[0].at(x, y), filtered[1].at(x, y), filtered[2].at(x, y)};
            float c[3], lab[3];
            flip_detail::yCxCzToLinearRgb(o, c);
            for (float& v : c) v = std::clamp(v, 0.0f, 1.0f);
            flip_detail::linearRgbToHuntLab(c, lab);
            for (int i = 0; i < 3; ++i) seen.lab[i].at(x, y) = lab[i];
        }
    });

    // Features: the edge detector (first derivative of a Gaussian) and point detector (second
    // derivative) along x and along y, the Gaussian across.
    const flip_detail::FeatureFilter f = flip_detail::featureFilter(ppd);
    PlaneF g, d1, d2, ex, ey, px, py;
    filterRows(lum, f.gauss, g, threads);
    filterRows(lum, f.edge, d1, threads);
    filterRows(lum, f.point, d2, threads);
    filterColumns(d1, f.gauss, ex, threads);
    filterColumns(g, f.edge, ey, threads);
    filterColumns(d2, f.gauss, px, threads);
    filterColumns(g, f.point, py, threads);
    seen.edges = PlaneF(w, h);
    seen.points = PlaneF(w, h);
    parallelFor(h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float a = ex.at(x, y), b = ey.at(x, y), c = px.at(x, y), d = py.at(x, y);
            seen.edges.at(x, y) = std::sqrt(a * a + b * b);
            seen.points.at(x, y) = std::sqrt(c * c + d * d);
        }
    });
    return seen;
}

void checkSameSize(const RgbImage& a, const RgbImage& b) {
    for (const RgbImage* p : {&a, &b})
        if (p->g.width() != p->width() || p->b.width() != p->width() ||
            p->g.height() != p->height() || p->b.height() != p->height())
            throw std::invalid_argument("FLIP: an image's R, G and B planes differ in size");
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument("FLIP: the images differ in size");
}

// LDR-FLIP's error map of two images.
PlaneF ldrError(const RgbImage& test, const RgbImage& reference, double ppd, int threads) {
    using K = flip_detail::FlipConstants;
    static_assert(K::qf == 0.5f, "the feature exponent is taken as a square root");
    const Seen t = see(test, ppd, threads);
    const Seen r = see(reference, ppd, threads);
    const int w = test.width(), h = test.height();
    const float cmax = flip_detail::flipColourMax();
    const float pccmax = K::pc * cmax;
    PlaneF error(w, h);
    parallelFor(h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            // Colour: HyAB^qc, mapped so that pc * cmax gives pt and cmax gives 1.
            const float lt[3] = {t.lab[0].at(x, y), t.lab[1].at(x, y), t.lab[2].at(x, y)};
            const float lr[3] = {r.lab[0].at(x, y), r.lab[1].at(x, y), r.lab[2].at(x, y)};
            const float d = ln::pow(hyab(lr, lt), K::qc);
            const float colour = d < pccmax
                                     ? d * (K::pt / pccmax)
                                     : K::pt + ((d - pccmax) / (cmax - pccmax)) * (1.0f - K::pt);
            // Features: the larger difference of edge or point magnitude, over sqrt(2), ^qf.
            const float de = std::abs(t.edges.at(x, y) - r.edges.at(x, y));
            const float dp = std::abs(t.points.at(x, y) - r.points.at(x, y));
            const float feature = std::sqrt(std::max(de, dp) / 1.41421356237309505f);
            error.at(x, y) = ln::pow(colour, 1.0f - feature);
        }
    });
    return error;
}

// ---------------------------------------------------------------------------------------
// HDR-FLIP's tone map: Narkowicz's fit of the ACES curve (2016),
// f(u) = u (2.51 u + 0.03) / (u (2.43 u + 0.59) + 0.14), applied to 0.6 x (the pre-exposure
// the fit assumes, cancelled as the HDR-FLIP paper does), clamped to [0, 1].
constexpr double kAcesA = 2.51, kAcesB = 0.03, kAcesC = 2.43, kAcesD = 0.59, kAcesE = 0.14;
constexpr float kAcesExposure = 0.6f;

float toneMap(float x) {
    const float u = kAcesExposure * x;
    if (!(u < 1e15f)) return 1.0f;  // the curve's limit, 2.51 / 2.43, clamped
    const float y = u * (float(kAcesA) * u + float(kAcesB)) /
                    (u * (float(kAcesC) * u + float(kAcesD)) + float(kAcesE));
    return std::clamp(y, 0.0f, 1.0f);
}

// The x the tone map takes to t: the larger root of (A - tC) u^2 + (B - tD) u - tE = 0, over 0.6.
double toneMapInverse(double t) {
    const double a = kAcesA - t * kAcesC, b = kAcesB - t * kAcesD, c = -t * kAcesE;
    return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a) / double(kAcesExposure);
}

// Linear input of any range as HDR-FLIP reads it: NaN and negative values 0, +inf the
// largest float.
float hdrValue(float v) {
    if (!(v > 0.0f)) return 0.0f;
    return std::min(v, std::numeric_limits<float>::max());
}

float luminance(float r, float g, float b) {
    return 0.2126f * hdrValue(r) + 0.7152f * hdrValue(g) + 0.0722f * hdrValue(b);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// The pieces

namespace flip_detail {

void linearRgbToYCxCz(const float rgb[3], float out[3]) {
    const ColourSpaces& s = colourSpaces();
    float xyz[3];
    multiply(s.toXyz, rgb, xyz);
    for (int i = 0; i < 3; ++i) xyz[i] *= s.invWhite[i];
    out[0] = 116.0f * xyz[1] - 16.0f;
    out[1] = 500.0f * (xyz[0] - xyz[1]);
    out[2] = 200.0f * (xyz[1] - xyz[2]);
}

void yCxCzToLinearRgb(const float o[3], float out[3]) {
    const ColourSpaces& s = colourSpaces();
    const float y = (o[0] + 16.0f) / 116.0f;
    float xyz[3] = {y + o[1] / 500.0f, y, y - o[2] / 200.0f};
    for (int i = 0; i < 3; ++i) xyz[i] *= s.white[i];
    multiply(s.fromXyz, xyz, out);
}

void linearRgbToHuntLab(const float rgb[3], float out[3]) {
    const ColourSpaces& s = colourSpaces();
    float xyz[3];
    multiply(s.toXyz, rgb, xyz);
    const float fx = labF(xyz[0] * s.invWhite[0]), fy = labF(xyz[1] * s.invWhite[1]),
                fz = labF(xyz[2] * s.invWhite[2]);
    const float l = 116.0f * fy - 16.0f;
    out[0] = l;
    out[1] = 0.01f * l * (500.0f * (fx - fy));
    out[2] = 0.01f * l * (200.0f * (fy - fz));
}

float flipColourMax() {
    const float green[3] = {0.0f, 1.0f, 0.0f}, blue[3] = {0.0f, 0.0f, 1.0f};
    float g[3], b[3];
    linearRgbToHuntLab(green, g);
    linearRgbToHuntLab(blue, b);
    return ln::pow(hyab(g, b), FlipConstants::qc);
}

// The contrast sensitivity of channel c as a sum of Gaussians over x in degrees (the FLIP
// paper, eq. 2): S(x) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 x^2 / b_i), used in 2D as S(|x|)
// over a (2r+1)^2 window normalized to sum 1, r = ceil(3 sigma_max ppd) from the widest
// Gaussian of every channel (sigma^2 = b / (2 pi^2)). exp(-pi^2 (x^2 + y^2) / b) is
// g(x) g(y), so term i is the separable g_i x g_i of weight a_i sqrt(pi / b_i) (sum g_i)^2
// within the 2D sum: that weight over the total is share[i], g_i / sum g_i the taps.
SpatialFilter spatialFilter(int channel, double ppd) {
    struct Gaussians {
        double a[2], b[2];
    };
    static constexpr Gaussians kCsf[3] = {{{1.0, 0.0}, {0.0047, 1e-5}},    // achromatic
                                          {{1.0, 0.0}, {0.0053, 1e-5}},    // red-green
                                          {{34.1, 13.5}, {0.04, 0.025}}};  // blue-yellow
    const double widest = 0.04;
    SpatialFilter f;
    f.radius = int(std::ceil(3.0 * std::sqrt(widest / (2.0 * kPi * kPi)) * ppd));
    const Gaussians& csf = kCsf[std::clamp(channel, 0, 2)];
    double weight[2] = {0.0, 0.0};
    for (int i = 0; i < 2; ++i) {
        if (csf.a[i] == 0.0) continue;
        std::vector<float>& taps = f.taps[i];
        taps.resize(std::size_t(2 * f.radius + 1));
        double sum = 0.0;
        for (int k = -f.radius; k <= f.radius; ++k) {
            const double x = double(k) / ppd;
            const float g = ln::exp(float(-kPi * kPi * x * x / csf.b[i]));
            taps[std::size_t(k + f.radius)] = g;
            sum += double(g);
        }
        for (float& t : taps) t = float(double(t) / sum);
        weight[i] = csf.a[i] * std::sqrt(kPi / csf.b[i]) * sum * sum;
    }
    f.share[0] = float(weight[0] / (weight[0] + weight[1]));
    f.share[1] = float(weight[1] / (weight[0] + weight[1]));
    return f;
}

// The edge and point detectors (the FLIP paper, section 4.2): a Gaussian of standard deviation
// sigma = w / 2 degrees (w the peak-to-trough width of the human edge detector), its first and
// second derivatives over r = ceil(3 sigma) pixels, each normalized so that its positive taps
// sum to 1 and its negative ones to -1 (the Gaussian itself to 1).
FeatureFilter featureFilter(double ppd) {
    const double sd = 0.5 * double(FlipConstants::w) * ppd;
    FeatureFilter f;
    f.radius = int(std::ceil(3.0 * sd));
    const std::size_t n = std::size_t(2 * f.radius + 1);
    f.gauss.resize(n);
    f.edge.resize(n);
    f.point.resize(n);
    double gSum = 0.0, edgeSum[2] = {0.0, 0.0}, pointSum[2] = {0.0, 0.0};  // [negative, positive]
    for (int k = -f.radius; k <= f.radius; ++k) {
        const std::size_t i = std::size_t(k + f.radius);
        const double x = double(k);
        const double g = double(ln::exp(float(-x * x / (2.0 * sd * sd))));
        const double d1 = -x * g, d2 = (x * x / (sd * sd) - 1.0) * g;
        f.gauss[i] = float(g);
        f.edge[i] = float(d1);
        f.point[i] = float(d2);
        gSum += g;
        edgeSum[d1 > 0.0] += std::abs(d1);
        pointSum[d2 > 0.0] += std::abs(d2);
    }
    for (std::size_t i = 0; i < n; ++i) {
        f.gauss[i] = float(double(f.gauss[i]) / gSum);
        f.edge[i] = float(double(f.edge[i]) / edgeSum[f.edge[i] > 0.0f]);
        f.point[i] = float(double(f.point[i]) / pointSum[f.point[i] > 0.0f]);
    }
    return f;
}

}  // namespace flip_detail

// ---------------------------------------------------------------------------------------
// Public

FlipStats flipStats(const PlaneF& error) {
    FlipStats s;
    std::vector<float> values;
    values.reserve(std::size_t(error.width()) * std::size_t(error.height()));
    double sum = 0.0;
    for (int y = 0; y < error.height(); ++y)
        for (int x = 0; x < error.width(); ++x) {
            const float e = error.at(x, y);
            values.push_back(e);
            sum += double(e);
            s.max = std::max(s.max, double(e));
        }
    if (values.empty()) return s;
    s.mean = sum / double(values.size());
    std::sort(values.begin(), values.end());
    double running = 0.0;
    for (const float e : values) {
        running += double(e);
        if (running > 0.5 * sum) {
            s.weightedMedian = double(e);
            break;
        }
    }
    return s;
}

FlipResult ldrFlip(const RgbImage& test, const RgbImage& reference, double ppd, int threads) {
    checkSameSize(test, reference);
    FlipResult result;
    result.error = ldrError(test, reference, ppd, threads);
    result.stats = flipStats(result.error);
    return result;
}

FlipResult hdrFlip(const RgbImage& test, const RgbImage& reference, double ppd, int threads) {
    checkSameSize(test, reference);
    const int w = reference.width(), h = reference.height();
    FlipResult result;
    result.hdr = true;
    // The exposures: from the one that takes the brightest pixel's luminance to t = 0.85 to the
    // one that takes the median's there (the HDR-FLIP paper, section 3), in steps of at most a
    // stop, at least two. The median is the upper one (element n / 2 in order); when it is 0,
    // the smallest luminance above 0 stands in, and a black reference gives exposure 0.
    std::vector<float> lum;
    lum.reserve(std::size_t(w) * std::size_t(h));
    float smallest = std::numeric_limits<float>::max();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float l =
                luminance(reference.r.at(x, y), reference.g.at(x, y), reference.b.at(x, y));
            lum.push_back(l);
            if (l > 0.0f) smallest = std::min(smallest, l);
        }
    float start = 0.0f, stop = 0.0f;
    if (!lum.empty()) {
        const float largest = *std::max_element(lum.begin(), lum.end());
        const std::size_t mid = lum.size() / 2;
        std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(mid), lum.end());
        const float median = lum[mid] > 0.0f ? lum[mid] : smallest;
        if (largest > 0.0f) {
            const float xMax = float(toneMapInverse(0.85));
            start = ln::log2(xMax / largest);
            stop = ln::log2(xMax / median);
        }
    }
    const int n = int(std::max(2.0f, std::ceil(stop - start)));
    const float step = (stop - start) / float(n - 1);
    result.exposures = n;
    result.startExposure = start;
    result.stopExposure = stop;

    result.error = PlaneF(w, h, 0.0f);
    RgbImage t{PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)};
    RgbImage r{PlaneF(w, h), PlaneF(w, h), PlaneF(w, h)};
    for (int i = 0; i < n; ++i) {
        const float scale = ln::exp2(start + float(i) * step);
        parallelFor(h, threads, [&](int y) {
            for (int x = 0; x < w; ++x) {
                t.r.at(x, y) = toneMap(scale * hdrValue(test.r.at(x, y)));
                t.g.at(x, y) = toneMap(scale * hdrValue(test.g.at(x, y)));
                t.b.at(x, y) = toneMap(scale * hdrValue(test.b.at(x, y)));
                r.r.at(x, y) = toneMap(scale * hdrValue(reference.r.at(x, y)));
                r.g.at(x, y) = toneMap(scale * hdrValue(reference.g.at(x, y)));
                r.b.at(x, y) = toneMap(scale * hdrValue(reference.b.at(x, y)));
            }
        });
        const PlaneF e = ldrError(t, r, ppd, threads);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                result.error.at(x, y) = std::max(result.error.at(x, y), e.at(x, y));
    }
    result.stats = flipStats(result.error);
    return result;
}

}  // namespace ssrt
