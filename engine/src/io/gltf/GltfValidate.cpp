// The glTF loader's structural pass: the asset version, required extensions, every reference
// between objects, every buffer view and accessor (bounds, alignment, formats per use), index
// and count rules, enums. Runs before any data is read; messages carry glTF object paths.
#include "io/gltf/GltfInternal.h"

#include <algorithm>
#include <cstring>
#include <set>

namespace lantern::gltf {
namespace {


bool supported(const std::string& extension) {
    return std::any_of(std::begin(kSupportedExtensions), std::end(kSupportedExtensions),
                       [&](const char* e) { return extension == e; });
}

// Whether every KHR_texture_basisu texture also names a PNG or JPEG image (`source`): then the
// file can be drawn, though it requires the extension (KTX2 has no decoder in Debian).
bool basisuHasFallbacks(const tinygltf::Model& model) {
    return std::all_of(model.textures.begin(), model.textures.end(), [](const auto& t) {
        return extensionSource(t, "KHR_texture_basisu") == -1 || t.source != -1;
    });
}

/// "2.0" -> {2, 0}; nothing for anything that is not MAJOR.MINOR.
std::optional<std::pair<int, int>> parseVersion(const std::string& v) {
    const std::size_t dot = v.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == v.size() || v.size() > 12)
        return std::nullopt;
    for (std::size_t i = 0; i < v.size(); ++i)
        if (i != dot && (v[i] < '0' || v[i] > '9')) return std::nullopt;
    return std::pair{std::stoi(v.substr(0, dot)), std::stoi(v.substr(dot + 1))};
}

Result<void> checkIndex(int index, std::size_t size, const std::string& object, const char* what,
                        const Diagnostics& diag) {
    if (index < 0 || std::size_t(index) >= size)
        return diag.error(object, std::string(what) + " " + std::to_string(index) +
                                      " does not exist (the file has " + std::to_string(size) +
                                      ")");
    return {};
}

/// An accessor used for a purpose: its type and component types must be among those allowed.
struct Format {
    std::vector<int> types;
    std::vector<int> componentTypes; ///< FLOAT, or normalized integer types
    bool allowNormalizedOnly = true; ///< integer types must be normalized
};

Result<void> checkFormat(const tinygltf::Model& model, int accessor, const Format& format,
                         const std::string& object, const Diagnostics& diag) {
    const tinygltf::Accessor& a = model.accessors[std::size_t(accessor)];
    const bool typeOk =
        std::find(format.types.begin(), format.types.end(), a.type) != format.types.end();
    const bool componentOk =
        std::find(format.componentTypes.begin(), format.componentTypes.end(), a.componentType) !=
            format.componentTypes.end() &&
        (a.componentType == kFloat || !format.allowNormalizedOnly || a.normalized);
    if (typeOk && componentOk) return {};
    std::string allowed;
    for (int t : format.types)
        allowed += (allowed.empty() ? "" : "/") + typeName(t);
    allowed += " of ";
    bool first = true;
    for (int c : format.componentTypes) {
        allowed += (first ? "" : ", ") +
                   std::string(c != kFloat && format.allowNormalizedOnly ? "normalized " : "") +
                   componentTypeName(c);
        first = false;
    }
    return diag.error(object, at("accessors", std::size_t(accessor)) + " is " + typeName(a.type) +
                                  " of " + (a.normalized ? "normalized " : "") +
                                  componentTypeName(a.componentType) + "; expected " + allowed);
}

/// Whether the file declares `name` (in extensionsUsed; extensionsRequired should be a subset).
bool declares(const tinygltf::Model& model, const char* name) {
    for (const auto* list : {&model.extensionsUsed, &model.extensionsRequired})
        if (std::find(list->begin(), list->end(), name) != list->end()) return true;
    return false;
}

/// The formats allowed for each vertex attribute Lantern reads: glTF 2.0's, or, when the file
/// declares KHR_mesh_quantization, that extension's wider table (integer positions and texture
/// coordinates, normalized or not; BYTE/SHORT normalized normals and tangents; BYTE/SHORT morph target
/// position displacements, normalized or not, and normalized normal displacements). Skin
/// influences (JOINTS_0/1, WEIGHTS_0/1) are the same in both: KHR_mesh_quantization leaves them.
struct AttributeFormats {
    Format position, normal, tangent, color, texcoord, joints, weights, targetPosition, targetNormal;
    explicit AttributeFormats(bool quantized)
        : position{{TINYGLTF_TYPE_VEC3}, {kFloat}}, normal{{TINYGLTF_TYPE_VEC3}, {kFloat}},
          tangent{{TINYGLTF_TYPE_VEC4}, {kFloat}},
          color{{TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, {kFloat, kUnsignedByte, kUnsignedShort}},
          texcoord{{TINYGLTF_TYPE_VEC2}, {kFloat, kUnsignedByte, kUnsignedShort}},
          joints{{TINYGLTF_TYPE_VEC4}, {kUnsignedByte, kUnsignedShort}, false},
          weights{{TINYGLTF_TYPE_VEC4}, {kFloat, kUnsignedByte, kUnsignedShort}},
          targetPosition{{TINYGLTF_TYPE_VEC3}, {kFloat}},
          targetNormal{{TINYGLTF_TYPE_VEC3}, {kFloat}} {
        if (!quantized) return;
        const std::vector<int> all{kFloat, kByte, kUnsignedByte, kShort, kUnsignedShort};
        position = {{TINYGLTF_TYPE_VEC3}, all, false};
        normal = {{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kShort}};
        tangent = {{TINYGLTF_TYPE_VEC4}, {kFloat, kByte, kShort}};
        texcoord = {{TINYGLTF_TYPE_VEC2}, all, false};
        targetPosition = {{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kShort}, false};
        targetNormal = {{TINYGLTF_TYPE_VEC3}, {kFloat, kByte, kShort}};
    }
    /// The format for attribute `name` (of a morph target when `target`), or null for
    /// attributes Lantern does not read.
    const Format* of(const std::string& name, bool target) const {
        if (target) {
            if (name == "POSITION") return &targetPosition;
            if (name == "NORMAL") return &targetNormal;
            return nullptr;
        }
        if (name == "POSITION") return &position;
        if (name == "NORMAL") return &normal;
        if (name == "TANGENT") return &tangent;
        if (name == "COLOR_0") return &color;
        if (name.rfind("TEXCOORD_", 0) == 0) return &texcoord;
        if (name == "JOINTS_0" || name == "JOINTS_1") return &joints;
        if (name == "WEIGHTS_0" || name == "WEIGHTS_1") return &weights;
        return nullptr;
    }
};

/// An attribute's format (a morph target's when `target`); a refusal says when
/// KHR_mesh_quantization would have allowed it.
Result<void> checkAttributeFormat(const tinygltf::Model& model, int accessor,
                                  const std::string& name, bool target, bool quantized,
                                  const std::string& object, const Diagnostics& diag) {
    static const AttributeFormats core(false), withQuantization(true);
    const Format* format = (quantized ? withQuantization : core).of(name, target);
    if (!format) return {};
    auto checked = checkFormat(model, accessor, *format, object, diag);
    if (checked || quantized ||
        !checkFormat(model, accessor, *withQuantization.of(name, target), object,
                     Diagnostics("", {})))
        return checked;
    Error e = std::move(checked).error();
    e.message += " (KHR_mesh_quantization allows it, but the file does not declare that "
                 "extension in extensionsUsed)";
    return e;
}

Result<void> validateMeshes(const tinygltf::Model& model, const RawFacts& raw,
                            const Diagnostics& diag) {
    const bool quantized = declares(model, "KHR_mesh_quantization");
    const Format indices{
        {TINYGLTF_TYPE_SCALAR}, {kUnsignedByte, kUnsignedShort, kUnsignedInt}, false};
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const tinygltf::Mesh& mesh = model.meshes[m];
        if (m < raw.primitiveCounts.size() && raw.primitiveCounts[m] != mesh.primitives.size())
            return diag.error(at("meshes", m) + ".primitives",
                              "only " + std::to_string(mesh.primitives.size()) + " of " +
                                  std::to_string(raw.primitiveCounts[m]) +
                                  " primitives could be parsed");
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            const std::string obj = at("meshes", m) + "." + at("primitives", p);
            if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
                return diag.error(obj + ".mode", std::to_string(prim.mode) +
                                                     " is not a glTF primitive mode (0-6)");
            if (prim.material != -1)
                LANTERN_TRY(checkIndex(prim.material, model.materials.size(), obj + ".material",
                                       "material", diag));
            std::optional<std::size_t> count;
            std::string countFrom;
            for (const auto& [name, accessor] : prim.attributes) {
                const std::string aobj = obj + ".attributes." + name;
                LANTERN_TRY(checkIndex(accessor, model.accessors.size(), aobj, "accessor", diag));
                LANTERN_TRY(checkAttributeFormat(model, accessor, name, false, quantized, aobj, diag));
                const std::size_t n = model.accessors[std::size_t(accessor)].count;
                if (count && *count != n)
                    return diag.error(aobj, "has " + std::to_string(n) + " elements but " +
                                                countFrom + " has " + std::to_string(*count) +
                                                " (attributes of a primitive must match)");
                count = n;
                countFrom = name;
            }
            for (std::size_t t = 0; t < prim.targets.size(); ++t)
                for (const auto& [name, accessor] : prim.targets[t]) {
                    const std::string tobj = obj + "." + at("targets", t) + "." + name;
                    LANTERN_TRY(checkIndex(accessor, model.accessors.size(), tobj, "accessor", diag));
                    LANTERN_TRY(
                        checkAttributeFormat(model, accessor, name, true, quantized, tobj, diag));
                    const std::size_t n = model.accessors[std::size_t(accessor)].count;
                    if (count && *count != n)
                        return diag.error(tobj, "has " + std::to_string(n) + " elements but " +
                                                    countFrom + " has " + std::to_string(*count) +
                                                    " (a morph target matches its primitive)");
                }
            if (p > 0 && prim.targets.size() != mesh.primitives[0].targets.size())
                return diag.error(obj + ".targets",
                                  "has " + std::to_string(prim.targets.size()) +
                                      " morph targets; primitives[0] has " +
                                      std::to_string(mesh.primitives[0].targets.size()) +
                                      " (every primitive of a mesh has the same number)");
            if (prim.indices != -1) {
                LANTERN_TRY(checkIndex(prim.indices, model.accessors.size(), obj + ".indices",
                                       "accessor", diag));
                LANTERN_TRY(checkFormat(model, prim.indices, indices, obj + ".indices", diag));
                const tinygltf::Accessor& a = model.accessors[std::size_t(prim.indices)];
                if (a.bufferView >= 0 &&
                    model.bufferViews[std::size_t(a.bufferView)].byteStride != 0)
                    return diag.error(obj + ".indices",
                                      "index data must be tightly packed (" +
                                          at("bufferViews", std::size_t(a.bufferView)) +
                                          " has a byteStride)");
            }
        }
    }
    return {};
}

