// The fidelity report (common/FidelityReport.h).
#include "common/FidelityReport.h"

namespace lantern::cli {
namespace {

// Maps whose texels phong reads per fragment and gouraud and flat do not
// (docs/gl-differences.md): approximated there, by the rule named here.
const char* vertexShadingRule(const std::string& key) {
    if (key == "metallic-roughness-texture") return "texture-mean-in-gouraud-and-flat";
    if (key == "normal-texture" || key == "occlusion-texture") return "not-applied-in-gouraud-and-flat";
    return nullptr;
}

} // namespace

nlohmann::ordered_json fidelityJson(const Scene& scene, std::optional<ShadingMode> shading) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const FeatureUse& f : scene.features) {
        Fidelity fidelity = f.fidelity;
        std::string rule = f.rule;
        if (shading && *shading != ShadingMode::Phong && fidelity == Fidelity::Supported)
            if (const char* r = vertexShadingRule(f.key)) {
                fidelity = Fidelity::Approximated;
                rule = r;
            }
        nlohmann::ordered_json j;
        j["key"] = f.key;
        j["status"] = toString(fidelity);
        if (!rule.empty()) j["rule"] = rule;
        j["count"] = f.count;
        j["objects"] = f.objects;
        list.push_back(std::move(j));
    }
    return list;
}

nlohmann::ordered_json sceneReport(const std::string& source, const Scene& scene,
                                   std::optional<ShadingMode> shading) {
    nlohmann::ordered_json j;
    j["scene"] = source;
    if (shading) j["shading"] = toString(*shading);
    j["variants"] = scene.variants;
    if (scene.activeVariant >= 0) j["variant"] = scene.variants[std::size_t(scene.activeVariant)];
    j["features"] = fidelityJson(scene, shading);
    return j;
}

} // namespace lantern::cli
