// The reconstruction of a trace layout's untraced pixels (trace/reconstruct.h): constant
// signals stay constant, depth edges do not bleed, every ISA and thread count gives the
// same bits.
#include "trace/reconstruct.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/isa.h"
#include "thread_counts.h"
#include "trace/trace_layout.h"

using namespace ssrt;

namespace {

// A w x h frame looking down -z at a plane z = near facing the camera; columns from
// `edgeX` on are a second plane at z = far (a depth edge). Normals +z (world = view).
struct Scene2 {
    int w, h;
    TraceCamera camera;
    PlaneF viewZ, normal[3];
    Scene2(int w_, int h_, int edgeX, float nearZ, float farZ) : w(w_), h(h_) {
        camera.width = w;
        camera.height = h;
        camera.tanHalfX = 0.5f;
        camera.tanHalfY = 0.5f * float(h) / float(w);
        viewZ = PlaneF(w, h);
        for (PlaneF& n : normal) n = PlaneF(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                viewZ.at(x, y) = x < edgeX ? nearZ : farZ;
                normal[2].at(x, y) = 1.0f;
            }
    }
    ReconstructGuides guides() const {
        return {camera, gbufferView("test", w, h,
                                    {{kGViewZ, &viewZ},
                                     {kGNormalX, &normal[0]},
                                     {kGNormalY, &normal[1]},
                                     {kGNormalZ, &normal[2]}})};
    }
};

struct Signal {
    PlaneF color[3], opacity, hit, dist;
    Signal(int w, int h) {
        for (PlaneF& c : color) c = PlaneF(w, h);
        opacity = PlaneF(w, h), hit = PlaneF(w, h), dist = PlaneF(w, h);
    }
    Signal clone() const {
        Signal s(1, 1);
        for (int c = 0; c < 3; ++c) s.color[c] = color[c].clone();
        s.opacity = opacity.clone(), s.hit = hit.clone(), s.dist = dist.clone();
        return s;
    }
    ReconstructPlanes planes(bool withOpacity) {
        return {{&color[0], &color[1], &color[2]}, withOpacity ? &opacity : nullptr, &hit, &dist};
    }
};

// Equal but for the rounding of a weighted mean (sum w c / sum w need not be c to the bit).
bool near(float a, float b) { return std::fabs(a - b) <= 1e-6f * std::fabs(b); }

// The value a pixel of plane `near` or `far` carries.
float valueOf(bool nearSide, int ch) { return nearSide ? 0.25f + 0.1f * float(ch) : 3.0f; }

// A checkerboard frame: traced pixels carry their side's values, cut ones poison (NaN).
void makeCheckerboard(const Scene2& s, int edgeX, uint32_t frame, PlaneF& pdf, Signal& sig) {
    pdf = PlaneF(s.w, s.h);
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) {
            const bool traced = checkerboardTraced(x, y, frame, kSsgiCheckerboardPhase);
            pdf.at(x, y) = traced ? 0.5f : kPdfLayoutCut;
            const float nan = std::nanf("");
            for (int c = 0; c < 3; ++c)
                sig.color[c].at(x, y) = traced ? valueOf(x < edgeX, c) : nan;
            sig.opacity.at(x, y) = traced ? 0.8f : nan;
            sig.hit.at(x, y) = traced ? 1.0f : nan;
            sig.dist.at(x, y) = traced ? (x < edgeX ? 2.0f : 5.0f) : nan;
        }
}

bool samePlanes(const Signal& a, const Signal& b) {
    const PlaneF* pa[6] = {&a.color[0], &a.color[1], &a.color[2], &a.opacity, &a.hit, &a.dist};
    const PlaneF* pb[6] = {&b.color[0], &b.color[1], &b.color[2], &b.opacity, &b.hit, &b.dist};
    for (int p = 0; p < 6; ++p)
        for (int y = 0; y < pa[p]->height(); ++y)
            if (std::memcmp(pa[p]->row(y), pb[p]->row(y), std::size_t(pa[p]->width()) * 4) != 0)
                return false;
    return true;
}

}  // namespace

