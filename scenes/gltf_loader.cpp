#include "scenes/gltf_loader.h"

// Debian's tinygltf is a shared library built with its own JSON and image code; we only
// include the declarations and replace its image decoding: textures are decoded through
// OpenImageIO (scenes/gltf_textures.h).
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <iterator>
#include <limits>
#include <new>
#include <optional>
#include <set>

#include "scenes/gltf_camera.h"
#include "scenes/gltf_compression.h"
#include "scenes/gltf_textures.h"
#include "scenes/mesh_builders.h"

namespace ssrt {
namespace {

namespace fs = std::filesystem;

// Collapses tinygltf's multi-line reports into one line.
std::string oneLine(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            if (!out.empty() && out.back() != ' ') out += "; ";
        } else {
            out += c;
        }
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
    return out;
}

// What the conversion drops, counted as it goes; warningLines() turns it into one line per
// kind at the end.
struct Notes {
    std::size_t skippedPrimitives = 0;  // POINTS, LINES, LINE_LOOP, LINE_STRIP
    std::size_t pointLights = 0, spotLights = 0, otherLights = 0, extraDirectional = 0;
    int usedCamera = -1;
    std::set<int> extraCameras, orthographicCameras;
    gltf::CameraPlacement placement;          // of the camera used
    std::vector<std::size_t> blendMaterials;  // alphaMode BLEND, drawn as MASK
    std::size_t vertexColours = 0, morphTargets = 0;
};

// Everything the conversion needs to name the file in its errors, and what it drops.
struct Context {
    std::string path;
    const tinygltf::Model& model;
    gltf::TextureTable& textures;
    Notes& notes;

    [[noreturn]] void fail(const std::string& problem) const {
        throw SceneLoadError(path + ": " + oneLine(problem));
    }
};

std::string str(std::size_t n) { return std::to_string(n); }

// "a", "a and b", "a, b and c".
std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (i > 0) out += i + 1 == items.size() ? " and " : ", ";
        out += items[i];
    }
    return out;
}

// "1 point light", "2 point lights".
std::string counted(std::size_t n, const std::string& noun) {
    return str(n) + " " + noun + (n == 1 ? "" : "s");
}

// "material 2", "materials 0, 1 and 3".
template <class Indices>
std::string named(const std::string& noun, const Indices& indices) {
    std::vector<std::string> items;
    for (auto i : indices) items.push_back(std::to_string(i));
    return noun + (items.size() == 1 ? " " : "s ") + joined(items);
}

// ---------------------------------------------------------------------------------------
// tinygltf silently skips a top-level member of the wrong JSON type ("meshes": 5 reads as
// no meshes), so the top level is checked here. The text has already parsed as JSON; this
// scanner only needs to step over values, and stops at anything unexpected.

std::size_t skipSpace(const std::string& s, std::size_t i) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    return i;
}

std::size_t skipString(const std::string& s, std::size_t i) {  // i at the opening quote
    for (++i; i < s.size() && s[i] != '"'; ++i)
        if (s[i] == '\\') ++i;
    return i + 1;
}

std::size_t skipValue(const std::string& s, std::size_t i) {
    int depth = 0;
    for (; i < s.size(); ++i) {
        const char c = s[i];
        if (c == '"') {
            i = skipString(s, i) - 1;
        } else if (c == '[' || c == '{') {
            ++depth;
        } else if (c == ']' || c == '}') {
            if (depth == 0) return i;
            if (--depth == 0) return i + 1;
        } else if (c == ',' && depth == 0) {
            return i;
        }
        if (depth == 0 && c == '"') return i + 1;
    }
    return i;
}

// The first problem found, or "" when every known top-level member has its glTF type.
std::string topLevelTypeProblem(const std::string& json) {
    static const char* arrays[] = {"accessors", "animations", "buffers", "bufferViews", "cameras",
                                   "images",    "materials",  "meshes",  "nodes",       "samplers",
                                   "scenes",    "skins",      "textures"};
    std::size_t i = skipSpace(json, 0);
    if (i >= json.size() || json[i] != '{') return "the top level is not a JSON object";
    for (i = skipSpace(json, i + 1); i < json.size() && json[i] == '"';) {
        const std::size_t end = skipString(json, i);
        const std::string key = json.substr(i + 1, end - i - 2);
        i = skipSpace(json, end);
        if (i >= json.size() || json[i] != ':') break;
        i = skipSpace(json, i + 1);
        const char first = i < json.size() ? json[i] : ' ';
        for (const char* name : arrays)
            if (key == name && first != '[') return "\"" + key + "\" must be a JSON array";
        if (key == "scene" && !(std::isdigit(static_cast<unsigned char>(first)) || first == '-'))
            return "\"scene\" must be a number";
        i = skipSpace(json, skipValue(json, i));
        if (i < json.size() && json[i] == ',') i = skipSpace(json, i + 1);
    }
    return "";
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (already validated by tinygltf).
std::string jsonText(const std::string& bytes, bool binary) {
    if (!binary) return bytes;
    if (bytes.size() < 20) return "";
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return bytes.substr(20, std::min<std::size_t>(length, bytes.size() - 20));
}

// tinygltf's own base directory for a file's relative URIs (GetBaseDir in tiny_gltf.h), so a
// file parsed from memory resolves them as one read from disk.
std::string baseDir(const std::string& path) {
    const std::size_t slash = path.find_last_of("/\\");
    return slash == std::string::npos ? "" : path.substr(0, slash);
}

// Compressed files (scenes/gltf_compression.h) are parsed from their adjusted bytes; every
// other file as tinygltf reads it from disk. Then compressed data is decoded.
tinygltf::Model readModel(const std::string& path, gltf::DataUriImages& dataUris) {
    std::string bytes;
    {
        errno = 0;
        std::ifstream in(path, std::ios::binary);
        // (errno holds the OS's reason where the open set one: "No such file or directory".)
        if (!in)
            throw SceneLoadError(path + ": cannot open file" +
                                 (errno ? " (" + std::string(std::strerror(errno)) + ")" : ""));
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(gltf::keepDataUriImage, &dataUris);
    tinygltf::Model model;
    std::string err, warn;
    // The container is chosen by content, not by extension: a renamed file still loads.
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    gltf::CompressionFixups fixups;
    const std::optional<std::string> fixed = gltf::withCompressionFixups(bytes, binary, &fixups);
    if (fixed && fixed->size() > std::numeric_limits<unsigned>::max())
        throw SceneLoadError(path + ": file too large (tinygltf reads at most 4 GiB)");
    bool ok = false;
    if (fixed && binary)
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn,
                                         reinterpret_cast<const unsigned char*>(fixed->data()),
                                         unsigned(fixed->size()), baseDir(path));
    else if (fixed)
        ok = loader.LoadASCIIFromString(&model, &err, &warn, fixed->data(), unsigned(fixed->size()),
                                        baseDir(path));
    else
        ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                    : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok || !err.empty())
        throw SceneLoadError(path + ": " + oneLine(err.empty() ? "cannot parse glTF" : err));
    const std::string problem = topLevelTypeProblem(jsonText(bytes, binary));
    if (!problem.empty()) throw SceneLoadError(path + ": wrong JSON type: " + problem);
    gltf::decompress(model, fixups);
    return model;
}

