// What each of REBLUR's passes does, pinned so that a rewrite of the denoiser (one pass over both
// signals, packed signals) can be checked against it: the spatial weights stop at plane,
// normal, roughness and hit-distance edges; the history read is Catmull-Rom where its 4x4
// footprint is whole and bilinear where a tap is occluded; the fast history follows a step
// within the window its cap implies; the history fix widens young pixels' reconstruction and
// clamps the slow history to the fast one; the temporal pass's firefly suppressor.
//
// Every expected value comes from the formulas of denoise/reblur_math.h and the kernels,
// restated here in double; every tolerance from the weight functions or float rounding. The
// passes run through their per-ISA kernels (denoise/reblur_kernel.h), on every ISA this
// machine runs. (tests/denoise/reblur_passes_test.cpp holds the passes' simpler invariants.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/isa.h"
#include "core/rng.h"
#include "core/tiles.h"
#include "denoise/denoise_settings.h"
#include "denoise/reblur_kernel.h"
#include "denoise/reblur_wall.h"

using namespace ssrt;

namespace {

constexpr int kWidth = 80, kHeight = 48;  // two tiles across (the second with padding), one down

// A wall facing the camera at depth 2 (view = world), both signals everywhere.
struct Guides : test::WallGuides {
    Guides() : WallGuides(kWidth, kHeight) {}
    void setDepth(int x, int y, float z) {
        viewZ.at(x, y) = z;
        signalZ[0].at(x, y) = signalZ[1].at(x, y) = z;
    }
};

// A signal: RGB and the normalised hit distance.
struct Signal {
    PlaneF p[4];
    explicit Signal(float value = 0.0f) {
        for (PlaneF& c : p) c = PlaneF(kWidth, kHeight, value);
    }
    void setRgb(int x, int y, float v) {
        for (int c = 0; c < 3; ++c) p[c].at(x, y) = v;
    }
    const float* in(int c) const { return p[c].row(0); }
    float* out(int c) { return p[c].row(0); }
};

std::vector<Isa> runnableIsas() {
    std::vector<Isa> isas;
    for (Isa isa : kAllIsas)
        if (isaSupported(isa)) isas.push_back(isa);
    return isas;
}

template <class Fn>
void forEachTile(Fn&& fn) {
    const TileGrid grid(kWidth, kHeight);
    for (int t = 0; t < grid.count(); ++t) fn(t);
}

double luma(double r, double g, double b) { return 0.25 * r + 0.5 * g + 0.25 * b; }

// reblur_math.h's shapes, in double.
double smoothstep01(double x) {
    const double s = std::clamp(x, 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}
double weightNonExp(double t) { return 1.0 - smoothstep01(std::abs(t)); }
double weightExp(double t) {
    const double a = std::abs(t);
    return 1.0 / (9.0 * a * a + 3.0 * a + 1.0);
}
double lerp(double a, double b, double t) { return a + (b - a) * t; }

// ---------------------------------------------------------------------------------------
// Spatial edges.
//
// The blur's 8 taps (spatial_kernel.cpp's kSpecial8): 4 on the axes at the radius r with the
// Gaussian weight g1 = exp(-0.66), 4 on the diagonals at r / 2 with g2 = exp(-0.66 / 4),
// rotated by one angle in [0, pi/2) per group of 16 pixels. For the pixel just left of a
// vertical edge (centre 0.5 px from it) a tap crosses where its x offset is >= 0.5: of the
// axis taps' offsets {r c, -r c, -r s, r s} and the diagonals' r/(2 sqrt 2) {c - s, -c - s,
// c + s, s - c} (c, s >= 0) at most two each are positive, so the crossing taps' Gaussians sum
// to G_B <= GB = 2 g1 + 2 g2, of a total G = 4 g1 + 4 g2; where r >= 1 at least one axis tap
// crosses (max(c, s) r >= r / sqrt 2 > 0.5), so G_B >= g1.
//
// Both sides flat and constant (a on the pixel's side, b across), every weight other than the
// edge's factor is 1 (same plane, normal, roughness and hit distance on each side), and the
// result is (a (1 + G - G_B) + b w G_B) / (1 + G - G_B + w G_B), with w the edge factor of the
// crossing taps (1 without the edge: the control). Its pull toward b, as a share of b - a:
//   control   f_c = G_B / (1 + G)                      >= g1 / (1 + G) ~ 0.080
//   edge      f_e = w G_B / (1 + G - G_B + w G_B)      <= w (1 + G) / (1 + G - GB) f_c
// with the same taps in both runs (the group's radius and rotation do not depend on the other
// side: the edge is on a group boundary). So the edge test's bound is w x 1.73 x the control's
// own pull, plus float rounding, where w is the edge factor from reblur_math.h's formulas.

constexpr int kEdge = 32;  // the first pixel of side B (a multiple of the 16-pixel group)
constexpr float kRadius = 4.0f;
constexpr float kSideA = 0.2f, kSideB = 1.0f;
constexpr float kFramesSpatial = 3.0f;  // the pixels' accumulation speed (alpha = 1/4)

const double kG1 = std::exp(-0.66), kG2 = std::exp(-0.66 / 4.0);
const double kGTotal = 4.0 * kG1 + 4.0 * kG2, kGCross = 2.0 * kG1 + 2.0 * kG2;

enum class Edge { Plane, Normal, Roughness, HitDistance };

// The weight every tap across the edge gets from the edge's own factor (reblur_math.h and
// spatial_kernel.cpp's spatialPixel / spatialFilter, with the settings' defaults).
double edgeFactor(Edge e, double fractionScale) {
    const DenoiseSettings s;
    const double alpha = 1.0 / (1.0 + kFramesSpatial);
    switch (e) {
        case Edge::Plane: {  // depth 2 against 3 on planes facing the camera: t = dz / (p f z)
            const double t = 1.0 / (double(s.planeDistanceSensitivity) * 1.0 * 2.0);
            return weightNonExp(t);
        }
        case Edge::Normal: {  // diffuse (r = 1), normals 90 degrees apart
            const double lobe2 = double(s.lobeAngleFraction) * s.lobeAngleFraction;
            const double percent = 0.75 * lerp(lobe2, 1.0, alpha);
            const double angle =
                std::max(std::atan(std::sqrt(percent / ((1.0 - percent) + 1e-6))), 0.5 / 255.0);
            const double acosApprox = std::sqrt(2.0) * std::sqrt(1.0 - 0.0);
            return weightNonExp(acosApprox / (angle * fractionScale));
        }
        case Edge::Roughness: {  // specular, the centre 0.9 rough, across 0.1
            const double r = 0.9;
            const double scale =
                1.0 /
                lerp(0.01, 1.0,
                     std::clamp(r * std::min(1.0, s.roughnessFraction * fractionScale), 0.0, 1.0));
            return weightNonExp(scale * (0.1 - r));
        }
        case Edge::HitDistance: {  // diffuse (magic curve 1), normalised hits 0.05 against 0.95
            const double hitScale = 1.0 / lerp(0.0005, 1.0, std::min(alpha, 1.0));
            const double minHit = s.minHitDistanceWeight * fractionScale;
            return lerp(minHit, 1.0, weightExp(hitScale * (0.95 - 0.05)));
        }
    }
    return 1.0;
}

// Runs one spatial pass over a two-sided frame (side A left of kEdge, side B right of it);
// `edge` false: the same frame with side B's guides equal to side A's (the control).
Signal runSpatialEdge(Isa isa, Edge e, bool edge, ReblurSpatial pass, uint32_t frameIndex) {
    Guides g;
    const bool specular = e == Edge::Roughness;
    Signal in(kSideA), out(-1.0f);
    in.p[3].fill(0.5f);
    g.roughness.fill(0.9f);
    PlaneF frames(kWidth, kHeight, kFramesSpatial);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const bool sideB = x >= kEdge;
            if (sideB) in.setRgb(x, y, kSideB);
            if (e == Edge::HitDistance) in.p[3].at(x, y) = sideB ? 0.95f : 0.05f;
            if (!edge || !sideB) continue;
            switch (e) {
                case Edge::Plane: g.setDepth(x, y, 3.0f); break;
                case Edge::Normal:
                    g.normal[0].at(x, y) = 1.0f;  // facing +x: 90 degrees from side A's
                    g.normal[2].at(x, y) = 0.0f;
                    break;
                case Edge::Roughness: g.roughness.at(x, y) = 0.1f; break;
                case Edge::HitDistance: break;
            }
        }
    // Without the edge, side B's hit distance is side A's.
    if (!edge && e == Edge::HitDistance) in.p[3].fill(0.05f);
    ReblurPassArgs a;
    a.frame = g.view();
    a.pass = pass;
    a.specular = specular;
    for (int c = 0; c < 4; ++c) a.in[c] = in.in(c), a.out[c] = out.out(c);
    a.frames = frames.row(0);
    a.frame.frameIndex = frameIndex;
    a.stream = 7;
    // The radius and its floor alike: every pixel's radius is kRadius (for the 0.9-rough
    // specular pixel, between the floor x its magic curve, 0.97, and kRadius).
    a.radius = a.frame.minBlurRadius = kRadius;
    a.fractionScale = pass == ReblurSpatial::PostBlur ? 0.5f : 1.0f;
    const auto fn = SSRT_DISPATCH(isa, reblurSpatialTile);
    forEachTile([&](int t) { fn(a, t); });
    return out;
}

}  // namespace

