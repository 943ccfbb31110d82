// OpenGL 3.3 core on Mesa through EGL's surfaceless platform: no window system, no X, no
// GPU needed; llvmpipe is what Mesa picks there when no GPU driver loads.
#include "perf/peers/gl_peer.h"

#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace peer {

namespace {

[[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("llvmpipe peer: " + what);
}

std::string eglErrorText() {
    char buf[32];
    std::snprintf(buf, sizeof buf, "EGL error 0x%04x", unsigned(eglGetError()));
    return buf;
}

// Whole-word match in a space-separated extension list (one name may prefix another).
bool hasExtension(const char* list, std::string_view name) {
    std::string_view rest = list ? list : "";
    while (!rest.empty()) {
        std::size_t end = std::min(rest.find(' '), rest.size());
        if (rest.substr(0, end) == name) return true;
        rest.remove_prefix(std::min(end + 1, rest.size()));
    }
    return false;
}

EGLDisplay openSurfacelessDisplay() {
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExts, "EGL_MESA_platform_surfaceless"))
        fail(
            "EGL has no surfaceless platform (EGL_MESA_platform_surfaceless); is Mesa's "
            "EGL (libegl-mesa0) installed?");
    EGLDisplay dpy =
        eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy == EGL_NO_DISPLAY) fail("eglGetPlatformDisplay(surfaceless) failed: " + eglErrorText());
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor))
        fail("eglInitialize failed: " + eglErrorText() + " (is libgl1-mesa-dri installed?)");
    return dpy;
}

EGLConfig chooseConfig(EGLDisplay dpy) {
    // The surfaceless platform offers only pbuffer-capable configs; we render into FBOs.
    const EGLint attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                              EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(dpy, attribs, &config, 1, &count) || count < 1)
        fail("no EGL config with EGL_PBUFFER_BIT and EGL_OPENGL_BIT: " + eglErrorText());
    return config;
}

EGLContext createCoreContext(EGLDisplay dpy, EGLConfig config) {
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              3,
                              EGL_CONTEXT_MINOR_VERSION,
                              3,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT) fail("cannot create an OpenGL 3.3 core context: " + eglErrorText());
    // Surfaceless: no default framebuffer at all, every pass renders into its own FBO.
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        fail("eglMakeCurrent without a surface failed: " + eglErrorText());
    return ctx;
}

std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

GlContext::GlContext(int llvmpipeThreads) {
    // Must precede eglInitialize: llvmpipe reads it once when the screen is created.
    setenv("LP_NUM_THREADS", std::to_string(llvmpipeThreads).c_str(), /*overwrite=*/0);
    EGLDisplay dpy = openSurfacelessDisplay();
    display_ = dpy;
    context_ = createCoreContext(dpy, chooseConfig(dpy));
    if (renderer().empty()) fail("glGetString(GL_RENDERER) returned nothing");
}

GlContext::~GlContext() {
    auto dpy = static_cast<EGLDisplay>(display_);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(dpy, static_cast<EGLContext>(context_));
    eglTerminate(dpy);
}

std::string GlContext::renderer() const { return glString(GL_RENDERER); }
std::string GlContext::version() const { return glString(GL_VERSION); }
bool GlContext::isLlvmpipe() const { return renderer().find("llvmpipe") != std::string::npos; }

int GlContext::subpixelBits() const {
    GLint bits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
    return bits;
}

std::vector<uint32_t> firstTriangles(const GlSceneDesc& desc) {
    std::vector<uint32_t> first;
    uint32_t next = 0;
    for (const GlDraw& d : desc.draws) {
        first.push_back(next);
        next += uint32_t(desc.meshes.at(d.mesh).indices.size() / 3);
    }
    first.push_back(next);
    return first;
}

// ---------------------------------------------------------------------------------------

namespace {

const char* kShadowVs = R"(#version 330 core
layout(location = 0) in vec3 aPos;
uniform mat4 uLightViewProj;
uniform mat4 uModel;
void main() { gl_Position = uLightViewProj * (uModel * vec4(aPos, 1.0)); }
)";

// Depth only: no colour attachment, so the fragment stage writes nothing.
const char* kShadowFs = R"(#version 330 core
void main() {}
)";

