// glTF 2.0 (.gltf with external or embedded buffers, .glb) into the scene model.
// Lives beside the scene model but in its own library (ssrt_gltf), so that the core
// library does not depend on tinygltf (see DESIGN.md).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace ssrt {

// A file that cannot be turned into a scene. what() is one line: "<path>: <problem>".
class SceneLoadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Loads every triangle primitive reachable from the file's scene (the default scene, else
// the first; a file without scenes uses every root node) as one Mesh and one Instance per
// primitive, with the node's world transform as both transform and previousTransform.
// Materials: emissiveFactor times KHR_materials_emissive_strength's emissiveStrength.
//
// Camera: the first perspective camera met in a depth-first walk of the node tree, placed by
// its node's world matrix (scale and all: scenes/gltf_camera.h). Without
// one, a camera fitted to the bounds: it looks at the centre of the bounding sphere from
// above and in front (+Z, tilted up), with a 45 degree vertical field of view and far enough
// that the whole sphere fits vertically (and horizontally for aspect ratios of 1 and wider).
// Light: the first directional KHR_lights_punctual light met in the walk, else the default.
// Textures: base-colour (sRGB) and metallic-roughness (linear) textures are decoded through
// OpenImageIO, from files, data URIs or buffer views, into Scene::textures with their
// samplers' wrap modes (scenes/gltf_textures.h) and their KHR_texture_transform (into
// Material::baseColorUv, metallicRoughnessUv); TEXCOORD_0 and TEXCOORD_1. Normal (linear, with
// its scale), occlusion (linear, with its strength) and emissive (sRGB) textures likewise,
// each with its own texCoord and transform; TANGENT into Mesh::tangents (generated where a
// normal map needs them and the file has none, scenes/tangents.h).
// Geometry: plain, or compressed with KHR_draco_mesh_compression or EXT_meshopt_compression
// (decoded first, then checked as plain data: scenes/gltf_compression.h). Attributes may be
// quantized under KHR_mesh_quantization (POSITION and TEXCOORD_n any 8- or 16-bit integer,
// normalized or not; NORMAL and TANGENT normalized BYTE or SHORT), decoded by glTF 2.0's rules
// for normalized integers (c / 255, max(c / 127, -1), ...) or as their integer values; the
// dequantization is the node's transform (and KHR_texture_transform for UVs), read as for any
// file. A component type the attribute may not have is an error that says which it may have
// (and when only KHR_mesh_quantization would allow it).
// alphaMode, alphaCutoff and baseColorFactor's alpha go to the Material (MASK is a cut-out;
// BLEND is drawn as MASK at the default cutoff 0.5, not blended, with one warning line that
// says so and counts the materials); an alphaMode other than OPAQUE, MASK or BLEND, or a
// negative or non-finite cutoff, is an error.
//
// What the file holds beyond this is a warning, never a silent drop (one line per kind, in
// a fixed order, each "<path>: <what was ignored>"): point and line primitives (skipped; a
// file with nothing else has no triangles and is an error), extensions in extensionsUsed that
// ssrt does not support, point and spot lights and directional lights after the first,
// cameras other than the one used and orthographic cameras, a camera node's scale, shear or
// mirror and the triangles wholly past its far plane, alphaMode BLEND, COLOR_0, skins,
// animations and morph targets. Samplers' filters are checked to be glTF's values and
// otherwise not read, without a warning: every texture is filtered one way
// (scenes/texture.h).
// kSupportedGltfExtensions are the extensions ssrt honours; one in extensionsRequired that is
// not among them is an error naming it.
//
// Throws SceneLoadError for anything malformed: it never returns a partial scene.
struct GltfLoadOptions {
    bool strict = false;  // every warning is an error: the first is thrown as SceneLoadError
};
struct GltfLoadReport {
    std::vector<std::string> warnings;  // one line each, naming the file
};
inline const std::vector<std::string> kSupportedGltfExtensions = {
    "KHR_lights_punctual",     "KHR_materials_emissive_strength", "KHR_texture_transform",
    "EXT_meshopt_compression", "KHR_draco_mesh_compression",      "KHR_mesh_quantization"};

// `report` (may be null) is cleared, then receives the warnings of a successful load.
Scene loadGltf(const std::string& path, const GltfLoadOptions& options, GltfLoadReport* report);
Scene loadGltf(const std::string& path);  // not strict, warnings discarded

}  // namespace ssrt