TEST_CASE("reblur behaviour: the spatial weights stop at plane, normal, roughness and hit edges") {
    const std::string names[] = {"plane", "normal", "roughness", "hit distance"};
    const double crossBound = (1.0 + kGTotal) / (1.0 + kGTotal - kGCross);  // ~1.73
    const double controlFloor = kG1 / (1.0 + kGTotal);                      // ~0.080
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        for (const Edge e : {Edge::Plane, Edge::Normal, Edge::Roughness, Edge::HitDistance}) {
            for (const ReblurSpatial pass : {ReblurSpatial::Blur, ReblurSpatial::PostBlur}) {
                const double fs = pass == ReblurSpatial::PostBlur ? 0.5 : 1.0;
                const double w = edgeFactor(e, fs);
                CAPTURE(names[int(e)]);
                CAPTURE(fs);
                CAPTURE(w);
                // The weights stop: the first three cut to exactly 0, the hit distance's to its
                // floor (minHitDistanceWeight) and a little over.
                CHECK(w <= 0.11);
                for (uint32_t frame = 0; frame < 4; ++frame) {
                    CAPTURE(frame);
                    const Signal withEdge = runSpatialEdge(isa, e, true, pass, frame);
                    const Signal control = runSpatialEdge(isa, e, false, pass, frame);
                    // Rows whose taps (at most kRadius up or down) stay in the frame.
                    int blended = 0, stopped = 0, rows = 0;
                    for (int y = 6; y < kHeight - 6; ++y) {
                        const int x = kEdge - 1;  // side A, next to the edge
                        for (int c = 0; c < 3; ++c) {
                            const double pullC =
                                (control.p[c].at(x, y) - kSideA) / (kSideB - kSideA);
                            const double pullE =
                                (withEdge.p[c].at(x, y) - kSideA) / (kSideB - kSideA);
                            blended += pullC >= 0.999 * controlFloor;
                            stopped += pullE <= w * crossBound * pullC + 1.0e-5;
                        }
                        ++rows;
                    }
                    CHECK(blended == 3 * rows);  // the control takes side B's value in
                    CHECK(stopped == 3 * rows);  // the edge keeps it out
                }
            }
        }
    }
}

