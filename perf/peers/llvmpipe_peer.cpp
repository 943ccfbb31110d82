// ssrt against Mesa llvmpipe on the same scene and camera, in one run: a depth-only shadow
// map and a four-target G-buffer, median milliseconds over N repetitions, as ratios; then,
// outside the clocks, both renders compared pixel by pixel (perf/peers/pixel_compare.h).
//
//   ssrt_peer_llvmpipe [--reps N] [--scene knot3k|knot121k|cornell|all]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "perf/peers/gl_peer.h"
#include "perf/peers/pixel_compare.h"
#include "raster/raster.h"
#include "raster/setup.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"

namespace {

constexpr int kWidth = 1920, kHeight = 1080, kShadowSize = 2048, kThreads = 2;

struct Options {
    int reps = 10;
    std::string scene = "all";
};

struct NamedScene {
    std::string name;
    ssrt::Scene scene;
};

void printUsage() {
    std::printf(
        "usage: ssrt_peer_llvmpipe [--reps N] [--scene knot3k|knot121k|cornell|all]\n"
        "Times a %dx%d shadow map and a %dx%d G-buffer on Mesa llvmpipe and on ssrt\n"
        "(%d threads each) and prints median ms and llvmpipe/ssrt ratios.\n",
        kShadowSize, kShadowSize, kWidth, kHeight, kThreads);
}

Options parseOptions(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--help" || arg == "-h") {
            printUsage();
            std::exit(0);
        } else if (arg == "--reps") {
            o.reps = std::atoi(value().c_str());
            if (o.reps < 1) throw std::invalid_argument("--reps must be at least 1");
        } else if (arg == "--scene") {
            o.scene = value();
        } else {
            throw std::invalid_argument("unknown argument '" + arg + "' (try --help)");
        }
    }
    return o;
}

// Built only when asked for: the 121k knot takes a moment to make.
std::vector<NamedScene> makeScenes(const std::string& which) {
    const std::vector<std::string> known = {"knot3k", "knot121k", "cornell"};
    if (which != "all" && std::find(known.begin(), known.end(), which) == known.end())
        throw std::invalid_argument("unknown scene '" + which +
                                    "' (knot3k, knot121k, cornell or all)");
    std::vector<NamedScene> scenes;
    auto want = [&](const char* name) { return which == "all" || which == name; };
    if (want("knot3k")) scenes.push_back({"knot3k", ssrt::makeKnotScene(3700)});
    if (want("knot121k")) scenes.push_back({"knot121k", ssrt::makeKnotScene(121000)});
    if (want("cornell")) scenes.push_back({"cornell", ssrt::makeBuiltinScene("cornell")});
    return scenes;
}

// An orthographic light camera looking along the light, its box fitted to the corners of
// the scene bounds in light view space: the same texels ssrt's shadow pass covers, fitted
// here rather than borrowed so the peer depends only on the public scene model.
glm::mat4 fitLightViewProjection(const ssrt::Scene& scene) {
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    glm::vec3 dir = glm::normalize(scene.light.direction);
    glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    glm::mat4 view = glm::lookAt(glm::vec3(0.0f), dir, up);
    glm::vec3 vlo(1e30f), vhi(-1e30f);
    for (int i = 0; i < 8; ++i) {
        glm::vec3 corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        glm::vec3 v = glm::vec3(view * glm::vec4(corner, 1.0f));
        vlo = glm::min(vlo, v);
        vhi = glm::max(vhi, v);
    }
    // A margin of 1 % of the bounds' radius, as raster/shadow_map.cpp leaves.
    float margin = 0.01f * std::max(0.5f * glm::length(hi - lo), 1e-3f);
    vlo -= glm::vec3(margin);
    vhi += glm::vec3(margin);
    // View space looks down -z: near is the largest z, far the smallest.
    return glm::ortho(vlo.x, vhi.x, vlo.y, vhi.y, -vhi.z, -vlo.z) * view;
}

peer::GlMesh toGlMesh(const ssrt::Mesh& mesh) {
    return {mesh.positions, mesh.normals, mesh.indices};
}

