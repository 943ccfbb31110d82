// The determinism contract: the same bits for every thread count and every ISA the machine
// runs, and golden hashes for the built-in scenes.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

using namespace ssrt;

namespace {

// One hash over every plane, in order, names included.
uint64_t frameHash(const Frame& f) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (const NamedPlane& p : f.planes) {
        for (char c : p.name) h = (h ^ uint8_t(c)) * 0x100000001b3ull;
        h = hashPlane(p.plane, h);
    }
    return h;
}

Frame renderSmall(const std::string& scene, Isa isa, int threads) {
    RenderSettings rs;
    rs.width = 240;
    rs.height = 136;
    rs.shadowMapSize = 512;
    rs.isa = isa;
    rs.threads = threads;
    return Renderer(rs).render(makeBuiltinScene(scene));
}

// Recorded from this build (GCC 12, Debian 12). A change to any pass changes them on
// purpose: re-record with SSRT_PRINT_GOLDEN=1 and say why in the commit.
const std::map<std::string, uint64_t> kGolden = {
    {"cornell", 0x424e70d0d1bc6edbull},
    {"spheres", 0xa66601da9d1babbaull},
    {"bunny", 0xac96514cff235a0full},
};

}  // namespace

TEST_CASE("every ISA and thread count renders the same bits") {
    for (const char* scene : {"cornell", "spheres"}) {
        CAPTURE(scene);
        const uint64_t ref = frameHash(renderSmall(scene, Isa::Scalar, 1));
        for (Isa isa : supportedIsas())
            for (int threads : {1, 2, 8}) {
                const std::string isaStr(isaName(isa));
                CAPTURE(isaStr);
                CAPTURE(threads);
                CHECK(frameHash(renderSmall(scene, isa, threads)) == ref);
            }
    }
}

TEST_CASE("built-in scenes keep their golden hashes") {
    const bool print = std::getenv("SSRT_PRINT_GOLDEN") != nullptr;
    for (const auto& [scene, golden] : kGolden) {
        CAPTURE(scene);
        const uint64_t h = frameHash(renderSmall(scene, Isa::Scalar, 2));
        if (print) std::printf("    {\"%s\", 0x%016llxull},\n", scene.c_str(), (unsigned long long)h);
        CHECK(h == golden);
    }
}

TEST_CASE("no NaN or infinity in any plane of the built-in scenes") {
    for (const auto& info : builtinScenes()) {
        CAPTURE(info.name);
        const Frame f = renderSmall(info.name, defaultIsa(), 2);
        for (const NamedPlane& p : f.planes) {
            CAPTURE(p.name);
            bool finite = true;
            for (int y = 0; y < f.height; ++y)
                for (int x = 0; x < f.width; ++x) finite &= std::isfinite(p.plane.at(x, y));
            CHECK(finite);
        }
        // The display planes are tone mapped into [0, 1].
        for (const char* c : {"display.R", "display.G", "display.B"})
            for (int y = 0; y < f.height; ++y)
                for (int x = 0; x < f.width; ++x) {
                    const float v = f.plane(c).at(x, y);
                    REQUIRE((v >= 0.0f && v <= 1.0f));
                }
    }
}