namespace {

// ---------------------------------------------------------------------------------------
// The temporal pass (diffuse: no parallax or virtual motion), on a still camera.

// The previous frame's planes and this frame's, wired into the temporal kernel's arguments.
struct Temporal {
    Guides g;
    PlaneF motion[2] = {PlaneF(kWidth, kHeight, 0.0f), PlaneF(kWidth, kHeight, 0.0f)};
    Signal in, out{-1.0f}, previous;
    PlaneF prevViewZ{kWidth, kHeight, 2.0f};
    PlaneF prevFrames{kWidth, kHeight, 0.0f}, prevFast{kWidth, kHeight, 0.0f};
    PlaneF outFrames{kWidth, kHeight, -1.0f}, outFast{kWidth, kHeight, -1.0f};
    DenoiseSettings s;

    // One frame over every tile; `history` false: none (the first frame).
    void run(Isa isa, bool history = true) {
        ReblurPassArgs a;
        a.frame = g.view();
        a.specular = false;
        a.frame.motion[0] = motion[0].row(0), a.frame.motion[1] = motion[1].row(0);
        for (int c = 0; c < 4; ++c) a.in[c] = in.in(c), a.out[c] = out.out(c);
        a.outFrames = outFrames.row(0);
        a.outFast = outFast.row(0);
        if (history) {
            a.frame.prev.viewZ = prevViewZ.row(0);
            for (int i = 0; i < 3; ++i) a.frame.prev.normal[i] = g.normal[i].row(0);
            a.frame.prev.roughness = g.roughness.row(0);
            for (int c = 0; c < 4; ++c) a.prevSignal[c] = previous.in(c);
            a.prevFrames = prevFrames.row(0);
            a.prevFast = prevFast.row(0);
            for (int i = 0; i < 9; i += 4) a.frame.prevViewToWorld[i] = 1.0f;
            a.frame.prevTanHalfX = a.frame.tanHalfX;
            a.frame.prevTanHalfY = a.frame.tanHalfY;
        }
        // As denoise.cpp fills them from the settings.
        a.frame.maxAccumulatedFrames = float(s.maxAccumulatedFrames);
        a.frame.maxFastAccumulatedFrames = float(s.maxFastAccumulatedFrames);
        a.frame.disocclusion = s.disocclusionThreshold;
        a.frame.fireflyScale = s.fireflyMinRelativeScale;
        const auto fn = SSRT_DISPATCH(isa, reblurTemporalTile);
        forEachTile([&](int t) { fn(a, t); });
    }
    // This frame's result becomes the next one's history (denoise.cpp's commitHistory: the
    // speed + 1, the fast luma as it is).
    void commit() {
        for (int c = 0; c < 4; ++c) previous.p[c] = out.p[c].clone();
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) prevFrames.at(x, y) = outFrames.at(x, y) + 1.0f;
        prevFast = outFast.clone();
    }
};

