// The JSON pass's number checks by schema position (GltfSchema.h). The schema is a tree of the
// places glTF 2.0 and the extensions Lantern reads put numbers: a member by name, any member
// ("*"), an array's elements ("[]"). A number is an integer only where the schema says so.
#include "io/gltf/GltfSchema.h"

#include <cmath>
#include <cstdint>
#include <deque>
#include <map>

namespace lantern::gltf {
namespace {

using nlohmann::json;

struct SchemaNode {
    NumberKind kind = NumberKind::Any;
    std::map<std::string, SchemaNode*, std::less<>> members;
    SchemaNode* anyMember = nullptr; ///< the node of members not named in `members`
    SchemaNode* element = nullptr;   ///< the node of an array's elements
    /// An `extensions` object: only the extensions named in `members` are read; any other is
    /// not Lantern's to check (it does not read it).
    bool onlyListed = false;
    /// Under a material: a member whose name ends in "Texture" is a textureInfo.
    bool textureInfos = false;
    bool positive = false; ///< a camera's aspectRatio: greater than 0
};

// Every integer place of glTF 2.0 (the schema's "integer" and glTFid properties) and of the
// extensions Lantern reads; "I" an index or enum, "S" an offset, length or count.
constexpr const char* kIntegerPlaces[][2] = {
    {"scene", "I"},
    {"scenes[].nodes[]", "I"},
    {"nodes[].camera", "I"}, {"nodes[].children[]", "I"}, {"nodes[].skin", "I"},
    {"nodes[].mesh", "I"},
    {"nodes[].extensions.KHR_lights_punctual.light", "I"},
    {"nodes[].extensions.EXT_mesh_gpu_instancing.attributes.*", "I"},
    {"meshes[].primitives[].attributes.*", "I"}, {"meshes[].primitives[].indices", "I"},
    {"meshes[].primitives[].material", "I"}, {"meshes[].primitives[].mode", "I"},
    {"meshes[].primitives[].targets[].*", "I"},
    {"meshes[].primitives[].extensions.KHR_draco_mesh_compression.bufferView", "I"},
    {"meshes[].primitives[].extensions.KHR_draco_mesh_compression.attributes.*", "I"},
    {"meshes[].primitives[].extensions.KHR_materials_variants.mappings[].material", "I"},
    {"meshes[].primitives[].extensions.KHR_materials_variants.mappings[].variants[]", "I"},
    {"accessors[].bufferView", "I"}, {"accessors[].byteOffset", "S"},
    {"accessors[].componentType", "I"}, {"accessors[].count", "S"},
    {"accessors[].sparse.count", "S"}, {"accessors[].sparse.indices.bufferView", "I"},
    {"accessors[].sparse.indices.byteOffset", "S"},
    {"accessors[].sparse.indices.componentType", "I"},
    {"accessors[].sparse.values.bufferView", "I"}, {"accessors[].sparse.values.byteOffset", "S"},
    {"animations[].channels[].sampler", "I"}, {"animations[].channels[].target.node", "I"},
    {"animations[].samplers[].input", "I"}, {"animations[].samplers[].output", "I"},
    {"buffers[].byteLength", "S"},
    {"bufferViews[].buffer", "I"}, {"bufferViews[].byteOffset", "S"},
    {"bufferViews[].byteLength", "S"}, {"bufferViews[].byteStride", "S"},
    {"bufferViews[].target", "I"},
    {"images[].bufferView", "I"},
    {"samplers[].magFilter", "I"}, {"samplers[].minFilter", "I"}, {"samplers[].wrapS", "I"},
    {"samplers[].wrapT", "I"},
    {"skins[].inverseBindMatrices", "I"}, {"skins[].skeleton", "I"}, {"skins[].joints[]", "I"},
    {"textures[].sampler", "I"}, {"textures[].source", "I"},
    {"textures[].extensions.EXT_texture_webp.source", "I"},
    {"textures[].extensions.KHR_texture_basisu.source", "I"},
};

// The meshopt codec's view members, under both of its names.
constexpr const char* kMeshoptPlaces[][2] = {
    {"buffer", "I"}, {"byteOffset", "S"}, {"byteLength", "S"}, {"byteStride", "S"}, {"count", "S"},
};

// Extensions Lantern reads that hold no integer: listed so that their numbers are checked
// (an extension not listed anywhere here is not read, so nothing in it is checked).
constexpr const char* kReadExtensions[] = {
    "extensions.KHR_lights_punctual",
    "extensions.KHR_materials_variants",
    "extensions.KHR_lights_punctual.lights[].extensions.LANTERN_lights_phong",
    "extensions.KHR_lights_punctual.lights[].extensions.LANTERN_lights_shadow",
    "scenes[].extensions.LANTERN_lighting",
    "cameras[].extensions.LANTERN_camera",
    "buffers[].extensions.EXT_meshopt_compression",
    "buffers[].extensions.KHR_meshopt_compression",
    "animations[].channels[].target.extensions.KHR_animation_pointer",
};

// Material extensions Lantern reads; their members follow the material's rules (textureInfos).
constexpr const char* kMaterialExtensions[] = {
    "LANTERN_materials_phong",  "KHR_materials_unlit",       "KHR_materials_emissive_strength",
    "KHR_materials_specular",   "KHR_materials_ior",         "KHR_materials_clearcoat",
    "KHR_materials_sheen",      "KHR_materials_transmission", "KHR_materials_volume",
};

class Schema {
public:
    Schema() {
        m_root = make();
        for (const auto& [place, kind] : kIntegerPlaces) add(place)->kind = kindOf(kind);
        for (const char* codec : kMeshoptExtensions)
            for (const auto& [member, kind] : kMeshoptPlaces)
                add(std::string("bufferViews[].extensions.") + codec + "." + member)->kind =
                    kindOf(kind);
        for (const char* place : kReadExtensions) add(place);
        add("cameras[].perspective.aspectRatio")->positive = true;
        buildMaterials();
    }
    const SchemaNode* root() const { return m_root; }

