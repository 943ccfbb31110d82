// The reference against answers known in closed form: a floor under a constant sky (every
// ray escapes: SSR and SSGI are the sky, the sun is unoccluded), and the same floor under an
// emitting ceiling (every ray hits it: SSGI is its emission, the sun is blocked).
#include <doctest/doctest.h>

#include <cmath>

#include "renderer/renderer.h"
#include "truth/reference_image.h"
#include "world/embree_scene.h"

using namespace ssrt;

namespace {

// A square at height y, 2 * half wide, facing up or down (counter-clockwise = front).
Mesh square(float y, float half, bool up) {
    Mesh m;
    m.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
    m.normals.assign(4, {0.0f, up ? 1.0f : -1.0f, 0.0f});
    m.indices =
        up ? std::vector<uint32_t>{0, 2, 1, 0, 3, 2} : std::vector<uint32_t>{0, 1, 2, 0, 2, 3};
    return m;
}

// The floor's options: an emitting ceiling over it, a gradient sky instead of the constant.
struct FloorOptions {
    bool ceiling = false;
    bool gradientSky = false;
    float roughness = 0.3f;
    SsrMethod method = SsrMethod::VndfBounded;
    int spp = 8;
};

Scene floorScene(const FloorOptions& o) {
    Scene s;
    s.meshes.push_back(square(0.0f, 1000.0f, true));
    Material floor;
    floor.roughness = o.roughness;
    s.materials.push_back(floor);
    s.instances.push_back(Instance{});
    if (o.ceiling) {
        s.meshes.push_back(square(1.0f, 1000.0f, false));
        Material glow;
        glow.baseColor = glm::vec3(0.0f);
        glow.emissive = {0.5f, 1.0f, 2.0f};
        s.materials.push_back(glow);
        Instance i;
        i.mesh = 1;
        i.material = 1;
        s.instances.push_back(i);
    }
    s.sky.kind = o.gradientSky ? Sky::Kind::Gradient : Sky::Kind::Constant;
    s.sky.zenith = {0.2f, 0.4f, 0.8f};
    s.sky.intensity = 1.0f;
    s.light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    s.camera.position = {0.0f, 0.5f, 2.0f};
    s.camera.target = {0.0f, 0.0f, -1.0f};
    s.previousCamera = s.camera;
    return s;
}

struct Floor {
    Scene scene;
    Renderer renderer;
    Frame frame;
    EmbreeScene embree;
    ReferenceImage ref;
    explicit Floor(const FloorOptions& o)
        : scene(floorScene(o)),
          renderer(settings(o.method)),
          frame(renderer.renderWithoutHistory(scene)),
          embree(scene) {
        ReferenceSettings s;
        s.spp = o.spp;
        s.maxDistance = 1e4f;
        ref = renderReference(embree, renderer, frame, s);
    }
    static RenderSettings settings(SsrMethod method) {
        RenderSettings rs;
        rs.trace.ssrMethod = method;
        rs.width = 48;
        rs.height = 27;
        rs.shadowMapSize = 256;
        return rs;
    }
    // Applies check(x, y) to the floor's pixels, returns how many there are.
    template <class Check>
    int forFloor(Check check) const {
        int n = 0;
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x)
                if (frame.gbuffer.viewZ.at(x, y) > 0.0f &&
                    frame.gbuffer.materialId.at(x, y) == 0.0f) {
                    check(x, y);
                    ++n;
                }
        return n;
    }
};

// Plain mean squared error over pixels and channels.
double mse(const PlaneF (&a)[3], const PlaneF (&b)[3]) {
    double s = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < a[c].height(); ++y)
            for (int x = 0; x < a[c].width(); ++x) {
                const double d = double(a[c].at(x, y)) - double(b[c].at(x, y));
                s += d * d;
            }
    return s / (3.0 * a[0].width() * a[0].height());
}

}  // namespace

TEST_CASE("reference: a floor under an open constant sky sees the sky in every ray") {
    const Floor f(FloorOptions{});
    const float sky[3] = {0.2f, 0.4f, 0.8f};
    int off = 0;
    const int n = f.forFloor([&](int x, int y) {
        for (int c = 0; c < 3; ++c) {
            off += std::abs(f.ref.ssr[c].at(x, y) - sky[c]) > 1e-6f * sky[c];
            off += std::abs(f.ref.ssgi[c].at(x, y) - sky[c]) > 1e-6f * sky[c];
            // Nothing shadows the floor: the sun part is positive.
            off += !(f.ref.direct[c].at(x, y) > 0.0f);
        }
    });
    MESSAGE(n << " floor pixels, " << off << " values off");
    CHECK(n > 300);
    CHECK(off == 0);
}

TEST_CASE("reference: a floor under an emitting ceiling gets the emission and no sun") {
    const Floor f(FloorOptions{.ceiling = true});
    const float emission[3] = {0.5f, 1.0f, 2.0f};
    int off = 0;
    const int n = f.forFloor([&](int x, int y) {
        for (int c = 0; c < 3; ++c) {
            // The ceiling's only light towards the floor is its emission (black, and the sun
            // on its back); rays grazing past its edge 1000 away are a 1e-6 minority.
            off += std::abs(f.ref.ssgi[c].at(x, y) - emission[c]) > 1e-3f * emission[c];
            off += f.ref.direct[c].at(x, y) != 0.0f;
        }
    });
    MESSAGE(n << " floor pixels, " << off << " values off");
    CHECK(n > 300);
    CHECK(off == 0);
}

TEST_CASE("reference: SSR converges to the same reflection whatever the sampler") {
    // ssr = sum(w L) / sum(w), w = D V n.l / pdf, estimates the lobe's mean radiance (the
    // integral of D V n.l L over that of D V n.l) for any pdf that covers the lobe; weights
    // off by the pdf would converge to a pdf-weighted mean instead, another for each sampler.
    // A rough floor under a gradient sky (every ray escapes: L is the smooth sky, little
    // noise) seen at grazing angles, where the samplers' pdfs differ most: the images of two
    // samplers differ by their noise alone, which for a 128-spp image is MSE(32 vs 128 spp) /
    // 3 (nested samples: s2 (1/32 - 1/128) = 3 s2 / 128). Measured: 1.2 times that (the ratio
    // estimator's O(1/n) bias differs a little between samplers); weights without the pdf
    // (the mutation this guards against): 8 times.
    auto floorSsr = [](SsrMethod method, int spp) {
        return Floor(FloorOptions{
                         .gradientSky = true, .roughness = 0.7f, .method = method, .spp = spp})
            .ref;
    };
    const ReferenceImage a1 = floorSsr(SsrMethod::GgxNdf, 32),
                         a4 = floorSsr(SsrMethod::GgxNdf, 128);
    const ReferenceImage b1 = floorSsr(SsrMethod::VndfBounded, 32),
                         b4 = floorSsr(SsrMethod::VndfBounded, 128);
    const double noise = (mse(a1.ssr, a4.ssr) + mse(b1.ssr, b4.ssr)) / 3.0;
    const double apart = mse(a4.ssr, b4.ssr);
    MESSAGE("MSE between the samplers at 128 spp " << apart << ", their noise " << noise
                                                   << ": ratio " << apart / noise);
    CHECK(noise > 0.0);
    CHECK(apart < 2.0 * noise);
}
