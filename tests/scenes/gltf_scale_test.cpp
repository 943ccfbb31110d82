// Real assets at any scale (issue 29 item 4): Khronos' 2CylinderEngine (assimp-testmodels)
// with its root nodes wrapped in one more node that scales them, camera included, by 1e-3
// or 1e3, or moves them 1e4 from 0, renders the same image and its rays fall in the same
// classes. The loader scales the camera's near and far planes with its node
// (scenes/gltf_camera.h); the rasterizer, the G-buffer, the trace and the Embree truth clip
// at those planes alike.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <glm/glm.hpp>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "renderer/renderer.h"
#include "temp_dir.h"
#include "truth/image_error.h"
#include "truth/ray_check.h"
#include "world/embree_scene.h"

using namespace ssrt;
using ssrt::test::TempDir;

namespace {

using Json = nlohmann::json;

const char* const kEngine = "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

// The .glb's JSON and BIN chunks (glTF 2.0 section 4.4).
struct Glb {
    Json json;
    std::string bin;
};

Glb readGlb(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    uint32_t jsonLength = 0, binLength = 0;
    std::memcpy(&jsonLength, bytes.data() + 12, 4);
    const std::size_t binAt = 20 + jsonLength;
    std::memcpy(&binLength, bytes.data() + binAt, 4);
    return {Json::parse(bytes.substr(20, jsonLength)), bytes.substr(binAt + 8, binLength)};
}

// The engine as a .gltf beside its buffer (engine.bin), its scene's root nodes (the model and
// the camera) under one more node that scales by `scale` and moves by `offset`: the loader's
// node walk composes that node into every mesh's and the camera's world matrix.
std::string writeWrapped(const TempDir& dir, const Glb& glb, const std::string& name, double scale,
                         const glm::dvec3& offset = glm::dvec3(0.0)) {
    const std::string bin = dir.file("engine.bin");
    if (!std::ifstream(bin).good()) test::writeFile(bin, glb.bin);
    Json j = glb.json;
    j["buffers"][0]["uri"] = "engine.bin";
    Json& scene = j["scenes"][j.value("scene", 0)];
    j["nodes"].push_back({{"children", scene["nodes"]},
                          {"scale", {scale, scale, scale}},
                          {"translation", {offset.x, offset.y, offset.z}}});
    scene["nodes"] = Json::array({j["nodes"].size() - 1});
    test::writeFile(dir.file(name), j.dump());
    return dir.file(name);
}

Scene load(const std::string& path, std::vector<std::string>& warnings) {
    GltfLoadReport report;
    Scene scene = loadGltf(path, {}, &report);
    warnings = report.warnings;
    return scene;
}

RenderSettings small() {
    RenderSettings rs;
    rs.width = 320;
    rs.height = 180;
    rs.shadowMapSize = 1024;
    rs.threads = 2;
    // Every pixel traced, and where the composite hides the answer too: the shares are of
    // every surface pixel's rays (the engine is mostly rough metal).
    rs.trace.ssrLayout = rs.trace.ssgiLayout = TraceLayout::Full;
    rs.trace.traceHidden = true;
    return rs;
}

struct Checked {
    Frame frame;
    RayCheckTable ssr, ssgi;
};

// Renders `scene` and has Embree check every ray the two trace passes marched.
Checked renderAndCheck(const Scene& scene) {
    const RenderSettings rs = small();
    const EmbreeScene embree(scene);
    Checked out;
    RayCheckSettings cs;
    cs.maxDistance = marchLengths(rs.trace.march, scene.diagonal()).maxDistance;
    // The G-buffer and camera are final before the trace passes run.
    const TraceObserver check = [&](TracePass pass, int, const RayBatch& rays,
                                    const MarchResult& march, const HalfFrame* half) {
        const RayCheckTable t = checkRays(embree, out.frame.camera, out.frame.gbuffer.viewZ, rays,
                                          march, cs, nullptr, 0, half);
        (pass == TracePass::Ssr ? out.ssr : out.ssgi).add(t);
    };
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), out.frame, &check);
    out.ssr.finish();
    out.ssgi.finish();
    return out;
}

double colourError(const Frame& f, const Frame& ref) {
    const auto imgRgb = f.rgb(Res::Color);
    const PlaneF* img[3] = {&imgRgb[0], &imgRgb[1], &imgRgb[2]};
    const auto rRgb = ref.rgb(Res::Color);
    const PlaneF* r[3] = {&rRgb[0], &rRgb[1], &rRgb[2]};
    return imageError(img, r).relMse;
}