// ---------------------------------------------------------------------------------------
// Accessors: every byte read is bounds-checked first, and read with memcpy (no alignment
// assumptions about the buffer).

struct AccessorView {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;
};

std::size_t componentBytes(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

AccessorView viewAccessor(const Context& ctx, int index, const std::string& role, int type) {
    const tinygltf::Model& m = ctx.model;
    const std::string name = "accessor " + std::to_string(index) + " (" + role + ")";
    if (index < 0 || std::size_t(index) >= m.accessors.size())
        ctx.fail(name + ": no such accessor (" + str(m.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = m.accessors[index];
    if (a.type != type) ctx.fail(name + ": wrong type for " + role);
    if (a.sparse.isSparse) ctx.fail(name + ": sparse accessors are not supported");
    const std::size_t compBytes = componentBytes(a.componentType);
    if (compBytes == 0)
        ctx.fail(name + ": invalid component type " + std::to_string(a.componentType));
    if (a.bufferView < 0 || std::size_t(a.bufferView) >= m.bufferViews.size())
        ctx.fail(name + ": bufferView " + std::to_string(a.bufferView) + " out of range");
    const tinygltf::BufferView& bv = m.bufferViews[a.bufferView];
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size())
        ctx.fail(name + ": buffer " + std::to_string(bv.buffer) + " out of range");
    const std::vector<unsigned char>& buf = m.buffers[bv.buffer].data;
    if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
        ctx.fail(name + ": bufferView " + std::to_string(a.bufferView) + " overruns its buffer (" +
                 str(buf.size()) + " bytes)");

    const int components = tinygltf::GetNumComponentsInType(a.type);
    const std::size_t elemBytes = compBytes * std::size_t(components);
    const std::size_t stride = bv.byteStride == 0 ? elemBytes : bv.byteStride;
    if (stride < elemBytes) ctx.fail(name + ": byteStride smaller than an element");
    // count * stride can overflow; compare by division instead.
    const std::size_t avail = bv.byteLength;
    const bool fits =
        a.count == 0 || (a.byteOffset <= avail && elemBytes <= avail - a.byteOffset &&
                         (a.count - 1) <= (avail - a.byteOffset - elemBytes) / stride);
    if (!fits)
        ctx.fail(name + ": count " + str(a.count) + " overruns bufferView " +
                 std::to_string(a.bufferView) + " (" + str(avail) + " bytes)");
    return {buf.data() + bv.byteOffset + a.byteOffset,
            a.count,
            stride,
            a.componentType,
            components,
            a.normalized};
}

template <class T>
T load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

// A component as a float: float as stored; integers as glTF 2.0's equations decode
// normalized ones (c / 255, c / 65535, max(c / 127, -1), max(c / 32767, -1), each one
// correctly rounded float division), and as their value when not normalized.
float readComponent(const AccessorView& v, std::size_t element, int component) {
    const unsigned char* p = v.data + element * v.stride;
    switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p + 4 * component);
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float c = float(load<int8_t>(p + component));
            return v.normalized ? std::max(c / 127.0f, -1.0f) : c;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float c = float(p[component]);
            return v.normalized ? c / 255.0f : c;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float c = float(load<int16_t>(p + 2 * component));
            return v.normalized ? std::max(c / 32767.0f, -1.0f) : c;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float c = float(load<uint16_t>(p + 2 * component));
            return v.normalized ? c / 65535.0f : c;
        }
        default: return 0.0f;
    }
}

// The vertex attributes read here and the component types each may have.
enum class Semantic { Position, Normal, Tangent, Texcoord };

const char* componentTypeName(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return "unknown";
    }
}

