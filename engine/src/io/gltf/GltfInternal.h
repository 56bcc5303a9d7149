// GltfInternal.h: the glTF loader's internal interfaces, shared by its passes:
// container checks (GLB, JSON nesting, URIs), structural validation, bounds-checked accessor
// reading, geometry and scene conversion. Only engine/src/io/gltf/ includes this.
//
// The passes, in order (GltfImport.cpp runs them):
//   1. GltfContainer.cpp  the bytes: size bound, GLB chunks, JSON nesting depth, external URIs
//                         (relative, inside the scene's folder), facts tinygltf discards.
//   2. tinygltf           JSON -> tinygltf::Model, buffers read through confined callbacks.
//   2b. compressed data   GltfMeshopt.cpp (EXT_/KHR_meshopt_compression buffer views) and
//                         GltfDraco.cpp (KHR_draco_mesh_compression primitives): decoded into
//                         buffers appended to the model, views and accessors pointed at them, so
//                         that every later pass reads them as plain data.
//   3. GltfValidate.cpp   every reference, buffer view, accessor, index, count and enum, with
//                         the glTF object path in each message, before any data is read.
//   4. conversion        data -> Scene: GltfGeometry.cpp meshes (strips/fans to lists, normals
//                         computed), GltfMaterials.cpp materials and textures,
//                         GltfLightsCameras.cpp lights and cameras, GltfConvert.cpp nodes,
//                         scenes, animations, extensions and the whole model.
//   5. Scene::validate()  the scene model's own checks, as a final net.
#pragma once

#include "io/FileAccess.h"
#include "io/LoadDiagnostics.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <lantern/FileOptions.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tiny_gltf.h>
#include <vector>

/// Assigns a conversion's result to `to`, or returns its error from the enclosing function.
#define LANTERN_TAKE(to, conversion)                       \
    do {                                                   \
        auto taken_ = (conversion);                        \
        if (!taken_) return std::move(taken_).error();     \
        (to) = std::move(*taken_);                         \
    } while (false)

