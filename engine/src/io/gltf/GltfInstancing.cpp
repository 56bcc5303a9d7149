// EXT_mesh_gpu_instancing (gltfpack -mi: forests, crowds, CAD assemblies): a node's mesh drawn
// at every instance's TRANSLATION, ROTATION and SCALE, in the node's space. The instances
// become child nodes of the node, one per instance, which draw the mesh (the node itself then
// draws nothing). Drawn correctly, as one draw per instance: instanced draws are the renderer's
// to add (docs/scene-format-support.md). Custom attributes (_ID, _COLOR...) are ignored.
#include "io/gltf/GltfInternal.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace lantern::gltf {
namespace {

struct InstanceAttributes {
    std::vector<double> translation, rotation, scale;
    std::size_t count = 0;
};

// One attribute: `components` numbers per instance (FLOAT or integers, normalized or not, as
// KHR_mesh_quantization allows); the count must be the other attributes'.
Result<std::vector<double>> readAttribute(const tinygltf::Model& model, const tinygltf::Value& ext,
                                          const char* name, int components, std::size_t& count,
                                          const std::string& obj, const Diagnostics& diag) {
    if (!ext.Has("attributes") || !ext.Get("attributes").Has(name)) return std::vector<double>();
    const std::string aobj = obj + ".attributes." + name;
    const tinygltf::Value& v = ext.Get("attributes").Get(name);
    if (!v.IsNumber()) return diag.error(aobj, "is not an accessor index");
    const double index = v.GetNumberAsDouble();
    if (index < 0 || index >= double(model.accessors.size()))
        return diag.error(aobj, "accessor " + std::to_string(std::int64_t(index)) +
                                    " does not exist (the file has " +
                                    std::to_string(model.accessors.size()) + ")");
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    if (componentCount(a.type) != components)
        return diag.error(aobj, "is " + typeName(a.type) + "; " + name + " needs " +
                                    (components == 3 ? "VEC3" : "VEC4"));
    if (count != 0 && a.count != count)
        return diag.error(aobj, "has " + std::to_string(a.count) + " instances where the other "
                                "attributes have " + std::to_string(count));
    count = a.count;
    return readDoubles(model, int(index), aobj, diag);
}

Result<InstanceAttributes> readInstances(const tinygltf::Model& model, const tinygltf::Value& ext,
                                         const std::string& obj, const Diagnostics& diag) {
    InstanceAttributes in;
    if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
        return diag.error(obj + ".attributes", "is missing or not an object");
    LANTERN_TAKE(in.translation, readAttribute(model, ext, "TRANSLATION", 3, in.count, obj, diag));
    LANTERN_TAKE(in.rotation, readAttribute(model, ext, "ROTATION", 4, in.count, obj, diag));
    LANTERN_TAKE(in.scale, readAttribute(model, ext, "SCALE", 3, in.count, obj, diag));
    return in;
}

Node instanceNode(const Node& of, const InstanceAttributes& in, std::size_t i) {
    Node n;
    n.name = of.name + " [instance " + std::to_string(i) + "]";
    n.mesh = of.mesh;
    n.skin = of.skin;
    n.weights = of.weights;
    if (!in.translation.empty())
        n.translation = {in.translation[3 * i], in.translation[3 * i + 1], in.translation[3 * i + 2]};
    if (!in.rotation.empty()) {
        const glm::dquat q(in.rotation[4 * i + 3], in.rotation[4 * i], in.rotation[4 * i + 1],
                           in.rotation[4 * i + 2]);
        const double len = glm::length(q);
        n.rotation = len > 0.0 ? q / len : glm::dquat(1.0, 0.0, 0.0, 0.0);
    }
    if (!in.scale.empty()) n.scale = {in.scale[3 * i], in.scale[3 * i + 1], in.scale[3 * i + 2]};
    return n;
}

} // namespace

Result<void> expandInstances(const tinygltf::Model& model, const Diagnostics& diag, Scene& scene) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Value* ext = extension(model.nodes[i].extensions, "EXT_mesh_gpu_instancing");
        if (!ext || scene.nodes[i].mesh < 0) continue;
        const std::string obj = at("nodes", i) + ".extensions.EXT_mesh_gpu_instancing";
        auto in = readInstances(model, *ext, obj, diag);
        if (!in) return std::move(in).error();
        LANTERN_TRY(diag.charge(in->count, sizeof(Node) + sizeof(int), obj, "its instances' nodes"));
        for (std::size_t k = 0; k < in->count; ++k) {
            scene.nodes.push_back(instanceNode(scene.nodes[i], *in, k));
            scene.nodes[i].children.push_back(int(scene.nodes.size()) - 1);
        }
        if (in->count > 0) scene.nodes[i].mesh = -1;  // drawn by its instances
    }
    return {};
}

} // namespace lantern::gltf