// What glTF 2.0 (section 3.7.2.1) allows for the attribute, and what KHR_mesh_quantization
// adds: POSITION and TEXCOORD_n any 8- or 16-bit integer, normalized or not; NORMAL and
// TANGENT normalized BYTE or SHORT.
bool coreAllows(Semantic s, int type, bool normalized) {
    if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
    return s == Semantic::Texcoord && normalized &&
           (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
            type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

bool quantizationAllows(Semantic s, int type, bool normalized) {
    const bool signedType =
        type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_SHORT;
    const bool integer = signedType || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
    if (s == Semantic::Position || s == Semantic::Texcoord) return integer;
    return signedType && normalized;
}

const char* coreChoices(Semantic s) {
    return s == Semantic::Texcoord ? "FLOAT, normalized UNSIGNED_BYTE or normalized UNSIGNED_SHORT"
                                   : "only FLOAT";
}

const char* quantizationChoices(Semantic s) {
    return s == Semantic::Position || s == Semantic::Texcoord
               ? "FLOAT or BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT, normalized or not"
               : "FLOAT, normalized BYTE or normalized SHORT";
}

bool usesQuantization(const tinygltf::Model& m) {
    const auto has = [](const std::vector<std::string>& list) {
        return std::find(list.begin(), list.end(), "KHR_mesh_quantization") != list.end();
    };
    return has(m.extensionsUsed) || has(m.extensionsRequired);
}

// An accessor's component type that the attribute may not have is an error that says what
// it may have, and whether KHR_mesh_quantization would allow it.
void checkComponentType(const Context& ctx, int index, const std::string& role, Semantic s,
                        const AccessorView& v) {
    const bool quantized = usesQuantization(ctx.model);
    if (coreAllows(s, v.componentType, v.normalized) ||
        (quantized && quantizationAllows(s, v.componentType, v.normalized)))
        return;
    const std::string type = std::string(v.normalized ? "normalized " : "") +
                             componentTypeName(v.componentType) + " (" +
                             std::to_string(v.componentType) + ")";
    const std::string name = "accessor " + std::to_string(index) + " (" + role + "): ";
    if (!quantized && quantizationAllows(s, v.componentType, v.normalized))
        ctx.fail(name + "component type " + type +
                 " needs KHR_mesh_quantization, which the file does not declare (glTF 2.0 "
                 "alone allows " +
                 coreChoices(s) + " for " + role + ")");
    ctx.fail(name + "component type " + type + " is not allowed for " + role + " (" +
             (quantized ? std::string("KHR_mesh_quantization allows ") + quantizationChoices(s)
                        : std::string("glTF 2.0 allows ") + coreChoices(s)) +
             ")");
}

template <int N>
std::vector<glm::vec<N, float>> readVectors(const Context& ctx, int index, const std::string& role,
                                            Semantic semantic) {
    const AccessorView v = viewAccessor(ctx, index, role,
                                        N == 2   ? TINYGLTF_TYPE_VEC2
                                        : N == 3 ? TINYGLTF_TYPE_VEC3
                                                 : TINYGLTF_TYPE_VEC4);
    checkComponentType(ctx, index, role, semantic, v);
    std::vector<glm::vec<N, float>> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
        for (int c = 0; c < N; ++c) {
            const float x = readComponent(v, i, c);
            // One bad vertex poisons bounds, the camera fit and every pass: reject the file.
            if (!std::isfinite(x))
                ctx.fail("accessor " + std::to_string(index) + " (" + role +
                         "): non-finite value (NaN or infinity) at element " + str(i));
            out[i][c] = x;
        }
    }
    return out;
}

std::vector<uint32_t> readIndices(const Context& ctx, int index, std::size_t vertexCount) {
    const AccessorView v = viewAccessor(ctx, index, "indices", TINYGLTF_TYPE_SCALAR);
    std::vector<uint32_t> out(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
        const unsigned char* p = v.data + i * v.stride;
        switch (v.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = p[0]; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: out[i] = load<uint16_t>(p); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: out[i] = load<uint32_t>(p); break;
            default:
                ctx.fail("accessor " + std::to_string(index) +
                         " (indices): component type must be an unsigned integer");
        }
        if (out[i] >= vertexCount)
            ctx.fail("accessor " + std::to_string(index) + " (indices): index " +
                     std::to_string(out[i]) + " out of range (" + str(vertexCount) + " vertices)");
    }
    return out;
}

// ---------------------------------------------------------------------------------------
// Primitives

// glTF 2.0 section 3.7.2.1 gives the triangle order of strips and fans; following it keeps
// the winding (and so front faces) the author meant.
std::vector<uint32_t> triangulate(const Context& ctx, const std::string& name, int mode,
                                  const std::vector<uint32_t>& v) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (v.size() % 3 != 0)
            ctx.fail(name + ": " + str(v.size()) + " vertices is not a multiple of 3");
        return v;
    }
    for (std::size_t i = 0; i + 2 < v.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const std::size_t odd = i % 2;
            out.insert(out.end(), {v[i], v[i + 1 + odd], v[i + 2 - odd]});
        } else {
            out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
        }
    }
    return out;
}

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        default: return "unknown";
    }
}

int attribute(const tinygltf::Primitive& p, const char* key) {
    const auto it = p.attributes.find(key);
    return it == p.attributes.end() ? -1 : it->second;
}

int primitiveMode(const tinygltf::Primitive& p) {
    return p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
}

bool isPointOrLine(int mode) {
    return mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
           mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP;
}

