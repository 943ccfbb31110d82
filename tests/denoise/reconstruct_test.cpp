// The reconstruction of a trace layout's untraced pixels (denoise/reconstruct.h): constant
// signals stay constant, depth edges do not bleed, every ISA and thread count gives the
// same bits.
#include "denoise/reconstruct.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/isa.h"
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
        return {camera, &viewZ, {&normal[0], &normal[1], &normal[2]}};
    }
};

struct Signal {
    PlaneF color[3], opacity, hit, dist;
    Signal(int w, int h) {
        for (PlaneF& c : color) c = PlaneF(w, h);
        opacity = PlaneF(w, h), hit = PlaneF(w, h), dist = PlaneF(w, h);
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