const char* kGBufferVs = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel, uView, uProj;
uniform mat4 uPrevModel, uPrevView, uPrevProj;
uniform mat3 uNormalMatrix;
out vec3 vNormal;
out float vViewDepth;
out vec4 vClip;
out vec4 vPrevClip;
void main() {
    vec4 viewPos = uView * (uModel * vec4(aPos, 1.0));
    vClip = uProj * viewPos;
    vPrevClip = uPrevProj * (uPrevView * (uPrevModel * vec4(aPos, 1.0)));
    vNormal = uNormalMatrix * aNormal;
    vViewDepth = -viewPos.z;
    gl_Position = vClip;
}
)";

const char* kGBufferFs = R"(#version 330 core
in vec3 vNormal;
in float vViewDepth;
in vec4 vClip;
in vec4 vPrevClip;
uniform vec3 uAlbedo;
uniform float uMetallic, uRoughness;
uniform vec2 uViewport;
layout(location = 0) out vec4 oNormalRoughness;
layout(location = 1) out vec4 oAlbedoMetallic;
layout(location = 2) out vec2 oMotion;
layout(location = 3) out float oLinearDepth;
void main() {
    vec3 n = normalize(vNormal);
    n = gl_FrontFacing ? n : -n;  // double-sided materials show their back faces
    oNormalRoughness = vec4(n, uRoughness);
    oAlbedoMetallic = vec4(uAlbedo, uMetallic);
    // Pixels moved since the previous frame (previous minus current screen position).
    oMotion = (vPrevClip.xy / vPrevClip.w - vClip.xy / vClip.w) * 0.5 * uViewport;
    oLinearDepth = vViewDepth;
}
)";

// The id pass: the G-buffer's vertex shader as it is (the same positions, so the same pixels
// and depths as the timed pass), and only the linear depth and the triangle id written.
const char* kIdFs = R"(#version 330 core
in float vViewDepth;
uniform uint uFirstTriangle;
layout(location = 0) out float oLinearDepth;
layout(location = 1) out uint oTriangle;
void main() {
    oLinearDepth = vViewDepth;
    oTriangle = uFirstTriangle + uint(gl_PrimitiveID);
}
)";

GLuint compileShader(GLenum type, const char* source) {
    GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        fail(std::string("shader does not compile: ") + log);
    }
    return shader;
}

GLuint linkProgram(const char* vs, const char* fs) {
    GLuint v = compileShader(GL_VERTEX_SHADER, vs), f = compileShader(GL_FRAGMENT_SHADER, fs);
    GLuint program = glCreateProgram();
    glAttachShader(program, v);
    glAttachShader(program, f);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        fail(std::string("program does not link: ") + log);
    }
    return program;
}

GLuint makeTexture(GLenum internalFormat, GLenum format, GLenum type, int w, int h) {
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GLint(internalFormat), w, h, 0, format, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

void checkFramebuffer(const char* which) {
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        fail(std::string(which) + " framebuffer incomplete: status " + std::to_string(status));
}

void checkGlError(const char* where) {
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) fail(std::string("GL error ") + std::to_string(err) + " in " + where);
}

struct MeshBuffers {
    GLuint vao = 0, vertices = 0, indices = 0;
    GLsizei indexCount = 0;
};

MeshBuffers uploadMesh(const GlMesh& mesh) {
    // Interleaved position + normal: one stream, as an engine would lay it out.
    std::vector<float> interleaved;
    interleaved.reserve(mesh.positions.size() * 6);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        glm::vec3 n = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0, 1, 0);
        interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    MeshBuffers b;
    b.indexCount = GLsizei(mesh.indices.size());
    glGenVertexArrays(1, &b.vao);
    glBindVertexArray(b.vao);
    glGenBuffers(1, &b.vertices);
    glBindBuffer(GL_ARRAY_BUFFER, b.vertices);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(interleaved.size() * sizeof(float)),
                 interleaved.data(), GL_STATIC_DRAW);
    glGenBuffers(1, &b.indices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.indices);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    glBindVertexArray(0);
    return b;
}

void setCulling(bool doubleSided) {
    if (doubleSided) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
}

GLint loc(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

void setMat4(GLuint program, const char* name, const glm::mat4& m) {
    glUniformMatrix4fv(loc(program, name), 1, GL_FALSE, &m[0][0]);
}

// The bound framebuffer's `source` (a colour attachment, or GL_NONE for depth) as w x h
// values, rows top-down: GL's row 0 is the bottom one, ssrt's the top one.
template <class T>
std::vector<T> readPixels(GLenum source, int w, int h, GLenum format, GLenum type) {
    glReadBuffer(source);
    std::vector<T> bottomUp(std::size_t(w) * std::size_t(h));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, format, type, bottomUp.data());
    checkGlError("read-back");
    std::vector<T> topDown(bottomUp.size());
    for (int y = 0; y < h; ++y)
        std::copy_n(bottomUp.begin() + std::ptrdiff_t(h - 1 - y) * w, w,
                    topDown.begin() + std::ptrdiff_t(y) * w);
    return topDown;
}