    /// The node of member `key` of an object at `node`; null when the member is not walked.
    static const SchemaNode* member(const SchemaNode* node, std::string_view key, bool& skip,
                                    const SchemaNode* textureInfo) {
        skip = false;
        if (key == "extras") return skip = true, nullptr;
        if (!node) {
            // Outside the schema's places (an asset's members, a node's name): any extensions
            // object found there is one Lantern does not read.
            skip = key == "extensions";
            return nullptr;
        }
        if (auto it = node->members.find(key); it != node->members.end()) return it->second;
        if (node->onlyListed || key == "extensions") return skip = true, nullptr;
        if (node->textureInfos && key.size() > 7 && key.substr(key.size() - 7) == "Texture")
            return textureInfo;
        return node->anyMember;
    }
    const SchemaNode* textureInfo() const { return m_textureInfo; }

private:
    static NumberKind kindOf(std::string_view k) {
        return k == "I" ? NumberKind::Index : NumberKind::Size;
    }
    SchemaNode* make() { return &m_nodes.emplace_back(); }
    SchemaNode* memberOf(SchemaNode* node, const std::string& name) {
        SchemaNode*& child = node->members[name];
        if (!child) child = make();
        if (name == "extensions") child->onlyListed = true;
        return child;
    }
    SchemaNode* elementOf(SchemaNode* node) {
        if (!node->element) node->element = make();
        return node->element;
    }
    // "a[].b.*": members by name, "[]" an array's elements, "*" any member.
    SchemaNode* add(std::string_view place, SchemaNode* from = nullptr) {
        SchemaNode* node = from ? from : m_root;
        while (!place.empty()) {
            const std::size_t dot = place.find('.');
            std::string_view token = place.substr(0, dot);
            place = dot == std::string_view::npos ? std::string_view() : place.substr(dot + 1);
            std::size_t arrays = 0;
            while (token.size() >= 2 && token.substr(token.size() - 2) == "[]") {
                token.remove_suffix(2);
                ++arrays;
            }
            if (token == "*") {
                if (!node->anyMember) node->anyMember = make();
                node = node->anyMember;
            } else if (!token.empty()) {
                node = memberOf(node, std::string(token));
            }
            for (std::size_t i = 0; i < arrays; ++i) node = elementOf(node);
        }
        return node;
    }
    // A material: any member, at any depth, holds numbers; a member whose name ends in
    // "Texture" is a textureInfo (index, texCoord, KHR_texture_transform's texCoord).
    void buildMaterials() {
        m_textureInfo = make();
        add("index", m_textureInfo)->kind = NumberKind::Index;
        add("texCoord", m_textureInfo)->kind = NumberKind::Index;
        add("extensions.KHR_texture_transform.texCoord", m_textureInfo)->kind = NumberKind::Index;
        SchemaNode* material = make();
        material->anyMember = material;
        material->element = material;
        material->textureInfos = true;
        SchemaNode* extensions = memberOf(material, "extensions");
        for (const char* name : kMaterialExtensions) extensions->members[name] = material;
        memberOf(m_root, "materials")->element = material;
    }