namespace lantern::gltf {

/// glTF accessor component types by name (INT and DOUBLE are not glTF 2.0 accessor types).
inline constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
inline constexpr int kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
inline constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
inline constexpr int kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
inline constexpr int kUnsignedInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
inline constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

/// Deepest JSON nesting accepted. Real glTF files nest about 8 levels; tinygltf converts
/// `extensions` and `extras` recursively, so a hostile file nested millions of levels deep
/// would overflow the stack without this bound.
inline constexpr int kMaxJsonDepth = 256;

/// The finite ceiling of the PBR roughness -> shininess mapping 2/r^4 - 2 (reached for
/// roughness <= 0.1189). Above ~1e4 float32 pow(n.h, s) loses accuracy (numerics.md 3.3), and
/// the lobe (half-width 0.68 degrees at 1e4) is already narrower than a pixel in most views.
inline constexpr double kMaxPbrShininess = 1.0e4;  // LANTERN_PBR_MAX_SHININESS in the shaders

/// The floor of that mapping: at 1 the lobe (n.h)^s still falls off across the surface, where
/// 2/r^4 - 2 = 0 at roughness 1 would make the specular term a constant over the lit side.
inline constexpr double kMinPbrShininess = 1.0;  // LANTERN_PBR_MIN_SHININESS

/// A metallic-roughness material in the classic equation's terms (see mapPbr in
/// GltfMaterials.cpp and docs/scene-format-support.md for the formula and its reasons).
struct PhongFromPbr {
    glm::dvec3 diffuse{0.0}, specular{0.0};
    double shininess = 1.0;
};
PhongFromPbr phongFromPbr(const glm::dvec3& base, double metallic, double roughness,
                          const glm::dvec3& dielectricF0 = glm::dvec3(0.04));

/// The KHR_materials_* extensions approximated in the classic equation (GltfPbrExtensions.cpp).
struct PbrExtensions {
    glm::dvec3 dielectricF0{0.04};  ///< ior and specular
    double clearcoat = 0.0, clearcoatRoughness = 0.0;
    glm::dvec3 sheenColor{0.0};
    double transmission = 0.0;
    double thickness = 0.0;
    glm::dvec3 attenuationColor{1.0};
    double attenuationDistance = kInfinity;
};

/// The TEXCOORD set a texture reference reads: KHR_texture_transform's `texCoord` when the
/// reference has one, else its own `texCoord`.
int texCoordOf(const tinygltf::TextureInfo& info);
/// The TEXCOORD set a material's textures read: the base colour's, else the first of the
/// metallic-roughness, normal, occlusion and emissive textures' (0 without textures).
int materialTexcoordSet(const tinygltf::Material& material);
/// The other TEXCOORD set the material's maps read (the first met: metallic-roughness,
/// normal, occlusion, emissive), or -1 when they all read materialTexcoordSet.
int materialSecondTexcoordSet(const tinygltf::Material& material);

/// Whether a material the primitive may be drawn with (its own, or one of its
/// KHR_materials_variants mappings) has a normal map: only then are its tangents read.
bool needsTangents(const tinygltf::Model& model, const tinygltf::Primitive& prim);

/// KHR_texture_transform's matrix: uv' = (T(offset) R(rotation) S(scale) (u, v, 1)).xy, with
/// u' = cos(r) u + sin(r) v, v' = -sin(r) u + cos(r) v for the rotation (counter-clockwise UVs,
/// the extension's own example: offset (0, 1), rotation pi/2, scale 0.5 reads the lower left
/// quadrant rotated).
glm::dmat3 textureTransform(const glm::dvec2& offset, double rotation, const glm::dvec2& scale);

/// Extensions the loader understands (anything else listed in extensionsRequired is refused;
/// listed only in extensionsUsed, it is ignored with a warning).
inline constexpr const char* kSupportedExtensions[] = {
    "KHR_lights_punctual",     "KHR_materials_unlit",     "KHR_materials_emissive_strength",
    "LANTERN_materials_phong", "LANTERN_lights_phong",    "LANTERN_lights_shadow",
    "LANTERN_lighting",
    "LANTERN_camera",          "KHR_mesh_quantization",   "EXT_meshopt_compression",
    "KHR_meshopt_compression", "KHR_draco_mesh_compression", "KHR_texture_transform",
    "EXT_texture_webp",        "KHR_materials_variants",  "KHR_materials_specular",
    "KHR_materials_ior",       "KHR_materials_clearcoat", "KHR_materials_sheen",
    "KHR_materials_transmission", "KHR_materials_volume", "EXT_mesh_gpu_instancing",
};

/// The image a texture's extension names (EXT_texture_webp, KHR_texture_basisu: `source`), or
/// -1 when the texture has no such extension or it names none.
int extensionSource(const tinygltf::Texture& texture, const char* extension);

/// The two names of the meshopt codec's extension: EXT_ (ratified) and KHR_ (its successor, the
/// same JSON; its newer bitstream versions are refused by the decoder with a message).
inline constexpr const char* kMeshoptExtensions[] = {"EXT_meshopt_compression",
                                                     "KHR_meshopt_compression"};

/// A load's messages and budget: shared with the other formats (io/LoadDiagnostics.h).
using io::Diagnostics;

/// "name[i]": the glTF object path convention of every message.
std::string at(std::string_view array, std::size_t index);

// --- Pass 1: the bytes (GltfContainer.cpp) ----------------------------------------------------

/// Where the chunks of a GLB container lie. `tinygltfLength` is the length to hand to
/// tinygltf: the header's, cut after the last chunk it understands (JSON, BIN).
struct GlbLayout {
    std::size_t jsonOffset = 0, jsonLength = 0;
    std::size_t binOffset = 0, binLength = 0;
    bool hasBin = false;
    std::size_t tinygltfLength = 0;
};

/// True when the bytes start with the GLB magic "glTF".
bool isGlb(const std::vector<unsigned char>& bytes);

/// Checks the GLB header and chunk structure (the validator's GLB_* rules).
Result<GlbLayout> parseGlb(const std::vector<unsigned char>& bytes, const Diagnostics& diag);

/// What a JSON text holds, counted by one scan of its bytes before anything is parsed: the
/// load charges the parsed document and the model built from it to its budget from these.
struct JsonShape {
    std::uint64_t objects = 0, arrays = 0;
    std::uint64_t members = 0;  ///< object members (each has a key string)
    std::uint64_t scalars = 0;  ///< numbers, true, false and null
    std::uint64_t strings = 0;  ///< keys and string values
    std::uint64_t longStringBytes = 0;  ///< heap bytes of strings longer than 15 characters
    /// Values of any kind: objects, arrays, scalars and string values.
    std::uint64_t values() const;
    /// Bytes the parsed document holds (nlohmann::json, an estimate from above).
    std::uint64_t documentBytes() const;
    /// Bytes a model built from the document holds beyond its objects' fixed size.
    std::uint64_t contentBytes() const;
};

/// Counts the JSON text's values (JsonShape); refuses text nested deeper than kMaxJsonDepth.
/// A scan that respects strings and allocates nothing.
Result<JsonShape> scanJson(std::string_view json, const Diagnostics& diag);

// Files are read and URIs resolved by io/FileAccess.h, for every format; the loader's passes
// use its functions by their short names.
using io::checkRelativeUri;
using io::ConfinedPath;
using io::percentDecode;
using io::printable;
using io::readConfinedFile;
using io::readRegularFile;
using io::resolveConfined;

/// checkRelativeUri with the loader's file named.
inline Result<std::string> checkRelativeUri(std::string_view uri, const std::string& object,
                                            const Diagnostics& diag, bool allowParent = false) {
    return io::checkRelativeUri(uri, object, diag.file(), allowParent);
}

/// What the JSON says that tinygltf does not keep: presence of optional numbers, the number
/// of primitives written (tinygltf silently drops malformed ones), and why an external image
/// cannot be read (tinygltf only warns; it is an error once a material uses the image).
struct RawFacts {
    std::vector<bool> perspectiveHasZfar;     ///< per camera
    std::vector<std::size_t> primitiveCounts; ///< per mesh, as written
    std::map<int, std::string> imageProblems; ///< per image index
    /// meshopt fallback buffers without data (no uri), per buffer index: the byteLength written.
    /// tinygltf cannot read a buffer without data, so each is handed to it as a 4-byte data: URI
    /// (`jsonForTinygltf`); every view into one must be compressed (GltfMeshopt.cpp).
    std::map<int, std::uint64_t> placeholderBuffers;
    /// Indices accessors of KHR_draco_mesh_compression primitives, per (mesh, primitive):
    /// left out of the JSON tinygltf reads (it refuses an indices accessor without a
    /// bufferView) and put back by restoreDracoIndices.
    std::map<std::pair<int, int>, int> dracoIndices;
    /// KHR_animation_pointer channels ("animations[0].channels[3]", and the JSON pointer they
    /// drive): tinygltf drops a channel without a target node, so they are found here, and
    /// skipped with a warning (Lantern does not play them).
    std::vector<std::pair<std::string, std::string>> pointerChannels;
    /// Bytes tinygltf's model will hold in its objects' fixed size (each array at the capacity
    /// its growth reaches) and in the extras and extensions it keeps as tinygltf::Value trees;
    /// and the bytes held only while it is built (each array's block before its last growth).
    std::uint64_t modelBytes = 0, modelGrowthBytes = 0;
    /// The JSON to hand tinygltf when it differs from the file's (placeholders, Draco indices);
    /// else empty.
    std::string jsonForTinygltf;
};

/// Where the JSON came from, for the checks on buffers and external files.
struct Source {
    std::filesystem::path folder; ///< the scene's folder (absolute)
    std::vector<std::filesystem::path> allowed;  ///< LoadOptions::allowedFolders
    bool glb = false;
    bool glbHasBin = false;
    std::uint64_t maxBytes = 0;
};

/// A GLB with the JSON chunk replaced by `json` (padded) and the same BIN chunk; unknown chunks
/// are left out (tinygltf reads none). Refused when the result reaches 4 GiB.
Result<std::vector<unsigned char>> rebuildGlb(const std::vector<unsigned char>& bytes,
                                              const GlbLayout& layout, const std::string& json,
                                              const Diagnostics& diag);

/// Parses the JSON text (already depth-checked) and collects RawFacts. Refuses syntax errors,
/// a root that is not an object, buffers without data, external URIs that leave the scene's
/// folder, missing buffer files, files over the size bound, and primitives tinygltf would
/// silently drop.
Result<RawFacts> inspectJson(std::string_view json, const Source& source, const Diagnostics& diag);

// --- Pass 2b: compressed data (GltfMeshopt.cpp, GltfDraco.cpp) -------------------------------

/// Appends a buffer holding decoded bytes to the model; returns its index.
int addDecodedBuffer(tinygltf::Model& model, std::vector<unsigned char> data);

/// Decodes every buffer view with EXT_meshopt_compression (or KHR_meshopt_compression) into a
/// buffer of its own and points the view at it; checks that views into placeholder buffers are
/// all compressed and that filtered views are read as the filter's output type.
/// The decoded data is charged to the load's budget (Diagnostics::charge) before it is allocated.
Result<void> decodeMeshopt(tinygltf::Model& model, const RawFacts& raw, const Diagnostics& diag);

/// Decodes every primitive with KHR_draco_mesh_compression and points its accessors at the
/// decoded data; the stream's counts are checked against the accessors before decoding
/// (GltfDracoHeader.cpp reads them) and after. The decoded data is charged to the load's budget
/// (Diagnostics::charge) before the stream is decoded.
Result<void> decodeDraco(tinygltf::Model& model, const Diagnostics& diag);

/// Puts back the Draco primitives' indices accessors that inspectJson hid from tinygltf.
void restoreDracoIndices(tinygltf::Model& model, const RawFacts& raw);

/// What a Draco stream's header says, read without decoding it.
struct DracoHeader {
    int versionMajor = 0, versionMinor = 0;
    bool edgebreaker = false;
    std::uint64_t faces = 0;
    /// Sequential: the point count. Edgebreaker: the encoded vertices plus split symbols (an
    /// upper bound of what the decoder allocates per vertex).
    std::uint64_t vertices = 0;
};

/// Reads the header and connectivity counts of a Draco mesh stream; refuses what is not a
/// triangle mesh of bitstream 2.0-2.2, metadata nested too deep or running past the end, and
/// counts that contradict each other.
Result<DracoHeader> readDracoHeader(const unsigned char* data, std::size_t size,
                                    const std::string& object, const Diagnostics& diag);

// --- Pass 3: structure (GltfValidate.cpp) ------------------------------------------------------

/// Checks every reference, buffer view, accessor (bounds, alignment, sparse parts), enum and
/// count the conversion relies on. After it succeeds, reading any accessor cannot go out of
/// bounds (the readers check again regardless).
Result<void> validateModel(const tinygltf::Model& model, const RawFacts& raw,
                           const LoadOptions& options, const Diagnostics& diag);

// --- Accessors (GltfAccessors.cpp) -------------------------------------------------------------

/// Bytes per element of an accessor, including the column padding glTF requires for
/// MAT2/MAT3 of 1- and 2-byte components; 0 for an invalid type/componentType.
std::size_t elementSize(int type, int componentType);
/// Components per element (1..16); 0 for an invalid type.
int componentCount(int type);
/// Bytes per component; 0 for an invalid componentType.
int componentSize(int componentType);
/// "FLOAT", "UNSIGNED_SHORT", ... for messages.
std::string componentTypeName(int componentType);
/// "VEC3", ... for messages.
std::string typeName(int type);

/// Checks buffer view `index`: its buffer exists and it lies inside it; a valid byteStride.
Result<void> checkBufferView(const tinygltf::Model& model, int index, const Diagnostics& diag);

/// Checks accessor `index` against its buffer views and buffers (and its sparse parts).
Result<void> checkAccessor(const tinygltf::Model& model, int index, const LoadOptions& options,
                           const Diagnostics& diag);

/// Reads an accessor as numbers: count x components values, normalised integers mapped to
/// [0,1] / [-1,1] as glTF specifies, sparse substitutions applied. Refuses non-finite floats.
/// `object` names the use in messages ("meshes[0].primitives[1].attributes.NORMAL").
Result<std::vector<float>> readFloats(const tinygltf::Model& model, int index,
                                      const std::string& object, const Diagnostics& diag);
Result<std::vector<double>> readDoubles(const tinygltf::Model& model, int index,
                                        const std::string& object, const Diagnostics& diag);
/// Reads an index accessor (UNSIGNED_BYTE/SHORT/INT scalars) and checks every index is below
/// `vertexCount`.
Result<std::vector<std::uint32_t>> readIndices(const tinygltf::Model& model, int index,
                                               std::size_t vertexCount, const std::string& object,
                                               const Diagnostics& diag);

// --- Pass 4: conversion (GltfGeometry/Materials/LightsCameras/Convert.cpp) -------------------

/// glTF number arrays as vectors: the first three numbers; the first four (1 when only three).
glm::dvec3 vec3(const std::vector<double>& v);
glm::dvec4 vec4(const std::vector<double>& v);
bool allFinite(const std::vector<double>& v);
/// Attaches the file to errors from the scene model's checkers (checkProjection, ...).
Error inFile(Error e, const Diagnostics& diag);
/// Extension `name` of an object, or null.
const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name);