Mesh convertPrimitive(const Context& ctx, const std::string& name, const tinygltf::Primitive& p) {
    const int mode = primitiveMode(p);
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        ctx.fail(name + ": mode " + modeName(mode) +
                 " is not supported (only triangles, strips and fans)");
    if (attribute(p, "COLOR_0") >= 0) ++ctx.notes.vertexColours;
    if (!p.targets.empty()) ++ctx.notes.morphTargets;
    const int pos = attribute(p, "POSITION");
    if (pos < 0) ctx.fail(name + ": no POSITION attribute");

    Mesh mesh;
    mesh.name = name;
    mesh.positions = readVectors<3>(ctx, pos, "POSITION", Semantic::Position);
    std::vector<uint32_t> order;
    if (p.indices >= 0) {
        order = readIndices(ctx, p.indices, mesh.positions.size());
    } else {
        order.resize(mesh.positions.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = uint32_t(i);
    }
    mesh.indices = triangulate(ctx, name, mode, order);

    const int nrm = attribute(p, "NORMAL");
    if (nrm >= 0) {
        mesh.normals = readVectors<3>(ctx, nrm, "NORMAL", Semantic::Normal);
        if (mesh.normals.size() != mesh.positions.size())
            ctx.fail(name + ": NORMAL count differs from POSITION count");
        for (glm::vec3& n : mesh.normals) {
            const float len = glm::length(n);
            n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
        }
    } else {
        mesh.normals = smoothNormals(mesh);
    }
    const int uv = attribute(p, "TEXCOORD_0");
    if (uv >= 0) {
        mesh.uvs = readVectors<2>(ctx, uv, "TEXCOORD_0", Semantic::Texcoord);
        if (mesh.uvs.size() != mesh.positions.size())
            ctx.fail(name + ": TEXCOORD_0 count differs from POSITION count");
    }
    const int uv1 = attribute(p, "TEXCOORD_1");
    if (uv1 >= 0) {
        mesh.uvs1 = readVectors<2>(ctx, uv1, "TEXCOORD_1", Semantic::Texcoord);
        if (mesh.uvs1.size() != mesh.positions.size())
            ctx.fail(name + ": TEXCOORD_1 count differs from POSITION count");
    }
    const int tan = attribute(p, "TANGENT");
    if (tan >= 0) {
        mesh.tangents = readVectors<4>(ctx, tan, "TANGENT", Semantic::Tangent);
        if (mesh.tangents.size() != mesh.positions.size())
            ctx.fail(name + ": TANGENT count differs from POSITION count");
        // xyz unit and w = +-1, as the specification requires of the file (lenient on
        // rounding: w's sign is what counts).
        for (glm::vec4& t : mesh.tangents) {
            const glm::vec3 d(t);
            const float len = glm::length(d);
            t = glm::vec4(len > 0.0f ? d / len : d, t.w < 0.0f ? -1.0f : 1.0f);
        }
    }
    return mesh;
}

// ---------------------------------------------------------------------------------------
// Materials and textures

// Every texture a material names must exist: a scene never renders silently without its
// textures.
void checkTexture(const Context& ctx, const std::string& name, int textureIndex) {
    if (textureIndex < 0) return;
    const tinygltf::Model& m = ctx.model;
    if (std::size_t(textureIndex) >= m.textures.size())
        ctx.fail(name + ": texture " + std::to_string(textureIndex) + " does not exist");
    const int source = m.textures[textureIndex].source;
    if (source < 0 || std::size_t(source) >= m.images.size())
        ctx.fail(name + ": texture " + std::to_string(textureIndex) + " has no image (source " +
                 std::to_string(source) + ")");
    const tinygltf::Image& img = m.images[source];
    if (img.bufferView >= 0 || img.uri.empty() || img.uri.rfind("data:", 0) == 0) return;
    const fs::path file = fs::path(ctx.path).parent_path() / gltf::percentDecoded(img.uri);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        ctx.fail(name + ": texture image " + std::to_string(source) +
                 " file not found: " + file.string());
}

glm::vec3 finiteColor(const Context& ctx, const std::string& name, const char* what,
                      const std::vector<double>& v, std::size_t n) {
    if (v.size() < n) ctx.fail(name + ": " + what + " needs " + str(n) + " numbers");
    glm::vec3 c(0.0f);
    for (std::size_t i = 0; i < 3; ++i) {
        if (!std::isfinite(v[i])) ctx.fail(name + ": " + what + " is not finite");
        c[i] = float(v[i]);
    }
    return c;
}

float unitFactor(const Context& ctx, const std::string& name, const char* what, double v) {
    if (!std::isfinite(v)) ctx.fail(name + ": " + what + " is not finite");
    return float(std::clamp(v, 0.0, 1.0));
}

// The scene texture for a material's texture slot, or -1 when the slot is empty, and the
// slot's UV transform (KHR_texture_transform).
int32_t texture(const Context& ctx, const std::string& name, const tinygltf::TextureInfo& info,
                TextureEncoding encoding, UvTransform* uv) {
    if (info.index < 0) return -1;
    try {
        int texCoord = 0;
        *uv = gltf::textureTransform(info, &texCoord);
        uv->set = texCoord;
        return ctx.textures.get(info.index, texCoord, encoding);
    } catch (const std::runtime_error& e) {
        ctx.fail(name + ": " + e.what());
    }
}

// KHR_materials_emissive_strength's factor on emissiveFactor (1 when absent).
float emissiveStrength(const Context& ctx, const std::string& name, const tinygltf::Material& g) {
    const auto it = g.extensions.find("KHR_materials_emissive_strength");
    if (it == g.extensions.end()) return 1.0f;
    const tinygltf::Value& ext = it->second;
    if (!ext.IsObject()) ctx.fail(name + ": KHR_materials_emissive_strength must be an object");
    if (!ext.Has("emissiveStrength")) return 1.0f;
    const tinygltf::Value& v = ext.Get("emissiveStrength");
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()) || v.GetNumberAsDouble() < 0.0)
        ctx.fail(name + ": emissiveStrength must be a finite number, not negative");
    return float(v.GetNumberAsDouble());
}