peer::GlSceneDesc toGlScene(const ssrt::Scene& scene) {
    peer::GlSceneDesc d;
    for (const ssrt::Mesh& m : scene.meshes) d.meshes.push_back(toGlMesh(m));
    for (const ssrt::Instance& inst : scene.instances) {
        const ssrt::Material& mat = scene.materials.at(inst.material);
        d.draws.push_back({inst.mesh, inst.transform, inst.previousTransform, mat.baseColor,
                           mat.metallic, mat.roughness, mat.doubleSided});
    }
    float aspect = float(kWidth) / float(kHeight);
    d.view = scene.camera.view();
    d.projection = scene.camera.projection(aspect);
    d.previousView = scene.previousCamera.view();
    d.previousProjection = scene.previousCamera.projection(aspect);
    d.lightViewProjection = fitLightViewProjection(scene);
    return d;
}

std::size_t drawnTriangles(const ssrt::Scene& scene) {
    std::size_t n = 0;
    for (const ssrt::Instance& inst : scene.instances)
        n += scene.meshes.at(inst.mesh).triangleCount();
    return n;
}

// Medians over the repetitions.
struct Timings {
    double shadowMs = 0.0, gbufferMs = 0.0;
    double parts[3] = {};  // ssrt only: geometry, visibility, resolve medians
};

constexpr const char* kGBufferPasses[3] = {"geometry", "visibility", "resolve"};

struct Samples {
    std::vector<double> shadow, gbuffer;
    std::vector<double> parts[3];  // ssrt's G-buffer passes one by one (where the time goes)
    Timings medians() const {
        Timings t;
        t.shadowMs = peer::medianOf(shadow);
        t.gbufferMs = peer::medianOf(gbuffer);
        for (int i = 0; i < 3; ++i) t.parts[i] = peer::medianOf(parts[i]);
        return t;
    }
};

double passMs(const ssrt::FrameStats& stats, const char* name) {
    for (const ssrt::PassTime& p : stats.passes)
        if (p.name == name) return p.ms;
    throw std::runtime_error(std::string("ssrt reported no pass named '") + name + "'");
}

void recordSsrt(const ssrt::Frame& frame, Samples& samples) {
    const ssrt::FrameStats& s = frame.stats;
    samples.shadow.push_back(passMs(s, "shadow"));
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        samples.parts[i].push_back(passMs(s, kGBufferPasses[i]));
        sum += samples.parts[i].back();
    }
    samples.gbuffer.push_back(sum);
}

void recordGl(peer::GlWorkloads& gl, Samples& samples) {
    samples.shadow.push_back(peer::timeOnce([&] { gl.drawShadow(); }));
    samples.gbuffer.push_back(peer::timeOnce([&] { gl.drawGBuffer(); }));
}

static_assert(peer::kNoTriangle == ssrt::kNoPrimitive, "both sides mark empty pixels alike");

// GL's G-buffer ids and linear depths, from the untimed id pass. Its linear depth must equal
// the timed pass's bit for bit (same vertex shader, same pixels), or the ids would describe a
// render other than the one timed; the count of pixels that differ is returned in `mismatch`.
peer::IdDepthImage glGBuffer(peer::GlWorkloads& gl, std::size_t& mismatch) {
    gl.drawIds();
    peer::IdDepthImage image{kWidth, kHeight, gl.readIdPassTriangles(), gl.readIdPassDepth()};
    const std::vector<float> timed = gl.readLinearDepth();
    mismatch = 0;
    for (std::size_t i = 0; i < timed.size(); ++i) mismatch += timed[i] != image.depth[i];
    return image;
}

// ssrt's visibility buffer holds the depth key 1/w (w: the distance along the view axis).
peer::IdDepthImage ssrtGBuffer(const ssrt::Frame& frame) {
    const ssrt::VisibilityBuffer& vb = frame.scratch.visibility;
    if (vb.ids.width() != kWidth || vb.depth.width() != kWidth)
        throw std::runtime_error("ssrt's frame no longer holds its visibility buffer");
    peer::IdDepthImage image{kWidth, kHeight, {}, {}};
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const uint32_t id = vb.ids.at(x, y);
            image.ids.push_back(id);
            image.depth.push_back(id == ssrt::kNoPrimitive ? 0.0f : 1.0f / vb.depth.at(x, y));
        }
    }
    return image;
}