    std::deque<SchemaNode> m_nodes;
    SchemaNode* m_root = nullptr;
    SchemaNode* m_textureInfo = nullptr;
};

const Schema& schema() {
    static const Schema s;
    return s;
}

// The largest magnitude accepted for any number that is not an integer (colours, intensities,
// transforms, camera parameters): 1e30, beyond the 1e-20..1e20 scales the image tests draw, and
// far below where double composition overflows (1e300 in a transform put Inf into EXR
// headers; in a light it turned the image black).
constexpr double kMaxMagnitude = 1e30;

// glTF's integer properties: tinygltf reads them into int or size_t, so 4294967296 became 0,
// 0.5 was dropped and -4 read as 0. Indices must be integers in 0..INT_MAX; offsets, lengths
// and counts in 0..2^53.
Result<void> checkInteger(const json& v, NumberKind kind, const std::string& path,
                          const Diagnostics& diag) {
    const double limit = kind == NumberKind::Index ? 2147483647.0 : 9007199254740992.0;
    const double d = v.get<double>();
    const bool integral = v.is_number_integer() || (std::isfinite(d) && d == std::floor(d));
    if (!integral)
        return diag.error(path, "is " + printable(v.dump(), 40) + ", not an integer");
    if (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() < 0)
        return diag.error(path, "is " + v.dump() + "; it must be 0 or more");
    if (d < 0) return diag.error(path, "is " + printable(v.dump(), 40) + "; it must be 0 or more");
    if (d > limit)
        return diag.error(path, "is " + printable(v.dump(), 40) + ", more than the largest " +
                                    (kind == NumberKind::Index ? "index" : "size") + " (" +
                                    std::to_string(std::uint64_t(limit)) + ")");
    return {};
}

Result<void> checkNumber(const json& v, const SchemaNode* node, const std::string& path,
                         const Diagnostics& diag) {
    const NumberKind kind = node ? node->kind : NumberKind::Any;
    if (kind != NumberKind::Any) return checkInteger(v, kind, path, diag);
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > kMaxMagnitude)
        return diag.error(path, "is " + printable(v.dump(), 40) +
                                    "; numbers beyond +-1e30 would become infinite on the way to "
                                    "an image");
    if (node && node->positive && !(d > 0))
        return diag.error(path, "is " + v.dump() + "; an aspect ratio must be greater than 0");
    return {};
}

// Walks the document once (linear; its depth is bounded by checkJsonNesting). A schema
// integer place given an array or object is left to the structural checks, which name it.
Result<void> walk(const json& v, const SchemaNode* node, std::string& path, bool inAccessor,
                  const Diagnostics& diag) {
    if (v.is_number()) return checkNumber(v, node, path, diag);
    const Schema& s = schema();
    if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it) {
            // Accessors' min/max describe the data, which is checked when read.
            if (inAccessor && (it.key() == "min" || it.key() == "max")) continue;
            bool skip = false;
            const SchemaNode* child = Schema::member(node, it.key(), skip, s.textureInfo());
            if (skip) continue;
            const std::size_t mark = path.size();
            path += (path.empty() ? "" : ".") + printable(it.key(), 40);
            const bool accessor = inAccessor || (node == s.root() && it.key() == "accessors");
            Result<void> r = walk(it.value(), child, path, accessor, diag);
            path.resize(mark);
            if (!r) return r;
        }
        return {};
    }
    if (v.is_array()) {
        // An array at an integer place (children, joints) holds integers; an array at a
        // number place (a colour, a matrix) numbers.
        const SchemaNode* element = node ? (node->element ? node->element : node) : nullptr;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::size_t mark = path.size();
            path += "[" + std::to_string(i) + "]";
            Result<void> r = walk(v[i], element, path, inAccessor, diag);
            path.resize(mark);
            if (!r) return r;
        }
    }
    return {};
}

} // namespace

NumberKind numberKindAt(std::string_view schemaPath) {
    const Schema& s = schema();
    const SchemaNode* node = s.root();
    while (node && !schemaPath.empty()) {
        if (schemaPath.substr(0, 2) == "[]") {
            node = node->element;
            schemaPath.remove_prefix(2);
        } else {
            if (schemaPath[0] == '.') schemaPath.remove_prefix(1);
            const std::size_t end = schemaPath.find_first_of(".[");
            const std::string_view key = schemaPath.substr(0, end);
            schemaPath = end == std::string_view::npos ? std::string_view() : schemaPath.substr(end);
            bool skip = false;
            node = Schema::member(node, key, skip, s.textureInfo());
            if (skip) return NumberKind::Any;
        }
    }
    return node ? node->kind : NumberKind::Any;
}

Result<void> checkAllNumbers(const json& doc, const Diagnostics& diag) {
    std::string path;
    return walk(doc, schema().root(), path, false, diag);
}

} // namespace lantern::gltf