// alphaMode and alphaCutoff (glTF 2.0 section 3.9.4), and baseColorFactor's alpha. BLEND is
// drawn as MASK at the default cutoff 0.5 (the specification has the cutoff ignored outside
// MASK): a cut where coverage is one half, which keeps the holes' sizes. True blending would
// need a forward pass over sorted layers, which a deferred G-buffer of one surface per pixel
// (and the SSR, SSGI and denoiser passes that read it) does not have; the warning says what
// is drawn instead.
void convertAlpha(const Context& ctx, std::size_t index, const std::string& name,
                  const tinygltf::Material& g, Material& m) {
    m.baseColorAlpha =
        unitFactor(ctx, name, "baseColorFactor's alpha", g.pbrMetallicRoughness.baseColorFactor[3]);
    if (g.alphaMode == "OPAQUE") return;
    if (g.alphaMode == "BLEND") {
        m.alphaMode = Material::AlphaMode::Blend;
        ctx.notes.blendMaterials.push_back(index);
        return;
    }
    if (g.alphaMode != "MASK")
        ctx.fail(name + ": alphaMode '" + g.alphaMode + "' is not OPAQUE, MASK or BLEND");
    if (!std::isfinite(g.alphaCutoff) || g.alphaCutoff < 0.0)
        ctx.fail(name + ": alphaCutoff must be a finite number, not negative");
    m.alphaMode = Material::AlphaMode::Mask;
    m.alphaCutoff = float(g.alphaCutoff);
}

// The normal and occlusion references as plain texture references (index, texCoord and
// extensions: what textureTransform and the texture table read).
template <class Info>
tinygltf::TextureInfo plainTextureInfo(const Info& info) {
    tinygltf::TextureInfo t;
    t.index = info.index;
    t.texCoord = info.texCoord;
    t.extensions = info.extensions;
    return t;
}

float finiteFactor(const Context& ctx, const std::string& name, const char* what, double v) {
    if (!std::isfinite(v)) ctx.fail(name + ": " + what + " is not finite");
    return float(v);
}

// glTF 2.0 sections 3.9.3-3.9.5: the normal texture with its scale (linear), the occlusion
// texture with its strength (linear, R; clamped to [0, 1] as the specification bounds it)
// and the emissive texture (sRGB), each with its texCoord and KHR_texture_transform.
void convertMaterialMaps(const Context& ctx, const std::string& name, const tinygltf::Material& g,
                         Material& m) {
    m.normalTexture =
        texture(ctx, name, plainTextureInfo(g.normalTexture), TextureEncoding::Linear, &m.normalUv);
    m.normalScale = finiteFactor(ctx, name, "normalTexture.scale", g.normalTexture.scale);
    m.occlusionTexture = texture(ctx, name, plainTextureInfo(g.occlusionTexture),
                                 TextureEncoding::Linear, &m.occlusionUv);
    m.occlusionStrength =
        unitFactor(ctx, name, "occlusionTexture.strength", g.occlusionTexture.strength);
    m.emissiveTexture = texture(ctx, name, g.emissiveTexture, TextureEncoding::Srgb, &m.emissiveUv);
}

Material convertMaterial(const Context& ctx, std::size_t index) {
    const tinygltf::Material& g = ctx.model.materials[index];
    const std::string name = "material " + str(index);
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    Material m;
    m.name = g.name.empty() ? name : g.name;
    m.baseColor = finiteColor(ctx, name, "baseColorFactor", pbr.baseColorFactor, 4);
    m.metallic = unitFactor(ctx, name, "metallicFactor", pbr.metallicFactor);
    m.roughness = unitFactor(ctx, name, "roughnessFactor", pbr.roughnessFactor);
    m.emissive = finiteColor(ctx, name, "emissiveFactor", g.emissiveFactor, 3);
    m.emissive *= emissiveStrength(ctx, name, g);
    m.doubleSided = g.doubleSided;
    checkTexture(ctx, name, pbr.baseColorTexture.index);
    checkTexture(ctx, name, pbr.metallicRoughnessTexture.index);
    checkTexture(ctx, name, g.emissiveTexture.index);
    checkTexture(ctx, name, g.normalTexture.index);
    checkTexture(ctx, name, g.occlusionTexture.index);
    convertAlpha(ctx, index, name, g, m);
    m.baseColorTexture =
        texture(ctx, name, pbr.baseColorTexture, TextureEncoding::Srgb, &m.baseColorUv);
    m.metallicRoughnessTexture = texture(ctx, name, pbr.metallicRoughnessTexture,
                                         TextureEncoding::Linear, &m.metallicRoughnessUv);
    convertMaterialMaps(ctx, name, g, m);
    return m;
}

// The material glTF prescribes for primitives without one (spec section 3.9.6).
Material defaultMaterial() {
    Material m;
    m.name = "glTF default";
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.roughness = 1.0f;
    return m;
}

// ---------------------------------------------------------------------------------------
// Meshes: one ssrt Mesh per glTF primitive, converted once however many nodes use it.

struct Part {
    uint32_t mesh;
    uint32_t material;
};

std::vector<std::vector<Part>> convertMeshes(const Context& ctx, Scene& scene) {
    const tinygltf::Model& m = ctx.model;
    if (m.meshes.empty()) ctx.fail("no meshes in the file");
    for (std::size_t i = 0; i < m.materials.size(); ++i)
        scene.materials.push_back(convertMaterial(ctx, i));
    std::optional<uint32_t> fallback;
    std::vector<std::vector<Part>> parts(m.meshes.size());
    for (std::size_t i = 0; i < m.meshes.size(); ++i) {
        const std::vector<tinygltf::Primitive>& prims = m.meshes[i].primitives;
        for (std::size_t k = 0; k < prims.size(); ++k) {
            const std::string name = "mesh " + str(i) + " primitive " + str(k);
            const int mat = prims[k].material;
            if (mat >= int(m.materials.size()))
                ctx.fail(name + ": material " + std::to_string(mat) + " does not exist");
            if (mat < 0 && !fallback) {
                fallback = uint32_t(scene.materials.size());
                scene.materials.push_back(defaultMaterial());
            }
            if (isPointOrLine(primitiveMode(prims[k]))) {  // skipped: a warning, not an error
                ++ctx.notes.skippedPrimitives;
                continue;
            }
            scene.meshes.push_back(convertPrimitive(ctx, name, prims[k]));
            parts[i].push_back(
                {uint32_t(scene.meshes.size() - 1), mat < 0 ? *fallback : uint32_t(mat)});
        }
    }
    return parts;
}

