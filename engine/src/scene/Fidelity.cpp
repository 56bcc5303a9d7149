// The fidelity report's vocabulary (fidelityKeys: one key per row of
// docs/scene-format-support.md's "At a glance" table, with how that feature is drawn) and the
// loaders' way of noting what a file uses (scene/Fidelity.h).
#include "scene/Fidelity.h"

#include <lantern/Assert.h>

#include <algorithm>

namespace lantern {
namespace {

constexpr std::size_t kMaxObjectsListed = 64;

FeatureUse row(const char* key, Fidelity f = Fidelity::Supported, const char* rule = "") {
    return FeatureUse{key, f, rule, {}, 0};
}

// The place of `key` in fidelityKeys(); a key it does not list is a programming error.
std::size_t rankOf(std::string_view key) {
    const auto& keys = fidelityKeys();
    const auto known = std::find_if(keys.begin(), keys.end(),
                                    [&](const FeatureUse& k) { return k.key == key; });
    LANTERN_ASSERT(known != keys.end(), "a fidelity key that fidelityKeys() does not list");
    return std::size_t(known - keys.begin());
}

} // namespace

const char* toString(Fidelity fidelity) noexcept {
    switch (fidelity) {
    case Fidelity::Supported: return "supported";
    case Fidelity::Approximated: return "approximated";
    case Fidelity::Skipped: return "skipped";
    }
    return "?";
}

const std::vector<FeatureUse>& fidelityKeys() {
    using F = Fidelity;
    static const std::vector<FeatureUse> keys = {
        row("container"),
        row("triangles"),
        row("points-lines"),
        row("attributes"),
        row("texcoord-sets"),
        row("tangents"),
        row("skins"),
        row("morph-targets"),
        row("animations"),
        row("KHR_animation_pointer", F::Skipped, "not-played"),
        row("cameras"),
        row("scenes"),
        row("pbr-factors", F::Approximated, "pbr-to-classic"),
        row("base-color-texture"),
        row("KHR_texture_transform"),
        row("metallic-roughness-texture", F::Supported, "per-texel-in-phong"),
        row("normal-texture", F::Supported, "phong-only"),
        row("occlusion-texture", F::Supported, "phong-only"),
        row("emissive-texture"),
        row("alpha-modes"),
        row("KHR_lights_punctual"),
        row("KHR_materials_unlit"),
        row("KHR_materials_emissive_strength"),
        row("KHR_materials_variants"),
        row("KHR_materials_specular", F::Approximated, "specular-scales-dielectric-f0"),
        row("KHR_materials_ior", F::Approximated, "ior-sets-dielectric-f0"),
        row("KHR_materials_clearcoat", F::Approximated, "clearcoat-sharpens-specular"),
        row("KHR_materials_sheen", F::Approximated, "sheen-adds-to-diffuse"),
        row("KHR_materials_transmission", F::Approximated, "transmission-as-alpha-blend"),
        row("KHR_materials_volume", F::Approximated, "volume-absorbs-transmission"),
        row("KHR_mesh_quantization"),
        row("EXT_meshopt_compression"),
        row("KHR_draco_mesh_compression"),
        row("EXT_mesh_gpu_instancing"),
        row("EXT_texture_webp"),
        row("KHR_texture_basisu", F::Supported, "png-jpeg-fallback"),
        row("lantern-extensions"),
        row("other-extension", F::Skipped, "not-supported"),
        row("obj"),
        row("obj-skipped-maps", F::Skipped, "not-read"),
        row("ply"),
        row("stl"),
        row("off"),
        row("up-axis"),
    };
    return keys;
}

namespace scene {

void noteFeature(Scene& scene, std::string_view key, std::string object, Fidelity fidelity,
                 std::string rule) {
    rankOf(key);
    // Kept in the table's order; one entry per (key, status, rule).
    auto it = std::find_if(scene.features.begin(), scene.features.end(), [&](const FeatureUse& f) {
        return f.key == key && f.fidelity == fidelity && f.rule == rule;
    });
    if (it == scene.features.end()) {
        const auto rank = [](const FeatureUse& f) { return rankOf(f.key); };
        FeatureUse use{std::string(key), fidelity, std::move(rule), {}, 0};
        it = scene.features.insert(
            std::upper_bound(scene.features.begin(), scene.features.end(), use,
                             [&](const FeatureUse& a, const FeatureUse& b) { return rank(a) < rank(b); }),
            std::move(use));
    }
    ++it->count;
    if (!object.empty() && it->objects.size() < kMaxObjectsListed &&
        std::find(it->objects.begin(), it->objects.end(), object) == it->objects.end())
        it->objects.push_back(std::move(object));
}

void noteFeature(Scene& scene, std::string_view key, std::string object) {
    const FeatureUse& row = fidelityKeys()[rankOf(key)];
    noteFeature(scene, key, std::move(object), row.fidelity, row.rule);
}

} // namespace scene
} // namespace lantern