// Catmull-Rom weights at fraction t (Keys' cubic convolution, a = -0.5).
void catmullRomWeights(double t, double w[4]) {
    const auto k = [](double x) {
        x = std::abs(x);
        return x < 1.0 ? 1.5 * x * x * x - 2.5 * x * x + 1.0
                       : (x < 2.0 ? -0.5 * x * x * x + 2.5 * x * x - 4.0 * x + 2.0 : 0.0);
    };
    for (int i = 0; i < 4; ++i) w[i] = k(t + 1.0 - double(i));
}

}  // namespace

TEST_CASE(
    "reblur behaviour: the history read is Catmull-Rom where whole, bilinear by an occluded tap") {
    // A sub-pixel motion of (0.3, -0.2) pixels over a history with curvature: a parabola in R,
    // sharp steps in G (across x) and B (across y). Catmull-Rom reproduces the parabola and
    // undershoots at the steps where bilinear does not: the two reads differ by 0.002 (R, the
    // parabola's 0.01 fx (1 - fx)) to a few hundredths (G, B, next to the steps).
    // (ssrt's Catmull-Rom takes all 16 taps, so an occluded corner also falls back to bilinear;
    // NRD's BicubicFilterNoCorners drops the corners. A rewrite that follows NRD there changes
    // the 4 corner places of this test, knowingly.)
    constexpr float kMotionX = 0.3f, kMotionY = -0.2f;
    const int occX = 41, occY = 22;  // the history pixel whose depth is far off
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        Temporal t;
        t.motion[0].fill(kMotionX);
        t.motion[1].fill(kMotionY);
        t.in = Signal(0.0f);  // this frame's radiance 0: the result is the history x (1 - alpha)
        t.in.p[3].fill(0.5f);
        t.previous = Signal(0.0f);
        t.previous.p[3].fill(0.5f);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                t.previous.p[0].at(x, y) = 0.2f + 0.01f * float((x - 40) * (x - 40));
                t.previous.p[1].at(x, y) = x >= 40 ? 1.0f : 0.2f;
                t.previous.p[2].at(x, y) = y >= 24 ? 0.9f : 0.3f;
            }
        const float kFrames = 20.0f;  // the history's speed (quality 1: the read keeps it)
        t.prevFrames.fill(kFrames);
        t.prevFast.fill(0.5f);
        t.prevViewZ.at(occX, occY) = 10.0f;  // far behind: fails the occlusion test
        t.run(isa);
        const double alpha = 1.0 / (1.0 + kFrames);
        int catmullRom = 0, bilinear = 0, apart = 0, reported = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                // The read's position in the previous frame and its 4x4 footprint, with the
                // kernel's float steps: q = pixel centre + motion, s = q - 0.5.
                const float sx = ((float(x) + 0.5f) + kMotionX) - 0.5f;
                const float sy = ((float(y) + 0.5f) + kMotionY) - 0.5f;
                const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
                const double fx = double(sx - float(x0)), fy = double(sy - float(y0));
                if (x0 - 1 < 0 || x0 + 2 >= kWidth || y0 - 1 < 0 || y0 + 2 >= kHeight)
                    continue;                              // part of the footprint off the frame
                const int dx = occX - x0, dy = occY - y0;  // the occluded tap's place, -1 .. 2
                const bool inFootprint = dx >= -1 && dx <= 2 && dy >= -1 && dy <= 2;
                const bool inner = (dx == 0 || dx == 1) && (dy == 0 || dy == 1);
                if (inFootprint && inner) continue;  // a partial bilinear: not pinned here
                double wx[4], wy[4];
                catmullRomWeights(fx, wx);
                catmullRomWeights(fy, wy);
                const double bx[2] = {1.0 - fx, fx}, by[2] = {1.0 - fy, fy};
                for (int c = 0; c < 3; ++c) {
                    double cr = 0.0, bil = 0.0;
                    for (int j = 0; j < 4; ++j)
                        for (int i = 0; i < 4; ++i)
                            cr += wy[j] * wx[i] * t.previous.p[c].at(x0 - 1 + i, y0 - 1 + j);
                    for (int j = 0; j < 2; ++j)
                        for (int i = 0; i < 2; ++i)
                            bil += by[j] * bx[i] * t.previous.p[c].at(x0 + i, y0 + j);
                    cr = std::max(cr, 0.0);  // the kernel keeps radiance >= 0
                    const double want = (inFootprint ? bil : cr) * (1.0 - alpha);
                    const double got = t.out.p[c].at(x, y);
                    // Float rounding of a 16-tap sum of values <= 2.
                    const bool ok = std::abs(got - want) <= 2.0e-6 * (1.0 + std::abs(want));
                    if (!ok && reported++ < 3) {  // the first few, not every pixel
                        INFO("pixel (" << x << ", " << y << ") channel " << c
                                       << std::string(inFootprint ? ": bilinear expected"
                                                                  : ": Catmull-Rom expected")
                                       << "; Catmull-Rom " << cr * (1.0 - alpha) << ", bilinear "
                                       << bil * (1.0 - alpha));
                        CHECK(got == doctest::Approx(want));
                    }
                    (inFootprint ? bilinear : catmullRom) += ok;
                    apart += std::abs(cr - bil) * (1.0 - alpha) > 1.0e-3;
                }
            }
        // Both reads were seen, and told apart (the two filters differ by far more than the
        // tolerance at many pixels).
        CHECK(catmullRom > 2000);
        CHECK(bilinear == 3 * (16 - 4));  // the 12 outer places of the occluded tap, 3 channels
        CHECK(apart > 300);
    }
}