// ---------------------------------------------------------------------------------------
// Nodes

glm::mat4 localTransform(const Context& ctx, std::size_t index) {
    const tinygltf::Node& n = ctx.model.nodes[index];
    const std::string name = "node " + str(index);
    auto finite = [&](const std::vector<double>& v, std::size_t size, const char* what) {
        if (!v.empty() && v.size() != size)
            ctx.fail(name + ": " + what + " needs " + str(size) + " numbers");
        for (double x : v)
            if (!std::isfinite(x)) ctx.fail(name + ": " + what + " is not finite");
    };
    finite(n.matrix, 16, "matrix");
    finite(n.translation, 3, "translation");
    finite(n.rotation, 4, "rotation");
    finite(n.scale, 3, "scale");
    if (!n.matrix.empty()) {
        glm::mat4 m;  // glTF matrices are column-major, like glm's
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[i]);
        return m;
    }
    glm::mat4 t(1.0f);
    if (!n.translation.empty())
        t = glm::translate(t, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
    if (!n.rotation.empty()) {  // glTF stores (x, y, z, w); glm's constructor takes w first
        const glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                          float(n.rotation[2]));
        t = t * glm::mat4_cast(glm::normalize(q));
    }
    if (!n.scale.empty()) t = glm::scale(t, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
    return t;
}

struct Walk {
    const Context& ctx;
    const std::vector<std::vector<Part>>& parts;
    Scene& scene;
    bool haveCamera = false;
    bool haveLight = false;
    float cameraFar = 0.0f;  // 0: the file's camera has no zfar (infinite); fitted later

    void visitNode(std::size_t index, const glm::mat4& world);
    void takeCamera(std::size_t node, int camera, const glm::mat4& world);
    void visitLight(std::size_t node, const glm::mat4& world);
    void takeLight(std::size_t node, const tinygltf::Light& light, int index,
                   const glm::mat4& world);
};

glm::vec3 worldDirection(const glm::mat4& world, glm::vec3 local) {
    return glm::normalize(glm::vec3(world * glm::vec4(local, 0.0f)));
}

void Walk::visitNode(std::size_t index, const glm::mat4& world) {
    const tinygltf::Node& n = ctx.model.nodes[index];
    if (n.mesh >= 0)
        for (const Part& part : parts[n.mesh])
            scene.instances.push_back({part.mesh, part.material, world, world});
    if (n.camera >= 0) {
        Notes& notes = ctx.notes;
        if (ctx.model.cameras[n.camera].type != "perspective") {
            notes.orthographicCameras.insert(n.camera);
        } else if (!haveCamera) {
            takeCamera(index, n.camera, world);
            notes.usedCamera = n.camera;
        } else if (n.camera != notes.usedCamera) {
            notes.extraCameras.insert(n.camera);
        }
    }
    visitLight(index, world);
}

void Walk::takeCamera(std::size_t node, int camera, const glm::mat4& world) {
    const tinygltf::Camera& c = ctx.model.cameras[camera];
    if (c.type != "perspective") return;
    const std::string name = "camera " + std::to_string(camera);
    const tinygltf::PerspectiveCamera& p = c.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.14159) || !(p.znear > 0.0) || !std::isfinite(p.zfar))
        ctx.fail(name + ": yfov must lie in (0, pi) and znear must be positive");
    if (p.zfar > 0.0 && p.zfar <= p.znear) ctx.fail(name + ": zfar must exceed znear");
    // Under a scaling node its znear and zfar scale with it (scenes/gltf_camera.h).
    Notes& notes = ctx.notes;
    scene.camera = gltf::placeCamera(world, p.yfov, p.znear, p.zfar, notes.placement);
    if (notes.placement.degenerate)
        ctx.fail("node " + str(node) + ": camera transform is degenerate");
    haveCamera = true;
}

// The first directional light is the scene's; every other light a node places is counted.
void Walk::visitLight(std::size_t node, const glm::mat4& world) {
    const auto ext = ctx.model.nodes[node].extensions.find("KHR_lights_punctual");
    if (ext == ctx.model.nodes[node].extensions.end() || !ext->second.Has("light")) return;
    const tinygltf::Value& v = ext->second.Get("light");
    const int index = v.IsNumber() ? v.GetNumberAsInt() : -1;
    if (index < 0 || std::size_t(index) >= ctx.model.lights.size())
        ctx.fail("node " + str(node) + ": light " + std::to_string(index) + " does not exist");
    const tinygltf::Light& l = ctx.model.lights[index];
    Notes& notes = ctx.notes;
    if (l.type == "directional" && !haveLight) takeLight(node, l, index, world);
    else if (l.type == "directional") ++notes.extraDirectional;
    else if (l.type == "point") ++notes.pointLights;
    else if (l.type == "spot") ++notes.spotLights;
    else ++notes.otherLights;
}