Result<void> validateMaterialsAndTextures(const tinygltf::Model& model, const Diagnostics& diag) {
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& m = model.materials[i];
        const std::string obj = at("materials", i);
        const std::pair<const char*, int> refs[] = {
            {"pbrMetallicRoughness.baseColorTexture",
             m.pbrMetallicRoughness.baseColorTexture.index},
            {"pbrMetallicRoughness.metallicRoughnessTexture",
             m.pbrMetallicRoughness.metallicRoughnessTexture.index},
            {"normalTexture", m.normalTexture.index},
            {"occlusionTexture", m.occlusionTexture.index},
            {"emissiveTexture", m.emissiveTexture.index},
        };
        for (const auto& [name, index] : refs)
            if (index != -1)
                LANTERN_TRY(checkIndex(index, model.textures.size(), obj + "." + name + ".index",
                                       "texture", diag));
        if (m.alphaMode != "OPAQUE" && m.alphaMode != "MASK" && m.alphaMode != "BLEND")
            return diag.error(obj + ".alphaMode",
                              "\"" + m.alphaMode + "\" is not OPAQUE, MASK or BLEND");
    }
    for (std::size_t i = 0; i < model.textures.size(); ++i) {
        const tinygltf::Texture& t = model.textures[i];
        if (t.source != -1)
            LANTERN_TRY(checkIndex(t.source, model.images.size(), at("textures", i) + ".source",
                                   "image", diag));
        for (const char* ext : {"EXT_texture_webp", "KHR_texture_basisu"})
            if (const int source = extensionSource(t, ext); source != -1)
                LANTERN_TRY(checkIndex(source, model.images.size(),
                                       at("textures", i) + ".extensions." + ext + ".source",
                                       "image", diag));
        if (t.sampler != -1)
            LANTERN_TRY(checkIndex(t.sampler, model.samplers.size(), at("textures", i) + ".sampler",
                                   "sampler", diag));
    }
    for (std::size_t i = 0; i < model.images.size(); ++i)
        if (model.images[i].bufferView != -1)
            LANTERN_TRY(checkIndex(model.images[i].bufferView, model.bufferViews.size(),
                                   at("images", i) + ".bufferView", "bufferView", diag));
    return {};
}