/// Encoded image bytes kept by the image callback (decoding waits until a material uses the
/// image), per image index.
struct ImageStore {
    std::map<int, std::vector<unsigned char>> encoded;
};

/// One mesh: triangle primitives (strips and fans converted), other modes skipped with a
/// warning; missing normals computed.
Result<Mesh> convertMesh(const tinygltf::Model& model, std::size_t meshIndex,
                         const Diagnostics& diag);

/// The materials into scene.materials, and the textures they use (decoded on first use) into
/// scene.textures (GltfMaterials.cpp).
Result<void> convertMaterials(const tinygltf::Model& model, const RawFacts& raw,
                              const ImageStore& images, const LoadOptions& options,
                              const Diagnostics& diag, Scene& scene);

/// A KHR_lights_punctual light, with LANTERN_lights_phong (GltfLightsCameras.cpp).
Result<Light> convertLight(const tinygltf::Light& src, std::size_t index, const Diagnostics& diag);

/// A camera, with LANTERN_camera; `hasZfar`: the perspective block has a zfar (RawFacts).
Result<Camera> convertCamera(const tinygltf::Camera& src, std::size_t index, bool hasZfar,
                             const Diagnostics& diag);

/// KHR_materials_variants (GltfVariants.cpp): the variants' names, and a primitive's
/// mappings (its material in each variant that lists it), every index checked.
Result<std::vector<std::string>> variantNames(const tinygltf::Model& model, const Diagnostics& diag);
Result<std::vector<Primitive::VariantMaterial>> primitiveVariants(const tinygltf::Model& model,
                                                                  const tinygltf::Primitive& prim,
                                                                  std::size_t variantCount,
                                                                  const std::string& obj,
                                                                  const Diagnostics& diag);