GLuint makeFramebuffer(const char* which, int colourTargets, const GLuint* colour, GLuint depth) {
    static const GLenum kAttachments[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                           GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    for (int i = 0; i < colourTargets; ++i)
        glFramebufferTexture2D(GL_FRAMEBUFFER, kAttachments[i], GL_TEXTURE_2D, colour[i], 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
    if (colourTargets > 0) {
        glDrawBuffers(colourTargets, kAttachments);
    } else {
        glDrawBuffer(GL_NONE);
        glReadBuffer(GL_NONE);
    }
    checkFramebuffer(which);
    return fbo;
}

}  // namespace

struct GlWorkloads::Impl {
    GlSceneDesc desc;
    int width = 0, height = 0, shadowSize = 0;
    std::vector<MeshBuffers> meshes;
    std::vector<uint32_t> firstTriangle;  // per draw, then the total (firstTriangles)
    GLuint shadowProgram = 0, gbufferProgram = 0, idProgram = 0;
    GLuint shadowFbo = 0, shadowDepth = 0;
    GLuint gbufferFbo = 0, gbufferDepth = 0;
    GLuint targets[4] = {};
    GLuint idFbo = 0, idDepth = 0;
    GLuint idTargets[2] = {};  // linear depth R32F, triangle id R32UI

    void makeShadowTarget();
    void makeGBufferTargets();
    void makeIdTargets();
    // Camera and per-draw uniforms of `program` (the G-buffer's vertex shader), then every
    // draw; `ids`: also each draw's first triangle id.
    void drawCameraView(GLuint program, bool ids);
    void drawMesh(const GlDraw& d, bool cull) {
        const MeshBuffers& b = meshes.at(d.mesh);
        if (cull) setCulling(d.doubleSided);
        glBindVertexArray(b.vao);
        glDrawElements(GL_TRIANGLES, b.indexCount, GL_UNSIGNED_INT, nullptr);
    }
};

void GlWorkloads::Impl::makeShadowTarget() {
    shadowDepth =
        makeTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, shadowSize, shadowSize);
    shadowFbo = makeFramebuffer("shadow-map", 0, nullptr, shadowDepth);
}

void GlWorkloads::Impl::makeGBufferTargets() {
    targets[0] = makeTexture(GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, width, height);   // N + rough
    targets[1] = makeTexture(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height);  // albedo + m
    targets[2] = makeTexture(GL_RG16F, GL_RG, GL_HALF_FLOAT, width, height);       // motion
    targets[3] = makeTexture(GL_R32F, GL_RED, GL_FLOAT, width, height);            // lin. depth
    gbufferDepth = makeTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, width, height);
    gbufferFbo = makeFramebuffer("G-buffer", 4, targets, gbufferDepth);
}

void GlWorkloads::Impl::makeIdTargets() {
    idTargets[0] = makeTexture(GL_R32F, GL_RED, GL_FLOAT, width, height);
    idTargets[1] = makeTexture(GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, width, height);
    idDepth = makeTexture(GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, width, height);
    idFbo = makeFramebuffer("id", 2, idTargets, idDepth);
}

void GlWorkloads::Impl::drawCameraView(GLuint p, bool ids) {
    glViewport(0, 0, width, height);
    glUseProgram(p);
    setMat4(p, "uView", desc.view);
    setMat4(p, "uProj", desc.projection);
    setMat4(p, "uPrevView", desc.previousView);
    setMat4(p, "uPrevProj", desc.previousProjection);
    glUniform2f(loc(p, "uViewport"), float(width), float(height));
    for (std::size_t i = 0; i < desc.draws.size(); ++i) {
        const GlDraw& d = desc.draws[i];
        setMat4(p, "uModel", d.model);
        setMat4(p, "uPrevModel", d.previousModel);
        glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(d.model)));
        glUniformMatrix3fv(loc(p, "uNormalMatrix"), 1, GL_FALSE, &normalMatrix[0][0]);
        glUniform3f(loc(p, "uAlbedo"), d.albedo.x, d.albedo.y, d.albedo.z);
        glUniform1f(loc(p, "uMetallic"), d.metallic);
        glUniform1f(loc(p, "uRoughness"), d.roughness);
        if (ids) glUniform1ui(loc(p, "uFirstTriangle"), firstTriangle[i]);
        drawMesh(d, /*cull=*/true);
    }
}