Result<void> validateNodes(const tinygltf::Model& model, const Diagnostics& diag) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& n = model.nodes[i];
        const std::string obj = at("nodes", i);
        if (n.mesh != -1)
            LANTERN_TRY(checkIndex(n.mesh, model.meshes.size(), obj + ".mesh", "mesh", diag));
        if (n.camera != -1)
            LANTERN_TRY(
                checkIndex(n.camera, model.cameras.size(), obj + ".camera", "camera", diag));
        if (n.skin != -1)
            LANTERN_TRY(checkIndex(n.skin, model.skins.size(), obj + ".skin", "skin", diag));
        for (std::size_t c = 0; c < n.children.size(); ++c)
            LANTERN_TRY(checkIndex(n.children[c], model.nodes.size(), obj + "." + at("children", c),
                                   "node", diag));
        const struct {
            const char* name;
            const std::vector<double>& values;
            std::size_t size;
        } arrays[] = {{"matrix", n.matrix, 16},
                      {"translation", n.translation, 3},
                      {"rotation", n.rotation, 4},
                      {"scale", n.scale, 3}};
        for (const auto& a : arrays)
            if (!a.values.empty() && a.values.size() != a.size)
                return diag.error(obj + "." + a.name, "has " + std::to_string(a.values.size()) +
                                                          " numbers, expected " +
                                                          std::to_string(a.size));
        auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext != n.extensions.end()) {
            const std::string lobj = obj + ".extensions.KHR_lights_punctual.light";
            const tinygltf::Value& light = ext->second.Get("light");
            if (!light.IsInt()) return diag.error(lobj, "is missing or not an integer");
            LANTERN_TRY(
                checkIndex(light.GetNumberAsInt(), model.lights.size(), lobj, "light", diag));
        }
    }
    for (std::size_t s = 0; s < model.scenes.size(); ++s)
        for (std::size_t k = 0; k < model.scenes[s].nodes.size(); ++k)
            LANTERN_TRY(checkIndex(model.scenes[s].nodes[k], model.nodes.size(),
                                   at("scenes", s) + "." + at("nodes", k), "node", diag));
    if (model.defaultScene != -1)
        LANTERN_TRY(checkIndex(model.defaultScene, model.scenes.size(), "scene", "scene", diag));
    return {};
}