TEST_CASE("reblur behaviour: the fast history follows a step within its capped window") {
    // A grey signal, still camera: 40 frames at 1 (the speed reaches its cap, 30), then 2.
    // The slow history is an exponential moving average with weight 1 / (1 + min(n, 30)) for
    // the n-th frame of history, the fast one the same with min(n, 6): after the step each is
    // left (1 - 1/(1 + cap))^k of the step behind after k frames, so the fast history comes
    // within 10 % of the new value after ceil(ln 0.1 / ln(6/7)) = 15 frames, the slow one only
    // after ceil(ln 0.1 / ln(30/31)) = 71.
    const DenoiseSettings defaults;
    CHECK(defaults.maxFastAccumulatedFrames == 6);  // REBLUR's maxFastAccumulatedFrameNum
    const int slowCap = defaults.maxAccumulatedFrames, fastCap = defaults.maxFastAccumulatedFrames;
    const int stepAt = 40, frames = stepAt + 90;
    const auto within = [](double cap) {
        return int(std::ceil(std::log(0.1) / std::log(1.0 - 1.0 / (1.0 + cap))));
    };
    const int fastWindow = within(fastCap), slowWindow = within(slowCap);
    CHECK(fastWindow == 15);
    CHECK(slowWindow == 71);
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        Temporal t;
        double slow = 0.0, fast = 0.0;  // the model
        std::vector<double> fastSeen, slowSeen;
        for (int f = 0; f < frames; ++f) {
            const float v = f < stepAt ? 1.0f : 2.0f;
            t.in = Signal(v);
            t.in.p[3].fill(0.5f);
            t.run(isa, f > 0);
            if (f == 0) {
                slow = fast = v;  // no history: the sample itself
            } else {              // the f-th frame of history, capped
                const double speed = std::min(f, slowCap);
                slow = lerp(slow, v, 1.0 / (1.0 + speed));
                fast = lerp(fast, v, 1.0 / (1.0 + std::min(speed, double(fastCap))));
            }
            t.commit();
            const double gotSlow =
                luma(t.out.p[0].at(40, 24), t.out.p[1].at(40, 24), t.out.p[2].at(40, 24));
            const double gotFast = t.outFast.at(40, 24);
            CAPTURE(f);
            CHECK(t.outFrames.at(40, 24) == float(std::min(f, slowCap)));
            CHECK(gotSlow == doctest::Approx(slow).epsilon(1.0e-5));
            CHECK(gotFast == doctest::Approx(fast).epsilon(1.0e-5));
            fastSeen.push_back(gotFast);
            slowSeen.push_back(gotSlow);
        }
        // Behind the step by a share of it (1) after k frames of the new value.
        const auto behind = [&](const std::vector<double>& seen, int k) {
            return 2.0 - seen[std::size_t(stepAt + k - 1)];
        };
        CHECK(behind(fastSeen, fastWindow) <= 0.1);
        CHECK(behind(fastSeen, fastWindow - 1) > 0.1);
        CHECK(behind(slowSeen, fastWindow) > 0.5);  // the slow one still over half a step behind
        CHECK(behind(slowSeen, slowWindow) <= 0.1);
        CHECK(behind(slowSeen, slowWindow - 1) > 0.1);
    }
}