TEST_CASE("reconstruct: checkerboard fill keeps a constant signal and every cut pixel filled") {
    const int w = 77, h = 45;
    const Scene2 s(w, h, w, 4.0f, 4.0f);  // one plane
    for (uint32_t frame : {0u, 1u}) {
        PlaneF pdf;
        Signal sig(w, h);
        makeCheckerboard(s, w, frame, pdf, sig);
        const uint64_t filled = fillCheckerboard(Isa::Scalar, s.guides(), pdf, sig.planes(true), 1);
        uint64_t cut = 0;
        bool constant = true;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                cut += pdf.at(x, y) == kPdfLayoutCut;
                for (int c = 0; c < 3; ++c)
                    constant &= near(sig.color[c].at(x, y), valueOf(true, c));
                constant &= near(sig.opacity.at(x, y), 0.8f) && near(sig.hit.at(x, y), 1.0f) &&
                            near(sig.dist.at(x, y), 2.0f);
            }
        CHECK(filled == cut);
        CHECK(constant);
    }
}

TEST_CASE("reconstruct: checkerboard fill does not bleed across a depth edge") {
    const int w = 64, h = 32, edge = 29;
    const Scene2 s(w, h, edge, 2.0f, 3.0f);  // two planes facing the camera, 50% apart
    PlaneF pdf;
    Signal sig(w, h);
    makeCheckerboard(s, edge, 0, pdf, sig);
    fillCheckerboard(Isa::Scalar, s.guides(), pdf, sig.planes(true), 1);
    bool separate = true;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool nearSide = x < edge;
            for (int c = 0; c < 3; ++c)
                separate &= near(sig.color[c].at(x, y), valueOf(nearSide, c));
            separate &= near(sig.dist.at(x, y), nearSide ? 2.0f : 5.0f);
        }
    CHECK(separate);
}

TEST_CASE("reconstruct: half-resolution upsample keeps constants and depth edges") {
    for (int w : {64, 61}) {
        const int h = w == 64 ? 34 : 33, hw = (w + 1) / 2, hh = (h + 1) / 2, edge = 30;
        const Scene2 s(w, h, edge, 2.0f, 3.0f);
        for (uint32_t frame = 0; frame < 4; ++frame) {
            CAPTURE(w);
            CAPTURE(frame);
            const PixelOffset o = halfOffset(frame);
            // The half frame as buildHalfFrame leaves it: each half pixel its chosen pixel's.
            PlaneF pdf(hw, hh, 0.5f), col[3] = {PlaneF(hw, hh), PlaneF(hw, hh), PlaneF(hw, hh)};
            PlaneF hit(hw, hh), dist(hw, hh), steps(hw, hh);
            for (int hy = 0; hy < hh; ++hy)
                for (int hx = 0; hx < hw; ++hx) {
                    const PixelOffset src = halfSource(hx, hy, o, w, h);
                    const bool nearSide = src.x < edge;
                    for (int c = 0; c < 3; ++c) col[c].at(hx, hy) = valueOf(nearSide, c);
                    hit.at(hx, hy) = 1.0f;
                    dist.at(hx, hy) = nearSide ? 2.0f : 5.0f;
                    steps.at(hx, hy) = 7.0f;
                }
            Signal out(1, 1);
            PlaneF outSteps;
            const ReconstructSource in{{&col[0], &col[1], &col[2]}, nullptr, &hit, &dist, &steps};
            ReconstructPlanes to = out.planes(false);
            to.steps = &outSteps;
            const uint64_t blended = upsampleHalf(Isa::Scalar, s.guides(), o, pdf, in, to, 1);
            bool separate = true, stepsAtChosen = true;
            uint64_t chosen = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const bool nearSide = x < edge;
                    for (int c = 0; c < 3; ++c)
                        separate &= near(out.color[c].at(x, y), valueOf(nearSide, c));
                    separate &= near(out.dist.at(x, y), nearSide ? 2.0f : 5.0f) &&
                                near(out.hit.at(x, y), 1.0f);
                    const PixelOffset src = halfSource(x / 2, y / 2, o, w, h);
                    const bool own = src.x == x && src.y == y;
                    chosen += own;
                    stepsAtChosen &= outSteps.at(x, y) == (own ? 7.0f : 0.0f);
                }
            CHECK(separate);
            CHECK(stepsAtChosen);
            CHECK(blended == uint64_t(w * h) - chosen);
        }
    }
}