void Walk::takeLight(std::size_t node, const tinygltf::Light& l, int index,
                     const glm::mat4& world) {
    const std::string name = "light " + std::to_string(index);
    DirectionalLight& out = scene.light;
    out.direction = worldDirection(world, {0.0f, 0.0f, -1.0f});  // lights shine along -Z
    out.color = l.color.empty() ? glm::vec3(1.0f) : finiteColor(ctx, name, "color", l.color, 3);
    if (!std::isfinite(l.intensity) || l.intensity < 0.0)
        ctx.fail(name + ": intensity must be finite and not negative");
    out.intensity = float(l.intensity);
    if (!std::isfinite(out.direction.x + out.direction.y + out.direction.z))
        ctx.fail("node " + str(node) + ": light transform is degenerate");
    haveLight = true;
}

// Checks every reference from nodes, and that each node has at most one parent (glTF nodes
// form strict trees; sharing would also let a small file expand exponentially).
void checkNodes(const Context& ctx) {
    const tinygltf::Model& m = ctx.model;
    std::vector<int> parent(m.nodes.size(), -1);
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
        const tinygltf::Node& n = m.nodes[i];
        const std::string name = "node " + str(i);
        if (n.mesh >= int(m.meshes.size()))
            ctx.fail(name + ": mesh " + std::to_string(n.mesh) + " does not exist");
        if (n.camera >= int(m.cameras.size()))
            ctx.fail(name + ": camera " + std::to_string(n.camera) + " does not exist");
        for (int child : n.children) {
            if (child < 0 || std::size_t(child) >= m.nodes.size())
                ctx.fail(name + ": child node " + std::to_string(child) + " does not exist");
            if (parent[child] >= 0)
                ctx.fail("node " + std::to_string(child) + " has more than one parent");
            parent[child] = int(i);
        }
    }
}

std::vector<int> rootNodes(const Context& ctx) {
    const tinygltf::Model& m = ctx.model;
    if (m.scenes.empty()) {  // no scene: every node that is nobody's child
        std::vector<bool> isChild(m.nodes.size(), false);
        for (const tinygltf::Node& n : m.nodes)
            for (int c : n.children) isChild[c] = true;
        std::vector<int> roots;
        for (std::size_t i = 0; i < m.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
        return roots;
    }
    const int s = m.defaultScene < 0 ? 0 : m.defaultScene;
    if (std::size_t(s) >= m.scenes.size())
        ctx.fail("scene index " + std::to_string(s) + " out of range (" + str(m.scenes.size()) +
                 " scenes)");
    for (int n : m.scenes[s].nodes)
        if (n < 0 || std::size_t(n) >= m.nodes.size())
            ctx.fail("scene " + std::to_string(s) + ": node " + std::to_string(n) +
                     " does not exist");
    return m.scenes[s].nodes;
}

// Depth-first, children in file order, with an explicit stack: a deep hierarchy cannot
// overflow the call stack, and a node met again while still on the path is a cycle.
void walkNodes(const Context& ctx, Walk& walk) {
    struct Frame {
        int node;
        glm::mat4 world;
        bool leaving;
    };
    const tinygltf::Model& m = ctx.model;
    std::vector<bool> onPath(m.nodes.size(), false), done(m.nodes.size(), false);
    std::vector<int> roots = rootNodes(ctx);
    std::vector<Frame> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
        stack.push_back({*it, glm::mat4(1.0f), false});
    while (!stack.empty()) {
        const Frame f = stack.back();
        stack.pop_back();
        if (f.leaving) {
            onPath[f.node] = false;
            continue;
        }
        if (onPath[f.node]) ctx.fail("node " + std::to_string(f.node) + " is its own ancestor");
        if (done[f.node]) ctx.fail("node " + std::to_string(f.node) + " is listed twice");
        onPath[f.node] = done[f.node] = true;
        const glm::mat4 world = f.world * localTransform(ctx, std::size_t(f.node));
        walk.visitNode(std::size_t(f.node), world);
        stack.push_back({f.node, world, true});
        const std::vector<int>& children = m.nodes[f.node].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it)
            stack.push_back({*it, world, false});
    }
}

// ---------------------------------------------------------------------------------------
// Camera fitted to the bounds (see the header): the bounding sphere of radius r seen with a
// vertical field of view fov fits when the distance is r / sin(fov / 2); 10% margin.
void fitCamera(Scene& scene, float fileFar, bool haveCamera) {
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    const glm::vec3 centre = 0.5f * (lo + hi);
    float radius = 0.5f * glm::length(hi - lo);
    if (!(radius > 0.0f)) radius = 1.0f;
    Camera& cam = scene.camera;
    if (!haveCamera) {
        cam.fovY = 45.0f;
        const float distance = 1.1f * radius / std::sin(glm::radians(cam.fovY) * 0.5f);
        cam.position = centre + distance * glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));
        cam.target = centre;
        cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
        cam.nearZ = 0.5f * (distance - radius);
        cam.farZ = 2.0f * (distance + radius);
    } else if (fileFar <= 0.0f) {
        // An infinite projection in the file: a finite far plane past the whole scene.
        cam.farZ =
            std::max(cam.nearZ * 1000.0f, 2.0f * (glm::length(cam.position - centre) + radius));
    }
    scene.previousCamera = cam;
}

bool isSupportedExtension(const std::string& name) {
    return std::find(kSupportedGltfExtensions.begin(), kSupportedGltfExtensions.end(), name) !=
           kSupportedGltfExtensions.end();
}

// An extension the file requires and ssrt cannot honour is an error naming it (all of them).
void checkRequiredExtensions(const Context& ctx) {
    std::vector<std::string> missing;
    for (const std::string& e : ctx.model.extensionsRequired)
        if (!isSupportedExtension(e)) missing.push_back(e);
    if (missing.size() == 1) ctx.fail("extension " + missing[0] + " is required but not supported");
    if (!missing.empty())
        ctx.fail("extensions " + joined(missing) + " are required but not supported");
}