GlWorkloads::GlWorkloads(const GlSceneDesc& desc, int width, int height, int shadowSize)
    : impl_(std::make_unique<Impl>()) {
    Impl& s = *impl_;
    s.desc = desc;
    s.width = width;
    s.height = height;
    s.shadowSize = shadowSize;
    s.firstTriangle = firstTriangles(desc);
    for (const GlMesh& m : desc.meshes) s.meshes.push_back(uploadMesh(m));
    s.shadowProgram = linkProgram(kShadowVs, kShadowFs);
    s.gbufferProgram = linkProgram(kGBufferVs, kGBufferFs);
    s.idProgram = linkProgram(kGBufferVs, kIdFs);
    s.makeShadowTarget();
    s.makeGBufferTargets();
    s.makeIdTargets();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glFrontFace(GL_CCW);  // counter-clockwise = front, as in the scene model
    checkGlError("set-up");
}

GlWorkloads::~GlWorkloads() {
    Impl& s = *impl_;
    for (MeshBuffers& b : s.meshes) {
        glDeleteVertexArrays(1, &b.vao);
        glDeleteBuffers(1, &b.vertices);
        glDeleteBuffers(1, &b.indices);
    }
    glDeleteFramebuffers(1, &s.shadowFbo);
    glDeleteFramebuffers(1, &s.gbufferFbo);
    glDeleteFramebuffers(1, &s.idFbo);
    glDeleteTextures(4, s.targets);
    glDeleteTextures(2, s.idTargets);
    glDeleteTextures(1, &s.shadowDepth);
    glDeleteTextures(1, &s.gbufferDepth);
    glDeleteTextures(1, &s.idDepth);
    glDeleteProgram(s.shadowProgram);
    glDeleteProgram(s.gbufferProgram);
    glDeleteProgram(s.idProgram);
}

void GlWorkloads::drawShadow() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.shadowFbo);
    glViewport(0, 0, s.shadowSize, s.shadowSize);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUseProgram(s.shadowProgram);
    setMat4(s.shadowProgram, "uLightViewProj", s.desc.lightViewProjection);
    GLint modelLoc = loc(s.shadowProgram, "uModel");
    // Every face casts a shadow: ssrt draws back faces into its shadow map too.
    glDisable(GL_CULL_FACE);
    for (const GlDraw& d : s.desc.draws) {
        glUniformMatrix4fv(modelLoc, 1, GL_FALSE, &d.model[0][0]);
        s.drawMesh(d, /*cull=*/false);
    }
}

void GlWorkloads::drawGBuffer() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.gbufferFbo);
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; ++i) glClearBufferfv(GL_COLOR, i, zero);
    const float one = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &one);
    s.drawCameraView(s.gbufferProgram, /*ids=*/false);
}

void GlWorkloads::drawIds() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.idFbo);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    const GLuint none[4] = {kNoTriangle, kNoTriangle, kNoTriangle, kNoTriangle};
    glClearBufferuiv(GL_COLOR, 1, none);
    const float one = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &one);
    s.drawCameraView(s.idProgram, /*ids=*/true);
    checkGlError("id pass");
}

std::vector<float> GlWorkloads::readShadowDepth() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.shadowFbo);
    return readPixels<float>(GL_NONE, s.shadowSize, s.shadowSize, GL_DEPTH_COMPONENT, GL_FLOAT);
}

std::vector<float> GlWorkloads::readLinearDepth() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.gbufferFbo);
    return readPixels<float>(GL_COLOR_ATTACHMENT3, s.width, s.height, GL_RED, GL_FLOAT);
}

std::vector<float> GlWorkloads::readIdPassDepth() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.idFbo);
    return readPixels<float>(GL_COLOR_ATTACHMENT0, s.width, s.height, GL_RED, GL_FLOAT);
}

std::vector<uint32_t> GlWorkloads::readIdPassTriangles() {
    Impl& s = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, s.idFbo);
    return readPixels<uint32_t>(GL_COLOR_ATTACHMENT1, s.width, s.height, GL_RED_INTEGER,
                                GL_UNSIGNED_INT);
}

double glFinishAndNowMs() {
    glFinish();
    using Clock = std::chrono::steady_clock;
    return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

double medianOf(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace peer