TEST_CASE("reconstruct: the same bits for every ISA and thread count") {
    const int w = 150, h = 70;
    Scene2 s(w, h, 77, 2.0f, 2.5f);
    // Some structure: a tilted second plane and noisy normals, a hole of background.
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (x >= 77) s.viewZ.at(x, y) = 2.5f + 0.01f * float(x - 77);
            s.normal[0].at(x, y) = 0.2f * std::sin(0.37f * float(x * y));
            s.normal[2].at(x, y) = std::sqrt(1.0f - s.normal[0].at(x, y) * s.normal[0].at(x, y));
            if (x > 20 && x < 26 && y > 10 && y < 40) s.viewZ.at(x, y) = 0.0f;
        }
    PlaneF pdf;
    Signal ref(w, h);
    makeCheckerboard(s, 77, 1, pdf, ref);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (pdf.at(x, y) > 0.0f) ref.color[1].at(x, y) += 0.01f * float((x * 7 + y * 3) % 11);
    const Signal base = ref.clone();
    fillCheckerboard(Isa::Scalar, s.guides(), pdf, ref.planes(true), 1);
    for (Isa isa : supportedIsas())
        for (int threads : testThreadCounts({1, 2, 8})) {
            const std::string isaStr(isaName(isa));
            CAPTURE(isaStr);
            CAPTURE(threads);
            Signal got = base.clone();
            fillCheckerboard(isa, s.guides(), pdf, got.planes(true), threads);
            CHECK(samePlanes(got, ref));
        }
}

TEST_CASE("reconstruct: a thinned checkerboard's cut pixels are filled from their diagonals") {
    // The left half thinned (trace/trace_layout.h, sparseBlockPick): of a block's two traced
    // pixels only the pick carries a value; the unpicked one has no traced edge neighbour.
    // Several tiles each way, so that tiles meet at corners.
    const int w = 150, h = 140;
    const Scene2 s(w, h, w, 4.0f, 4.0f);
    for (uint32_t frame = 0; frame < 4; ++frame) {
        CAPTURE(frame);
        PlaneF pdf;
        Signal sig(w, h);
        makeCheckerboard(s, w, frame, pdf, sig);
        uint64_t cut = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w / 2; ++x)
                if (pdf.at(x, y) > 0.0f && uint32_t(x & 1) != sparseBlockPick(frame)) {
                    pdf.at(x, y) = kPdfLayoutCut;
                    for (PlaneF* p : {&sig.color[0], &sig.color[1], &sig.color[2], &sig.opacity,
                                      &sig.hit, &sig.dist})
                        p->at(x, y) = std::nanf("");
                }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) cut += pdf.at(x, y) == kPdfLayoutCut;
        const Signal base = sig.clone();
        const uint64_t filled = fillCheckerboard(Isa::Scalar, s.guides(), pdf, sig.planes(true), 1);
        bool constant = true;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                for (int c = 0; c < 3; ++c)
                    constant &= near(sig.color[c].at(x, y), valueOf(true, c));
                constant &= near(sig.opacity.at(x, y), 0.8f) && near(sig.dist.at(x, y), 2.0f);
            }
        CHECK(filled == cut);
        CHECK(constant);
        for (Isa isa : supportedIsas())
            for (int threads : testThreadCounts({1, 3})) {
                CAPTURE(std::string(isaName(isa)));
                CAPTURE(threads);
                Signal got = base.clone();
                fillCheckerboard(isa, s.guides(), pdf, got.planes(true), threads);
                CHECK(samePlanes(got, sig));
            }
    }
}
