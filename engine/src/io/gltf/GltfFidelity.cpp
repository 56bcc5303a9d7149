// The fidelity report of a glTF file (Scene::features): every feature of the model noted with
// the objects that use it, by the keys of fidelityKeys() (scene/Fidelity.cpp).
#include "io/gltf/GltfInternal.h"
#include "scene/Fidelity.h"

#include <set>

namespace lantern::gltf {
namespace {

using scene::noteFeature;

// Material extensions and what they key.
constexpr const char* kMaterialExtensionKeys[] = {
    "KHR_materials_unlit",    "KHR_materials_emissive_strength", "KHR_materials_specular",
    "KHR_materials_ior",      "KHR_materials_clearcoat",         "KHR_materials_sheen",
    "KHR_materials_transmission", "KHR_materials_volume",
};

// Extensions noted where they are used (any other one in extensionsUsed is other-extension).
bool notedWhereUsed(const std::string& e) {
    for (const char* k : kMaterialExtensionKeys)
        if (e == k) return true;
    static const std::set<std::string> others = {
        "KHR_lights_punctual", "KHR_materials_variants", "KHR_texture_transform",
        "KHR_mesh_quantization", "EXT_meshopt_compression", "KHR_meshopt_compression",
        "KHR_draco_mesh_compression", "EXT_mesh_gpu_instancing", "EXT_texture_webp",
        "KHR_texture_basisu", "KHR_animation_pointer", "LANTERN_materials_phong",
        "LANTERN_lights_phong", "LANTERN_lights_shadow", "LANTERN_lighting", "LANTERN_camera"};
    return others.count(e) > 0;
}

void noteTextureInfo(const tinygltf::Model& model, int index, const tinygltf::ExtensionMap& ext,
                     const char* key, const std::string& object, Scene& scene) {
    if (index < 0) return;
    noteFeature(scene, key, object);
    if (extension(ext, "KHR_texture_transform")) noteFeature(scene, "KHR_texture_transform", object);
    if (std::size_t(index) >= model.textures.size()) return;
    const tinygltf::Texture& t = model.textures[std::size_t(index)];
    const std::string tobj = at("textures", std::size_t(index));
    if (extensionSource(t, "EXT_texture_webp") != -1) noteFeature(scene, "EXT_texture_webp", tobj);
    if (extensionSource(t, "KHR_texture_basisu") != -1) {
        if (t.source != -1)
            noteFeature(scene, "KHR_texture_basisu", tobj);
        else
            noteFeature(scene, "KHR_texture_basisu", tobj, Fidelity::Skipped,
                        "no-decoder-and-no-fallback");
    }
}

void noteMaterials(const tinygltf::Model& model, Scene& scene) {
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& m = model.materials[i];
        const std::string obj = at("materials", i);
        const bool phong = extension(m.extensions, "LANTERN_materials_phong") != nullptr;
        const bool unlit = extension(m.extensions, "KHR_materials_unlit") != nullptr;
        if (phong) noteFeature(scene, "lantern-extensions", obj + ".extensions.LANTERN_materials_phong");
        if (!phong && !unlit) noteFeature(scene, "pbr-factors", obj);
        const auto& pbr = m.pbrMetallicRoughness;
        noteTextureInfo(model, pbr.baseColorTexture.index, pbr.baseColorTexture.extensions,
                        "base-color-texture", obj + ".pbrMetallicRoughness.baseColorTexture", scene);
        noteTextureInfo(model, pbr.metallicRoughnessTexture.index,
                        pbr.metallicRoughnessTexture.extensions, "metallic-roughness-texture",
                        obj + ".pbrMetallicRoughness.metallicRoughnessTexture", scene);
        noteTextureInfo(model, m.normalTexture.index, m.normalTexture.extensions, "normal-texture",
                        obj + ".normalTexture", scene);
        noteTextureInfo(model, m.occlusionTexture.index, m.occlusionTexture.extensions,
                        "occlusion-texture", obj + ".occlusionTexture", scene);
        noteTextureInfo(model, m.emissiveTexture.index, m.emissiveTexture.extensions,
                        "emissive-texture", obj + ".emissiveTexture", scene);
        if (m.alphaMode != "OPAQUE" || m.doubleSided) noteFeature(scene, "alpha-modes", obj);
        for (const char* key : kMaterialExtensionKeys)
            if (extension(m.extensions, key)) noteFeature(scene, key, obj + ".extensions." + key);
    }
}

void noteMeshes(const tinygltf::Model& model, Scene& scene) {
    for (std::size_t i = 0; i < model.meshes.size(); ++i)
        for (std::size_t j = 0; j < model.meshes[i].primitives.size(); ++j) {
            const tinygltf::Primitive& p = model.meshes[i].primitives[j];
            const std::string obj = at("meshes", i) + "." + at("primitives", j);
            const bool points = p.mode == TINYGLTF_MODE_POINTS || p.mode == TINYGLTF_MODE_LINE ||
                                p.mode == TINYGLTF_MODE_LINE_LOOP || p.mode == TINYGLTF_MODE_LINE_STRIP;
            noteFeature(scene, points ? "points-lines" : "triangles", obj);
            noteFeature(scene, "attributes", obj);
            if (p.attributes.count("TANGENT") && needsTangents(model, p)) {
                // The deformation pre-pass moves positions and normals, not tangents.
                if (p.attributes.count("JOINTS_0") || !p.targets.empty())
                    noteFeature(scene, "tangents", obj + ".attributes.TANGENT",
                                Fidelity::Approximated, "derivative-frame-when-deformed");
                else
                    noteFeature(scene, "tangents", obj + ".attributes.TANGENT");
            }
            if (!p.targets.empty()) noteFeature(scene, "morph-targets", obj + ".targets");
            if (extension(p.extensions, "KHR_draco_mesh_compression"))
                noteFeature(scene, "KHR_draco_mesh_compression", obj);
            if (extension(p.extensions, "KHR_materials_variants"))
                noteFeature(scene, "KHR_materials_variants", obj);
        }
}

void noteNodesAndRest(const tinygltf::Model& model, const RawFacts& raw, Scene& scene) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& n = model.nodes[i];
        if (extension(n.extensions, "EXT_mesh_gpu_instancing"))
            noteFeature(scene, "EXT_mesh_gpu_instancing", at("nodes", i));
        if (extension(n.extensions, "KHR_lights_punctual"))
            noteFeature(scene, "KHR_lights_punctual", at("nodes", i));
    }
    for (std::size_t i = 0; i < model.skins.size(); ++i) noteFeature(scene, "skins", at("skins", i));
    for (std::size_t i = 0; i < model.animations.size(); ++i)
        noteFeature(scene, "animations", at("animations", i));
    for (const auto& [object, pointer] : raw.pointerChannels)
        noteFeature(scene, "KHR_animation_pointer", object);
    for (std::size_t i = 0; i < model.cameras.size(); ++i) {
        noteFeature(scene, "cameras", at("cameras", i));
        if (extension(model.cameras[i].extensions, "LANTERN_camera"))
            noteFeature(scene, "lantern-extensions", at("cameras", i) + ".extensions.LANTERN_camera");
    }
    for (std::size_t i = 0; i < model.scenes.size(); ++i) {
        noteFeature(scene, "scenes", at("scenes", i));
        if (extension(model.scenes[i].extensions, "LANTERN_lighting"))
            noteFeature(scene, "lantern-extensions", at("scenes", i) + ".extensions.LANTERN_lighting");
    }
    for (std::size_t i = 0; i < model.lights.size(); ++i)
        for (const char* name : {"LANTERN_lights_phong", "LANTERN_lights_shadow"})
            if (extension(model.lights[i].extensions, name))
                noteFeature(scene, "lantern-extensions",
                            "extensions.KHR_lights_punctual.lights[" + std::to_string(i) +
                                "].extensions." + name);
    for (std::size_t i = 0; i < model.bufferViews.size(); ++i)
        for (const char* name : kMeshoptExtensions)
            if (extension(model.bufferViews[i].extensions, name))
                noteFeature(scene, "EXT_meshopt_compression", at("bufferViews", i));
    for (std::size_t i = 0; i < model.extensionsUsed.size(); ++i) {
        const std::string& e = model.extensionsUsed[i];
        if (e == "KHR_mesh_quantization") noteFeature(scene, "KHR_mesh_quantization", at("extensionsUsed", i));
        if (!notedWhereUsed(e))
            noteFeature(scene, "other-extension", e, Fidelity::Skipped, "not-supported");
    }
}

} // namespace

void noteFeatures(const tinygltf::Model& model, const RawFacts& raw, bool glb, Scene& scene) {
    noteFeature(scene, "container", glb ? "GLB" : ".gltf");
    noteMaterials(model, scene);
    noteMeshes(model, scene);
    noteNodesAndRest(model, raw, scene);
}

} // namespace lantern::gltf