// "1 point or line primitive skipped", "3 point and line primitives skipped".
std::string skippedPrimitives(const Notes& n) {
    return counted(n.skippedPrimitives, n.skippedPrimitives == 1 ? "point or line primitive"
                                                                 : "point and line primitive") +
           " skipped";
}

// Each of the warnings, in a fixed order, one line per kind, each naming the file.
std::vector<std::string> warningLines(const Context& ctx, const Scene& scene) {
    const tinygltf::Model& m = ctx.model;
    const Notes& n = ctx.notes;
    std::vector<std::string> lines;
    std::vector<std::string> unsupported;
    for (const std::string& e : m.extensionsUsed)
        if (!isSupportedExtension(e)) unsupported.push_back(e);
    if (!unsupported.empty())
        lines.push_back((unsupported.size() == 1 ? "extension " : "extensions ") +
                        joined(unsupported) + (unsupported.size() == 1 ? " is" : " are") +
                        " used but not supported: ignored");
    if (n.skippedPrimitives > 0)
        lines.push_back(skippedPrimitives(n) + " (only triangles, strips and fans are rendered)");
    std::vector<std::string> lights;
    if (n.pointLights > 0) lights.push_back(counted(n.pointLights, "point light"));
    if (n.spotLights > 0) lights.push_back(counted(n.spotLights, "spot light"));
    if (n.otherLights > 0) lights.push_back(counted(n.otherLights, "light") + " of unknown type");
    if (!lights.empty()) lights.back() += " ignored (only directional lights are supported)";
    if (!lights.empty()) lines.push_back(joined(lights));
    if (n.extraDirectional > 0)
        lines.push_back(counted(n.extraDirectional, "directional light") +
                        " after the first ignored (one directional light is used)");
    if (!n.extraCameras.empty())
        lines.push_back(named("camera", n.extraCameras) + " ignored (the first perspective " +
                        "camera, camera " + std::to_string(n.usedCamera) + ", is used)");
    if (!n.orthographicCameras.empty())
        lines.push_back(named("orthographic camera", n.orthographicCameras) +
                        " ignored (only perspective cameras are supported)");
    if (n.usedCamera >= 0) {
        const tinygltf::PerspectiveCamera& p = m.cameras[n.usedCamera].perspective;
        for (std::string& line : gltf::placementWarnings(n.placement, p.znear, p.zfar, scene))
            lines.push_back("camera " + std::to_string(n.usedCamera) + ": " + line);
    }
    if (!n.blendMaterials.empty()) {
        std::vector<std::string> indices;
        for (std::size_t i : n.blendMaterials) indices.push_back(str(i));
        lines.push_back(
            "alphaMode BLEND is drawn as MASK with alphaCutoff 0.5, not blended: where alpha is "
            "0.5 or more the surface is opaque, elsewhere it is not drawn (" +
            counted(n.blendMaterials.size(), "material") + ": " + joined(indices) + ")");
    }
    if (n.vertexColours > 0)
        lines.push_back("vertex colours (COLOR_0) are not applied (" +
                        counted(n.vertexColours, "primitive") + ")");
    if (n.morphTargets > 0)
        lines.push_back("morph targets are not applied (" + counted(n.morphTargets, "primitive") +
                        ")");
    if (!m.skins.empty())
        lines.push_back("skins are not applied (" + counted(m.skins.size(), "skin") + ")");
    if (!m.animations.empty())
        lines.push_back("animations are not played (" + counted(m.animations.size(), "animation") +
                        ")");
    for (std::string& line : lines) line = ctx.path + ": " + line;
    return lines;
}

void convert(const Context& ctx, Scene& scene) {
    scene.name = fs::path(ctx.path).stem().string();
    checkRequiredExtensions(ctx);
    const std::vector<std::vector<Part>> parts = convertMeshes(ctx, scene);
    checkNodes(ctx);
    Walk walk{ctx, parts, scene};
    walkNodes(ctx, walk);
    if (scene.triangleCount() == 0)
        ctx.fail(ctx.notes.skippedPrimitives == 0
                     ? "the scene has no triangles"
                     : "the scene has no triangles (" + skippedPrimitives(ctx.notes) +
                           ": only triangles, strips and fans are rendered)");
    fitCamera(scene, scene.camera.farZ, walk.haveCamera);
    if (walk.haveCamera) ctx.notes.placement.beyondFar = gltf::trianglesBeyondFar(scene);
    try {
        scene.validate();
    } catch (const std::invalid_argument& e) {
        ctx.fail(e.what());
    }
}

}  // namespace

Scene loadGltf(const std::string& path) { return loadGltf(path, GltfLoadOptions{}, nullptr); }

Scene loadGltf(const std::string& path, const GltfLoadOptions& options, GltfLoadReport* report) {
    if (report) report->warnings.clear();
    try {
        gltf::DataUriImages dataUris;
        const tinygltf::Model model = readModel(path, dataUris);
        Scene scene;
        gltf::TextureTable textures(model, path, dataUris, scene.textures);
        Notes notes;
        const Context ctx{path, model, textures, notes};
        convert(ctx, scene);
        std::vector<std::string> warnings = warningLines(ctx, scene);
        if (options.strict && !warnings.empty())
            throw SceneLoadError(warnings.front() + " (strict: every warning is an error)");
        if (report) report->warnings = std::move(warnings);
        return scene;
    } catch (const SceneLoadError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw SceneLoadError(path + ": out of memory while loading");
    } catch (const std::exception& e) {
        throw SceneLoadError(path + ": " + oneLine(e.what()));
    }
}

}  // namespace ssrt