Result<void> validateSkins(const tinygltf::Model& model, const Diagnostics& diag) {
    const Format matrices{{TINYGLTF_TYPE_MAT4}, {kFloat}};
    for (std::size_t i = 0; i < model.skins.size(); ++i) {
        const tinygltf::Skin& skin = model.skins[i];
        const std::string obj = at("skins", i);
        if (skin.joints.empty()) return diag.error(obj + ".joints", "a skin needs at least one joint");
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
            LANTERN_TRY(checkIndex(skin.joints[j], model.nodes.size(), obj + "." + at("joints", j),
                                   "node", diag));
        if (skin.skeleton != -1)
            LANTERN_TRY(checkIndex(skin.skeleton, model.nodes.size(), obj + ".skeleton", "node", diag));
        if (skin.inverseBindMatrices != -1) {
            const std::string mobj = obj + ".inverseBindMatrices";
            LANTERN_TRY(checkIndex(skin.inverseBindMatrices, model.accessors.size(), mobj,
                                   "accessor", diag));
            LANTERN_TRY(checkFormat(model, skin.inverseBindMatrices, matrices, mobj, diag));
            const std::size_t count = model.accessors[std::size_t(skin.inverseBindMatrices)].count;
            if (count < skin.joints.size())
                return diag.error(mobj, "has " + std::to_string(count) + " matrices for " +
                                            std::to_string(skin.joints.size()) + " joints");
        }
    }
    return {};
}