// The largest change of any class's share (either pass), in points.
double largestShareChange(const Checked& c, const Checked& base) {
    double worst = 0.0;
    for (int k = 0; k < kRayClassCount; ++k) {
        const RayClass cls = RayClass(k);
        worst = std::max({worst, std::abs(c.ssr.share(cls) - base.ssr.share(cls)),
                          std::abs(c.ssgi.share(cls) - base.ssgi.share(cls))});
    }
    return 100.0 * worst;
}

uint64_t surfacePixels(const Frame& f) {
    uint64_t n = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) n += f.gbuffer.viewZ.at(x, y) > 0.0f;
    return n;
}

}  // namespace

TEST_CASE(
    "gltf scale: 2CylinderEngine scaled by 1e-3 and 1e3 or moved 1e4 keeps its image and ray "
    "classes") {
    const std::string path = test::assimpModel(kEngine);
    if (path.empty()) return;
    TempDir dir("gltf-scale");
    const Glb glb = readGlb(path);
    std::vector<std::string> warnings;
    const Checked base = renderAndCheck(load(writeWrapped(dir, glb, "1.gltf", 1.0), warnings));
    CHECK(warnings.empty());
    REQUIRE(base.ssr.rays > 10000);
    struct Variant {
        const char* label;
        double scale;
        glm::dvec3 offset;
    };
    const Variant variants[] = {{"scaled 1e-3", 1e-3, glm::dvec3(0.0)},
                                {"scaled 1e3", 1e3, glm::dvec3(0.0)},
                                {"moved 1e4", 1.0, glm::dvec3(1e4, -1e4, 1e4)}};
    for (const Variant& v : variants) {
        CAPTURE(std::string(v.label));
        const Scene scene = load(writeWrapped(dir, glb, "v.gltf", v.scale, v.offset), warnings);
        // A scaled camera's near and far planes are scaled with it, and the loader says so.
        CHECK(warnings.size() == (v.scale == 1.0 ? 0u : 1u));
        if (!warnings.empty())
            CHECK(warnings[0].find("znear and zfar are scaled") != std::string::npos);
        const Checked c = renderAndCheck(scene);
        const double error = colourError(c.frame, base.frame);
        const double shares = largestShareChange(c, base);
        CHECK(surfacePixels(c.frame) == surfacePixels(base.frame));
        // Not to the bit: the loader composes node matrices in float, and neither 1e-3 nor 1e3
        // is a power of two (nor are the camera's placement 1e4 out), so every vertex rounds
        // apart by an ulp, which moves a few silhouette pixels' rays (relMSE ~1e-11).
        CHECK(error <= 1e-9);
        CHECK(shares <= 1.0);
        MESSAGE("2CylinderEngine " << std::string(v.label) << ": colour relMSE " << error
                                   << ", largest class-share change " << shares << " points ("
                                   << c.ssr.rays << " SSR, " << c.ssgi.rays << " SSGI rays)");
    }
}

// The bug as found: with znear and zfar taken in world units under a node scaling by 1000,
// the whole engine lay past the far plane; the image was empty while --stats counted the
// rasterizer's covered pixels, and the trace saw no surface.
TEST_CASE(
    "gltf scale: a camera under a node scaling by 1000 sees the engine, the trace counts it") {
    const std::string path = test::assimpModel(kEngine);
    if (path.empty()) return;
    TempDir dir("gltf-scale");
    std::vector<std::string> warnings;
    const Scene scene = load(writeWrapped(dir, readGlb(path), "1000.gltf", 1e3), warnings);
    RenderSettings rs = small();
    rs.width = 160;
    rs.height = 90;
    const Frame f = Renderer(rs).renderWithoutHistory(scene);
    const uint64_t seen = surfacePixels(f);
    MESSAGE("2CylinderEngine under a 1000x node, 160x90: " << seen << " surface pixels, "
                                                           << f.stats.visibility.pixelsWritten
                                                           << " written by the rasterizer");
    CHECK(seen > 160 * 90 / 10);
    CHECK(f.stats.ssr.rays.pixels == seen);
    CHECK(f.stats.ssgi.rays.pixels == seen);
}