// ssrt's shadow map holds the depth key 1 - z01; GL's depth buffer z01 itself.
peer::DepthImage ssrtShadow(const ssrt::Frame& frame) {
    const ssrt::PlaneF& key = frame.scratch.shadow.depth;
    if (key.width() != kShadowSize || key.height() != kShadowSize)
        throw std::runtime_error("ssrt's frame no longer holds its shadow map");
    peer::DepthImage image{kShadowSize, kShadowSize, {}};
    for (int y = 0; y < kShadowSize; ++y)
        for (int x = 0; x < kShadowSize; ++x) image.depth.push_back(1.0f - key.at(x, y));
    return image;
}

// Both sides' renders, pixel by pixel, read after the timing.
struct Comparison {
    peer::GBufferComparison gbuffer;
    peer::ShadowComparison shadow;
    std::size_t idPassMismatch = 0;
    uint32_t centre[2] = {};  // the centre pixel's triangle id: llvmpipe, ssrt
    std::size_t centreInstance = 0;
    uint32_t centreTriangle = 0;  // llvmpipe's id as (instance, triangle of its mesh)
};

Comparison compareBoth(peer::GlWorkloads& gl, const ssrt::Frame& frame,
                       const peer::GlSceneDesc& desc) {
    Comparison c;
    const peer::IdDepthImage glImage = glGBuffer(gl, c.idPassMismatch),
                             ssImage = ssrtGBuffer(frame);
    const peer::TriangleNeighbours triangles(desc);
    c.gbuffer = peer::compareGBuffers(glImage, ssImage, triangles);
    const std::size_t centre = std::size_t(kHeight / 2) * kWidth + kWidth / 2;
    c.centre[0] = glImage.ids[centre];
    c.centre[1] = ssImage.ids[centre];
    if (triangles.contains(c.centre[0])) {
        c.centreInstance = triangles.drawOf(c.centre[0]);
        c.centreTriangle = triangles.localOf(c.centre[0]);
    }
    c.shadow = peer::compareShadowMaps({kShadowSize, kShadowSize, gl.readShadowDepth()},
                                       ssrtShadow(frame));
    // Whole-target counts prove each side drew something: an empty render is never timed
    // unnoticed (a camera may look past geometry at the centre).
    if (c.gbuffer.glCovered() == 0 || c.shadow.glCovered() == 0)
        throw std::runtime_error("llvmpipe's G-buffer or shadow map is empty");
    if (c.gbuffer.ssrtCovered() == 0 || c.shadow.ssrtCovered() == 0)
        throw std::runtime_error("ssrt's G-buffer or shadow map is empty");
    return c;
}

ssrt::RenderSettings ssrtSettings() {
    ssrt::RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.threads = kThreads;
    settings.shadowMapSize = kShadowSize;
    // ssrt's optional instanceId/triangleId float planes are left out, as the timed GL
    // G-buffer writes no ids either; the comparison reads the visibility buffer's ids, which
    // the frame keeps with tracePlanes (the default, said here because the comparison needs it).
    settings.idPlanes = false;
    settings.tracePlanes = true;
    return settings;
}

// Interleaved, one GL repetition then one ssrt frame, so that a burst of load on the machine
// falls on both sides alike. ssrt renders whole frames; its own per-pass clocks pick out
// the two workloads.
// Then compares the last repetition's renders pixel by pixel, outside the clocks.
Comparison timeBoth(const ssrt::Scene& scene, int reps, Timings& gl, Timings& ss) {
    const peer::GlSceneDesc desc = toGlScene(scene);
    peer::GlWorkloads glWork(desc, kWidth, kHeight, kShadowSize);
    ssrt::Renderer renderer(ssrtSettings());
    Samples glSamples, ssrtSamples, unused;
    for (int i = 0; i < 2; ++i) recordGl(glWork, unused);  // warm-up: JIT, first touches
    // Rendered into the same frame every time: its planes are reused, as GL reuses its
    // framebuffers (a fresh frame would time page faults).
    ssrt::Frame frame = renderer.renderWithoutHistory(scene);
    for (int i = 0; i < reps; ++i) {
        recordGl(glWork, glSamples);
        renderer.renderWithoutHistory(scene, ssrt::FrameInput::still(scene), frame);
        recordSsrt(frame, ssrtSamples);
    }
    gl = glSamples.medians();
    ss = ssrtSamples.medians();
    return compareBoth(glWork, frame, desc);
}

