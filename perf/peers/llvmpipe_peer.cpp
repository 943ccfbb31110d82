// ssrt against Mesa llvmpipe on the same scene and camera, in one run: a depth-only shadow
// map and a four-target G-buffer, median milliseconds over N repetitions, as ratios.
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

// Medians over the repetitions, and what each side drew (to show the workloads match).
struct Timings {
    double shadowMs = 0.0, gbufferMs = 0.0;
    double coverage = 0.0;        // share of G-buffer pixels with geometry
    float centre = 0.0f;          // linear depth (distance along the view axis), centre pixel
    double shadowCoverage = 0.0;  // share of shadow-map texels with geometry (GL only)
    double parts[3] = {};         // ssrt only: geometry, visibility, resolve medians
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

// The read-back proves GL drew something, so an empty render is never timed unnoticed.
// Whole-target counts rather than one centre pixel: a camera may look past geometry.
void checkGl(peer::GlWorkloads& gl, Timings& t) {
    peer::Coverage shadow = gl.shadowCoverage(), gbuffer = gl.gbufferCoverage();
    if (shadow.fraction == 0.0)
        throw std::runtime_error("llvmpipe shadow map is empty (every depth still 1)");
    if (gbuffer.fraction == 0.0)
        throw std::runtime_error("llvmpipe G-buffer is empty (every linear depth still 0)");
    t.coverage = gbuffer.fraction;
    t.centre = gbuffer.centre;
    t.shadowCoverage = shadow.fraction;
}

void checkSsrt(const ssrt::Frame& frame, Timings& t) {
    const ssrt::PlaneF& z = frame.gbuffer.viewZ;
    std::size_t touched = 0;
    for (int y = 0; y < z.height(); ++y)
        for (int x = 0; x < z.width(); ++x) touched += z.at(x, y) != 0.0f;
    t.coverage = double(touched) / (double(z.width()) * double(z.height()));
    // Read-back rows run bottom-up in GL and top-down here; the centre is the same pixel.
    t.centre = std::abs(z.at(z.width() / 2, (z.height() - 1) / 2));
    if (touched == 0) throw std::runtime_error("ssrt G-buffer is empty (viewZ all 0)");
}

ssrt::RenderSettings ssrtSettings() {
    ssrt::RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.threads = kThreads;
    settings.shadowMapSize = kShadowSize;
    // The GL G-buffer has no id targets; ssrt's optional instanceId/triangleId planes are
    // left out so both sides write the same attributes.
    settings.idPlanes = false;
    return settings;
}

// Interleaved, one GL repetition then one ssrt frame, so that a burst of load on the machine
// falls on both sides alike. ssrt renders whole frames; its own per-pass clocks pick out
// the two workloads.
void timeBoth(const ssrt::Scene& scene, int reps, Timings& gl, Timings& ss) {
    peer::GlWorkloads glWork(toGlScene(scene), kWidth, kHeight, kShadowSize);
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
    checkGl(glWork, gl);
    checkSsrt(frame, ss);
}

void printRow(const char* pass, double glMs, double ssrtMs) {
    std::printf("  %-22s %12.2f %10.2f %8.2f\n", pass, glMs, ssrtMs, glMs / ssrtMs);
}

void runScene(const NamedScene& s, int reps) {
    std::printf("\nscene %s: %zu triangles in the scene, %zu drawn (%zu instances)\n",
                s.name.c_str(), s.scene.triangleCount(), drawnTriangles(s.scene),
                s.scene.instances.size());
    std::fflush(stdout);
    Timings gl, ss;
    timeBoth(s.scene, reps, gl, ss);
    std::printf("  %-22s %12s %10s %8s\n", "pass (median ms)", "llvmpipe", "ssrt", "ratio");
    printRow("shadow map 2048^2", gl.shadowMs, ss.shadowMs);
    printRow("G-buffer 1920x1080", gl.gbufferMs, ss.gbufferMs);
    std::printf("  ssrt G-buffer medians: geometry %.2f, visibility %.2f, resolve %.2f ms\n",
                ss.parts[0], ss.parts[1], ss.parts[2]);
    std::printf(
        "  covered pixels: G-buffer llvmpipe %.1f%%, ssrt %.1f%%; "
        "shadow map llvmpipe %.1f%%\n",
        100.0 * gl.coverage, 100.0 * ss.coverage, 100.0 * gl.shadowCoverage);
    std::printf("  centre pixel depth: llvmpipe %.4f, ssrt %.4f\n", gl.centre, ss.centre);
    // Same scene and camera should cover the same pixels; if not, the workloads differ.
    if (std::abs(gl.coverage - ss.coverage) > 0.02)
        std::printf("  WARNING: coverage differs by more than 2%%: the two renders disagree\n");
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
        for (const NamedScene& s : scenes) runScene(s, opt.reps);
        std::printf("\nload average (1 min) at the end: %s on %u hardware threads\n",
                    loadAverage().c_str(), std::thread::hardware_concurrency());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