/// The KHR_materials_* extensions (PbrExtensions): reads them (each value checked, the path named); defaults where the material has none.
Result<PbrExtensions> readPbrExtensions(const tinygltf::Material& src, const std::string& obj,
                                        const Diagnostics& diag);
/// Applies the rules to a material the PBR mapping made (its front side, blending).
void applyPbrExtensions(const PbrExtensions& x, double metallic, Material& m);

/// EXT_mesh_gpu_instancing (GltfInstancing.cpp): each instancing node's mesh moved to one
/// child node per instance (TRANSLATION, ROTATION, SCALE), charged to the load's budget.
Result<void> expandInstances(const tinygltf::Model& model, const Diagnostics& diag, Scene& scene);

/// The fidelity report (Scene::features) of the model (GltfFidelity.cpp).
void noteFeatures(const tinygltf::Model& model, const RawFacts& raw, bool glb, Scene& scene);

/// The whole scene (GltfConvert.cpp), with the converters above and convertMesh.
Result<Scene> convertModel(const tinygltf::Model& model, const RawFacts& raw,
                           const ImageStore& images, const LoadOptions& options,
                           const Diagnostics& diag);

/// Reads an extension's members (tinygltf::Value) with checks and object paths. A member of the
/// wrong type or length, or a non-finite number, is recorded (the first one counts) and its
/// fallback returned, so a block of reads is checked once with status(); readers made by child()
/// record into the same place.
class ExtensionReader {
public:
    ExtensionReader(const tinygltf::Value& value, std::string object, const Diagnostics& diag)
        : m_value(value), m_object(std::move(object)), m_diag(diag),
          m_error(std::make_shared<std::optional<Error>>()) {}
    const std::string& object() const { return m_object; }
    bool has(const std::string& key) const { return m_value.Has(key); }
    /// A finite number; `fallback` when absent.
    double number(const std::string& key, double fallback) const;
    /// Two finite numbers.
    glm::dvec2 vec2(const std::string& key, const glm::dvec2& fallback) const;
    /// Three finite numbers.
    glm::dvec3 vec3(const std::string& key, const glm::dvec3& fallback) const;
    /// Four finite numbers, or three (an RGB colour given for an RGBA one: alpha 1).
    glm::dvec4 rgba(const std::string& key, const glm::dvec4& fallback) const;
    bool boolean(const std::string& key, bool fallback) const;
    std::string string(const std::string& key, const std::string& fallback) const;
    /// A member object (for nested blocks like "back" or "lookAt"); nothing when absent or not
    /// an object.
    std::optional<ExtensionReader> child(const std::string& key) const;
    /// Records an error about member `key` (unless one is recorded already).
    void fail(const std::string& key, const std::string& message) const;
    /// The first error recorded by this reader or its children.
    Result<void> status() const;
    /// Warns about members the extension does not define (typos should not pass silently).
    void warnUnknown(std::initializer_list<const char*> known) const;

private:
    std::string path(const std::string& key) const { return m_object + "." + key; }
    /// The numbers of an array member of `n` (or `alsoN` when nonzero) elements, or nothing
    /// (absent, or recorded as an error).
    std::optional<std::vector<double>> numbers(const std::string& key, std::size_t n,
                                               std::size_t alsoN) const;
    const tinygltf::Value& m_value;
    std::string m_object;
    const Diagnostics& m_diag;
    std::shared_ptr<std::optional<Error>> m_error;
};

} // namespace lantern::gltf