void printRow(const char* pass, double glMs, double ssrtMs) {
    std::printf("  %-22s %12.2f %10.2f %8.2f\n", pass, glMs, ssrtMs, glMs / ssrtMs);
}

void printCoverage(const Comparison& c) {
    const peer::GBufferComparison& g = c.gbuffer;
    const peer::ShadowComparison& m = c.shadow;
    auto pct = [](std::size_t n, std::size_t of) { return 100.0 * double(n) / double(of); };
    std::printf(
        "  covered: G-buffer llvmpipe %.2f%%, ssrt %.2f%%; shadow map llvmpipe %.2f%%, ssrt "
        "%.2f%%\n",
        pct(g.glCovered(), g.pixels), pct(g.ssrtCovered(), g.pixels), pct(m.glCovered(), m.texels),
        pct(m.ssrtCovered(), m.texels));
    std::printf("  centre pixel's triangle id: llvmpipe %u (instance %zu, triangle %u), ssrt %u\n",
                c.centre[0], c.centreInstance, c.centreTriangle, c.centre[1]);
    if (c.idPassMismatch)
        std::printf(
            "  WARNING: the id pass's linear depth differs from the timed G-buffer's in %zu "
            "pixels: the ids describe another render\n",
            c.idPassMismatch);
}

void runScene(const NamedScene& s, int reps, const peer::SubPixel& grid) {
    std::printf("\nscene %s: %zu triangles in the scene, %zu drawn (%zu instances)\n",
                s.name.c_str(), s.scene.triangleCount(), drawnTriangles(s.scene),
                s.scene.instances.size());
    std::fflush(stdout);
    Timings gl, ss;
    const Comparison c = timeBoth(s.scene, reps, gl, ss);
    std::printf("  %-22s %12s %10s %8s\n", "pass (median ms)", "llvmpipe", "ssrt", "ratio");
    printRow("shadow map 2048^2", gl.shadowMs, ss.shadowMs);
    printRow("G-buffer 1920x1080", gl.gbufferMs, ss.gbufferMs);
    std::printf("  ssrt G-buffer medians: geometry %.2f, visibility %.2f, resolve %.2f ms\n",
                ss.parts[0], ss.parts[1], ss.parts[2]);
    printCoverage(c);
    peer::printGBufferComparison(c.gbuffer, grid);
    peer::printShadowComparison(c.shadow);
    std::fflush(stdout);
}

// Other work on the machine skews both sides; the load average shows when it did.
std::string loadAverage() {
    std::FILE* f = std::fopen("/proc/loadavg", "r");
    if (!f) return "unknown";
    char buf[64] = {};
    std::string line = std::fgets(buf, sizeof buf, f) ? buf : "unknown";
    std::fclose(f);
    return line.substr(0, line.find(' '));  // the one-minute figure
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Options opt = parseOptions(argc, argv);
        std::vector<NamedScene> scenes = makeScenes(opt.scene);
        peer::GlContext context(kThreads);
        if (!context.isLlvmpipe())
            throw std::runtime_error("GL_RENDERER is '" + context.renderer() +
                                     "', not llvmpipe; this comparison is CPU against CPU");
        std::printf(
            "GL_RENDERER: %s\nGL_VERSION: %s\nLP_NUM_THREADS=%s, ssrt threads=%d, "
            "%d reps after warm-up, ratio = llvmpipe / ssrt (>1: ssrt faster)\n",
            context.renderer().c_str(), context.version().c_str(), std::getenv("LP_NUM_THREADS"),
            kThreads, opt.reps);
        const peer::SubPixel grid{ssrt::kSubPixelBits, context.subpixelBits()};
        for (const NamedScene& s : scenes) runScene(s, opt.reps, grid);
        std::printf("\nload average (1 min) at the end: %s on %u hardware threads\n",
                    loadAverage().c_str(), std::thread::hardware_concurrency());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
