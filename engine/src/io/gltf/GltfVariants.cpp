// KHR_materials_variants: the file's variant names (extensions.KHR_materials_variants.variants)
// and each primitive's mappings (material per variant), checked and kept in the scene model;
// selectMaterialVariant (scene/Scene.cpp) picks one, as LoadOptions::variant asks.
#include "io/gltf/GltfInternal.h"

namespace lantern::gltf {

Result<std::vector<std::string>> variantNames(const tinygltf::Model& model, const Diagnostics& diag) {
    std::vector<std::string> names;
    const tinygltf::Value* ext = extension(model.extensions, "KHR_materials_variants");
    if (!ext) return names;
    const std::string obj = "extensions.KHR_materials_variants.variants";
    if (!ext->IsObject() || !ext->Has("variants") || !ext->Get("variants").IsArray())
        return diag.error(obj, "is missing or not an array");
    const tinygltf::Value& list = ext->Get("variants");
    for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
        const tinygltf::Value& v = list.Get(int(i));
        if (!v.IsObject() || !v.Has("name") || !v.Get("name").IsString())
            return diag.error(obj + "[" + std::to_string(i) + "].name", "is missing or not a string");
        names.push_back(v.Get("name").Get<std::string>());
    }
    return names;
}

namespace {

// An index member of a mapping: an integer (the JSON pass checked its range) below `count`.
Result<int> mappingIndex(const tinygltf::Value& v, std::size_t count, const std::string& object,
                         const char* what, const Diagnostics& diag) {
    if (!v.IsNumber()) return diag.error(object, "is not an integer");
    const double d = v.GetNumberAsDouble();
    if (d < 0 || d >= double(count))
        return diag.error(object, std::string(what) + " " + std::to_string(std::int64_t(d)) +
                                      " does not exist (" + std::to_string(count) + " " + what +
                                      "s)");
    return int(d);
}

} // namespace

Result<std::vector<Primitive::VariantMaterial>> primitiveVariants(const tinygltf::Model& model,
                                                                  const tinygltf::Primitive& prim,
                                                                  std::size_t variantCount,
                                                                  const std::string& obj,
                                                                  const Diagnostics& diag) {
    std::vector<Primitive::VariantMaterial> out;
    const tinygltf::Value* ext = extension(prim.extensions, "KHR_materials_variants");
    if (!ext) return out;
    const std::string base = obj + ".extensions.KHR_materials_variants.mappings";
    if (!ext->IsObject() || !ext->Has("mappings") || !ext->Get("mappings").IsArray())
        return diag.error(base, "is missing or not an array");
    const tinygltf::Value& mappings = ext->Get("mappings");
    for (std::size_t m = 0; m < mappings.ArrayLen(); ++m) {
        const tinygltf::Value& mapping = mappings.Get(int(m));
        const std::string mobj = base + "[" + std::to_string(m) + "]";
        if (!mapping.IsObject() || !mapping.Has("material") || !mapping.Has("variants") ||
            !mapping.Get("variants").IsArray())
            return diag.error(mobj, "needs a material and an array of variants");
        auto material = mappingIndex(mapping.Get("material"), model.materials.size(),
                                     mobj + ".material", "material", diag);
        if (!material) return std::move(material).error();
        const tinygltf::Value& variants = mapping.Get("variants");
        for (std::size_t k = 0; k < variants.ArrayLen(); ++k) {
            auto variant = mappingIndex(variants.Get(int(k)), variantCount,
                                        mobj + ".variants[" + std::to_string(k) + "]", "variant",
                                        diag);
            if (!variant) return std::move(variant).error();
            out.push_back({*variant, *material});
        }
    }
    return out;
}

} // namespace lantern::gltf