// Whether Embree finds a surface the rasterizer would draw along the ray between t0 and t1:
// it skips the back faces of single-sided materials, as the rasterizer culls them (where the
// near plane cuts the engine open, its inside shows them).
bool drawnHit(const EmbreeScene& embree, glm::vec3 eye, glm::vec3 dir, float t0, float t1) {
    const Scene& scene = embree.scene();
    for (;;) {
        const EmbreeHit h = embree.intersect(eye, dir, t0, t1);
        if (!h.hit) return false;
        const Material& m = scene.materials[scene.instances[h.instance].material];
        if (m.doubleSided || glm::dot(embree.surface(eye, dir, h).geometricNormal, dir) < 0.0f)
            return true;
        t0 = std::nextafter(h.t, INFINITY);
    }
}

// Per pixel, whether Embree sees a drawn surface through its centre at view depths in
// [near, far] (the rule truth/reference_image.cpp's primary hits follow).
std::vector<char> embreeCoverage(const EmbreeScene& embree, const TraceCamera& c, float near,
                                 float far) {
    const glm::vec3 eye(c.position[0], c.position[1], c.position[2]);
    glm::mat3 rot;
    for (int k = 0; k < 9; ++k) rot[k / 3][k % 3] = c.viewToWorld[k];
    std::vector<char> hit;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const glm::vec3 view(((x + 0.5f) * 2.0f / c.width - 1.0f) * c.tanHalfX,
                                 (1.0f - (y + 0.5f) * 2.0f / c.height) * c.tanHalfY, -1.0f);
            const float length = glm::length(view);  // view depth 1 lies this far along the ray
            hit.push_back(
                drawnHit(embree, eye, rot * (view / length), near * length, far * length));
        }
    return hit;
}

uint64_t count(const std::vector<char>& v) { return std::count(v.begin(), v.end(), 1); }

// Near and far planes that cut through the engine: the rasterizer (and so the G-buffer and
// the trace) and Embree keep the same pixels, and the triangles the loader counts as past the
// far plane are dropped before the rasterizer bins them.
TEST_CASE("gltf scale: near and far planes through the engine clip the raster and Embree alike") {
    const std::string path = test::assimpModel(kEngine);
    if (path.empty()) return;
    TempDir dir("gltf-scale");
    Glb glb = readGlb(path);
    // The camera is 1582 units from the engine's origin.
    glb.json["cameras"][0]["perspective"]["znear"] = 1450.0;
    glb.json["cameras"][0]["perspective"]["zfar"] = 1700.0;
    std::vector<std::string> warnings;
    const Scene scene = load(writeWrapped(dir, glb, "cut.gltf", 1e3), warnings);
    REQUIRE(warnings.size() == 2);
    CHECK(warnings[1].find("lie wholly beyond its far plane") != std::string::npos);
    const uint64_t beyond = std::stoull(warnings[1].substr(warnings[1].find("camera 0: ") + 10));
    RenderSettings rs = small();
    rs.width = 160;
    rs.height = 90;
    const Frame f = Renderer(rs).renderWithoutHistory(scene);
    CHECK(f.stats.visibility.trianglesOutside >= beyond);
    const EmbreeScene embree(scene);
    const TraceCamera& c = f.camera;
    const std::vector<char> clipped = embreeCoverage(embree, c, c.nearZ, c.farZ);
    // Each plane cuts some of the engine away.
    const uint64_t whole = count(embreeCoverage(embree, c, 0.0f, INFINITY));
    CHECK(count(embreeCoverage(embree, c, c.nearZ, INFINITY)) < whole);
    CHECK(count(embreeCoverage(embree, c, 0.0f, c.farZ)) < whole);
    uint64_t covered = 0, differ = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const bool raster = f.gbuffer.viewZ.at(x, y) > 0.0f;
            covered += raster;
            differ += raster != bool(clipped[std::size_t(y) * f.width + x]);
        }
    MESSAGE("2CylinderEngine cut by its near and far planes, 160x90: "
            << covered << " pixels covered (" << whole << " uncut), " << differ
            << " where Embree differs; " << beyond << " triangles past far, "
            << f.stats.visibility.trianglesOutside << " dropped by the rasterizer as outside");
    CHECK(covered > 0);
    CHECK(f.stats.ssr.rays.pixels == covered);
    CHECK(differ <= covered / 200);  // silhouette pixels whose centre the two round apart
}