namespace {

// ---------------------------------------------------------------------------------------
// The history fix (diffuse), on the flat wall: every plane-distance and normal weight is 1.

struct HistoryFix {
    Guides g;
    Signal in, out{-1.0f};
    PlaneF frames{kWidth, kHeight, 0.0f}, fast{kWidth, kHeight, 0.0f};

    void run(Isa isa, bool clamp) {
        const DenoiseSettings s;
        ReblurPassArgs a;
        a.frame = g.view();
        a.specular = false;
        for (int c = 0; c < 4; ++c) a.in[c] = in.in(c), a.out[c] = out.out(c);
        a.frames = frames.row(0);
        a.fast = clamp ? fast.row(0) : nullptr;  // null: denoise.cpp's "clamp off"
        a.frame.historyFixFrames = float(s.historyFixFrames);
        a.frame.historyFixStride = float(s.historyFixStride);
        a.frame.lobeFraction2 = s.lobeAngleFraction * s.lobeAngleFraction;
        a.frame.planeDistance = s.planeDistanceSensitivity;
        const auto fn = SSRT_DISPATCH(isa, reblurHistoryFixTile);
        forEachTile([&](int t) { fn(a, t); });
    }
};

// Noise in [1, 2) per pixel and channel.
float noise(int x, int y, int c) { return 1.0f + randomFloat(uint32_t(y * kWidth + x), 0, 3, c); }

}  // namespace

TEST_CASE("reblur behaviour: the history fix widens young pixels' reconstruction") {
    // A pixel with F < historyFixFrames (3) frames of history is replaced by the mean of
    // itself (weight 1 + F) and 20 taps of a 5x5 without its corners, `stride` pixels apart,
    // each weighted by 1 + its own F (plane and normal weights are 1 on the flat wall):
    // stride = max(1, floor(historyFixStride / (2 + F))) = 7, 4, 3 for F = 0, 1, 2 (the
    // diffuse magic curve is 1). Older pixels are left as they are.
    const DenoiseSettings s;
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        HistoryFix h;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                for (int c = 0; c < 4; ++c) h.in.p[c].at(x, y) = noise(x, y, c);
                h.in.p[3].at(x, y) *= 0.4f;  // a normalised hit distance in [0.4, 0.8)
                h.frames.at(x, y) = float((x + 2 * y) % 5);  // 0 .. 4
            }
        h.run(isa, false);
        int young = 0, old = 0, reported = 0;
        double spreadYoung = 0.0, spreadIn = 0.0;  // mean |value - 1.5| of young pixels (R)
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const int f = int(h.frames.at(x, y));
                if (f >= s.historyFixFrames) {
                    bool same = true;
                    for (int c = 0; c < 4; ++c) same &= h.out.p[c].at(x, y) == h.in.p[c].at(x, y);
                    old += same;
                    continue;
                }
                const int stride = std::max(1, s.historyFixStride / (2 + f));
                double sum[4], weightSum = 1.0 + f;
                for (int c = 0; c < 4; ++c) sum[c] = weightSum * h.in.p[c].at(x, y);
                for (int j = -2; j <= 2; ++j)
                    for (int i = -2; i <= 2; ++i) {
                        if ((i == 0 && j == 0) || (std::abs(i) == 2 && std::abs(j) == 2)) continue;
                        const int tx = x + i * stride, ty = y + j * stride;
                        if (tx < 0 || tx >= kWidth || ty < 0 || ty >= kHeight) continue;
                        const double w = 1.0 + h.frames.at(tx, ty);
                        for (int c = 0; c < 4; ++c) sum[c] += w * h.in.p[c].at(tx, ty);
                        weightSum += w;
                    }
                bool ok = true;
                for (int c = 0; c < 4; ++c) {
                    const double want = sum[c] / weightSum;
                    const double got = h.out.p[c].at(x, y);
                    ok &= std::abs(got - want) <= 2.0e-6 * want;  // a float sum of 21 terms
                    if (std::abs(got - want) > 2.0e-6 * want && reported++ < 3) {
                        INFO("pixel (" << x << ", " << y << ") F " << f << " stride " << stride
                                       << " channel " << c);
                        CHECK(got == doctest::Approx(want));
                    }
                }
                young += ok;
                spreadYoung += std::abs(h.out.p[0].at(x, y) - 1.5);
                spreadIn += std::abs(h.in.p[0].at(x, y) - 1.5);
            }
        CHECK(young == kWidth * kHeight * 3 / 5);  // F = 0, 1, 2: three in five pixels
        CHECK(old == kWidth * kHeight * 2 / 5);
        // The wide average took the noise down (uniform noise about 1.5: mean deviation 0.25).
        CHECK(spreadYoung < 0.5 * spreadIn);
    }
}