// Whether a channel drives a node's translation, rotation or scale (one output element per key).
bool playsTransform(const tinygltf::AnimationChannel& ch) {
    return ch.target_path == "translation" || ch.target_path == "rotation" ||
           ch.target_path == "scale";
}

Result<void> validateAnimations(const tinygltf::Model& model, const Diagnostics& diag) {
    const Format input{{TINYGLTF_TYPE_SCALAR}, {kFloat}};
    const Format vec3{{TINYGLTF_TYPE_VEC3}, {kFloat}};
    const Format rotation{{TINYGLTF_TYPE_VEC4},
                          {kFloat, kByte, kUnsignedByte,
                           kShort, kUnsignedShort}};
    const Format weights{{TINYGLTF_TYPE_SCALAR},
                         {kFloat, kByte, kUnsignedByte,
                          kShort, kUnsignedShort}};
    for (std::size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& anim = model.animations[a];
        const std::string obj = at("animations", a);
        for (std::size_t s = 0; s < anim.samplers.size(); ++s) {
            const tinygltf::AnimationSampler& smp = anim.samplers[s];
            const std::string sobj = obj + "." + at("samplers", s);
            if (smp.interpolation != "LINEAR" && smp.interpolation != "STEP" &&
                smp.interpolation != "CUBICSPLINE")
                return diag.error(sobj + ".interpolation",
                                  "\"" + smp.interpolation +
                                      "\" is not LINEAR, STEP or CUBICSPLINE");
            LANTERN_TRY(
                checkIndex(smp.input, model.accessors.size(), sobj + ".input", "accessor", diag));
            LANTERN_TRY(
                checkIndex(smp.output, model.accessors.size(), sobj + ".output", "accessor", diag));
            LANTERN_TRY(checkFormat(model, smp.input, input, sobj + ".input", diag));
            const std::size_t keys = model.accessors[std::size_t(smp.input)].count;
            const std::size_t per = smp.interpolation == "CUBICSPLINE" ? 3 : 1;
            if (per == 3 && keys < 2)
                return diag.error(sobj + ".input",
                                  "CUBICSPLINE needs at least 2 keys, got " + std::to_string(keys));
            const std::size_t values = model.accessors[std::size_t(smp.output)].count;
            // A sampler that drives a node's translation, rotation or scale holds one element
            // per key (three for CUBICSPLINE). Any other (morph weights, checked when a channel
            // uses them; KHR_animation_pointer's, which drive what Lantern does not play, or
            // none) holds a whole number of elements per key: the spec's only rule for them.
            bool oneElementPerKey = false;
            for (const auto& ch : anim.channels)
                if (ch.sampler == int(s) && ch.target_node != -1 && playsTransform(ch))
                    oneElementPerKey = true;
            if (oneElementPerKey ? values != keys * per : keys > 0 && values % (keys * per) != 0)
                return diag.error(sobj + ".output",
                                  "has " + std::to_string(values) + " elements for " +
                                      std::to_string(keys) + " keys (expected " +
                                      (oneElementPerKey ? "" : "a multiple of ") +
                                      std::to_string(keys * per) + ")");
        }
        std::set<std::pair<int, std::string>> targets;
        for (std::size_t c = 0; c < anim.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = anim.channels[c];
            const std::string cobj = obj + "." + at("channels", c);
            LANTERN_TRY(
                checkIndex(ch.sampler, anim.samplers.size(), cobj + ".sampler", "sampler", diag));
            if (ch.target_node != -1)
                LANTERN_TRY(checkIndex(ch.target_node, model.nodes.size(), cobj + ".target.node",
                                       "node", diag));
            const int output = anim.samplers[std::size_t(ch.sampler)].output;
            const std::string pobj = cobj + ".target.path";
            if (ch.target_path == "pointer") continue;  // warned from RawFacts::pointerChannels
            if (ch.target_path == "translation" || ch.target_path == "scale")
                LANTERN_TRY(checkFormat(model, output, vec3, pobj, diag));
            else if (ch.target_path == "rotation")
                LANTERN_TRY(checkFormat(model, output, rotation, pobj, diag));
            else if (ch.target_path == "weights")
                LANTERN_TRY(checkFormat(model, output, weights, pobj, diag));
            else
                return diag.error(pobj, "\"" + ch.target_path +
                                            "\" is not translation, rotation, scale or weights");
            if (ch.target_node != -1 && !targets.insert({ch.target_node, ch.target_path}).second)
                diag.warn(cobj, "a second channel animates " + ch.target_path + " of node " +
                                    std::to_string(ch.target_node) + "; the last one wins");
        }
    }
    return {};
}

} // namespace

Result<void> validateModel(const tinygltf::Model& model, const RawFacts& raw,
                           const LoadOptions& options, const Diagnostics& diag) {
    const auto version = parseVersion(model.asset.version);
    if (!version)
        return diag.error("asset.version",
                          "\"" + model.asset.version + "\" is not a MAJOR.MINOR version");
    if (version->first != 2)
        return diag.error("asset.version",
                          "glTF " + model.asset.version + " is not supported (only 2.x)");
    if (!model.asset.minVersion.empty()) {
        const auto minVersion = parseVersion(model.asset.minVersion);
        if (!minVersion)
            return diag.error("asset.minVersion",
                              "\"" + model.asset.minVersion + "\" is not a MAJOR.MINOR version");
        if (*minVersion > *version)
            return diag.error("asset.minVersion", model.asset.minVersion +
                                                      " is greater than the version " +
                                                      model.asset.version);
        if (*minVersion > std::pair{2, 0})
            return diag.error("asset.minVersion", "the file needs glTF " + model.asset.minVersion +
                                                      "; this loader reads 2.0");
    }
    for (std::size_t i = 0; i < model.extensionsRequired.size(); ++i)
        if (!supported(model.extensionsRequired[i]) &&
            !(model.extensionsRequired[i] == "KHR_texture_basisu" && basisuHasFallbacks(model)))
            return diag.error(at("extensionsRequired", i),
                              "extension " + model.extensionsRequired[i] +
                                  " is required by the file but not supported");
    std::string ignored;
    for (const std::string& e : model.extensionsUsed)
        // KHR_texture_basisu is read through its fallbacks (a texture without one warns).
        if (!supported(e) && e != "KHR_texture_basisu") ignored += (ignored.empty() ? "" : ", ") + e;
    if (!ignored.empty()) diag.warn("extensionsUsed", "ignored (not supported): " + ignored);

    for (std::size_t i = 0; i < model.bufferViews.size(); ++i)
        LANTERN_TRY(checkBufferView(model, int(i), diag));
    for (std::size_t i = 0; i < model.accessors.size(); ++i) {
        LANTERN_TRY(checkAccessor(model, int(i), options, diag));
        // Non-finite floats are refused wherever they are, used or not: it costs one read of
        // the float data and gives the accessor's own path in the message.
        if (model.accessors[i].componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            auto values = readFloats(model, int(i), at("accessors", i), diag);
            if (!values) return std::move(values).error();
        }
    }
    LANTERN_TRY(validateMeshes(model, raw, diag));
    LANTERN_TRY(validateMaterialsAndTextures(model, diag));
    LANTERN_TRY(validateNodes(model, diag));
    LANTERN_TRY(validateSkins(model, diag));
    LANTERN_TRY(validateAnimations(model, diag));
    // KHR_animation_pointer (materials, lights, cameras, node properties by JSON pointer) is
    // not played; required, the file was refused above with the extension.
    for (const auto& [object, pointer] : raw.pointerChannels)
        diag.warn(object, "animates " + printable(pointer, 80) +
                              " through KHR_animation_pointer, which Lantern does not play; "
                              "channel skipped");
    return {};
}

} // namespace lantern::gltf