TEST_CASE("reblur behaviour: the history fix clamps the slow history to the fast one") {
    // After a step up, the slow history's luma (y0 = 1) lags the fast history's (about 2).
    // The fast luma's 5x5 mean m and deviation sigma bound it: y0 is clamped to
    // [m - 2 sigma, m + 2 sigma], and the result is lerp(clamped, y0, 1 / (1 + 2 F)) for a
    // pixel with F frames of history; RGB is scaled by (y1 + 1e-6) / (y0 + 1e-6). Without the
    // fast history (denoise.cpp hands none when maxFastAccumulatedFrames >=
    // maxAccumulatedFrames) the history is left as it is.
    const DenoiseSettings s;
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        HistoryFix h;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                // Colour with luma 1 (left half) or 2 (right: inside the fast history's band).
                const float k = x < kWidth / 2 ? 1.0f : 2.0f;
                h.in.p[0].at(x, y) = 0.8f * k, h.in.p[1].at(x, y) = 1.0f * k;
                h.in.p[2].at(x, y) = 1.2f * k, h.in.p[3].at(x, y) = 0.5f;
                h.fast.at(x, y) = 2.0f + 0.1f * float((x + 2 * y) % 3 - 1);
                h.frames.at(x, y) = float(s.historyFixFrames + (x + y) % 20);  // old: no fix
            }
        h.run(isa, false);
        bool unclamped = true;
        for (int c = 0; c < 4; ++c)
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x)
                    unclamped &= h.out.p[c].at(x, y) == h.in.p[c].at(x, y);
        CHECK(unclamped);
        h.run(isa, true);
        int clamped = 0, kept = 0, pulled = 0, reported = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                double m1 = 0.0, m2 = 0.0, n = 0.0;
                for (int j = -2; j <= 2; ++j)
                    for (int i = -2; i <= 2; ++i) {
                        const int tx = x + i, ty = y + j;
                        if (tx < 0 || tx >= kWidth || ty < 0 || ty >= kHeight) continue;
                        const double f = h.fast.at(tx, ty);
                        m1 += f, m2 += f * f, n += 1.0;
                    }
                m1 /= n;
                const double sigma = std::sqrt(std::max(m2 / n - m1 * m1, 0.0));
                const double y0 = luma(h.in.p[0].at(x, y), h.in.p[1].at(x, y), h.in.p[2].at(x, y));
                const double bounded = std::clamp(y0, m1 - 2.0 * sigma, m1 + 2.0 * sigma);
                const double frames = h.frames.at(x, y);
                const double y1 = lerp(bounded, y0, 1.0 / (1.0 + 2.0 * frames));
                const double scale = (y1 + 1.0e-6) / (y0 + 1.0e-6);
                // Float: sigma from m2 - m1^2 near 4 loses ~1e-6 x 4 / sigma^2 of itself.
                bool ok = h.out.p[3].at(x, y) == h.in.p[3].at(x, y);
                for (int c = 0; c < 3; ++c) {
                    const double want = h.in.p[c].at(x, y) * scale;
                    const double got = h.out.p[c].at(x, y);
                    ok &= std::abs(got - want) <= 1.0e-4;
                    if (std::abs(got - want) > 1.0e-4 && reported++ < 3) {
                        INFO("pixel (" << x << ", " << y << ") channel " << c << " y0 " << y0
                                       << " band " << m1 - 2.0 * sigma << " .. "
                                       << m1 + 2.0 * sigma);
                        CHECK(got == doctest::Approx(want));
                    }
                }
                if (bounded != y0) {
                    clamped += ok;
                    // Pulled most of the way to the band: y1 - y0 >= (1 - 1/7) of the gap.
                    pulled +=
                        (y1 - y0) >=
                        (1.0 - 1.0 / (1.0 + 2.0 * s.historyFixFrames)) * (bounded - y0) - 1.0e-9;
                } else {
                    kept += ok;
                }
            }
        CHECK(clamped == kWidth * kHeight / 2);  // the lagging half
        CHECK(pulled == kWidth * kHeight / 2);
        CHECK(kept == kWidth * kHeight / 2);  // inside the band: as it was
    }
}

TEST_CASE(
    "reblur behaviour: the firefly suppressor holds a new sample to a multiple of its history") {
    // The temporal pass's suppressor (REBLUR's, against the pixel's own history, not its
    // neighbourhood): a sample of luma L over a history of luma H with F frames enters as
    //   L' = lerp(L, min(L, H m), k),  m = fireflyMinRelativeScale + 38 / (F + 1),
    //   k = 3F / (1 + 3F),
    // its RGB scaled by (L' + 1e-6) / (L + 1e-6), and then averaged in with 1 / (1 + F). With
    // F = 10, m = 5.45 and k = 30/31: a sample 1000x its history enters at most
    // (1 - k) 1000 + k m = 37.5x it (not 1000x), and the result is under 4.4x the history
    // (without the suppressor, 91.8x). A sample under m times its history enters as it is,
    // and a pixel whose history is as bright is kept.
    constexpr float kLow = 0.1f, kFrames = 10.0f;
    const int fx = 40, fy = 24;  // the firefly, 1000x
    const int mx = 20, my = 24;  // 1.5x its history: under m
    const int bx = 60, by = 24;  // as bright as its history: a bright pixel that stays
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        Temporal t;
        const double m = t.s.fireflyMinRelativeScale + 38.0 / (kFrames + 1.0);
        const double k = 3.0 * kFrames / (1.0 + 3.0 * kFrames);
        const double alpha = 1.0 / (1.0 + kFrames);
        t.in = Signal(kLow);
        t.in.p[3].fill(0.5f);
        t.previous = Signal(kLow);
        t.previous.p[3].fill(0.5f);
        t.prevFrames.fill(kFrames);
        t.prevFast.fill(kLow);
        t.in.setRgb(fx, fy, 1000.0f * kLow);
        t.in.setRgb(mx, my, 1.5f * kLow);
        t.in.setRgb(bx, by, 1000.0f * kLow);
        t.previous.setRgb(bx, by, 1000.0f * kLow);
        t.run(isa);
        const auto expected = [&](double sample, double history) {
            const double kept = lerp(sample, std::min(sample, history * m), k);
            const double scale = (kept + 1.0e-6) / (sample + 1.0e-6);
            return lerp(history, sample * scale, alpha);
        };
        const double firefly = t.out.p[1].at(fx, fy);
        CHECK(firefly == doctest::Approx(expected(1000.0 * kLow, kLow)).epsilon(1.0e-5));
        const double bound = kLow * ((1.0 - alpha) + alpha * ((1.0 - k) * 1000.0 + k * m));
        CHECK(firefly <= bound * (1.0 + 1.0e-5));
        CHECK(bound < 4.4 * kLow);
        CHECK(t.out.p[1].at(mx, my) ==
              doctest::Approx(lerp(kLow, 1.5 * kLow, alpha)).epsilon(1.0e-5));
        CHECK(t.out.p[1].at(bx, by) == doctest::Approx(1000.0 * kLow).epsilon(1.0e-5));
        CHECK(t.out.p[1].at(fx + 2, fy) == doctest::Approx(kLow).epsilon(1.0e-5));
    }
}
