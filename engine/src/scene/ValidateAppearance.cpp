// Scene::validate()'s checks of what a scene looks like: materials (sides, maps), textures,
// lights and cameras (the rest is in Validate.cpp).
#include "scene/ValidateSupport.h"

namespace lantern::validation {
namespace {

Result<void> validateSide(const MaterialSide& s, const std::string& object) {
    if (!finite(s.ambient)) return invalid(object + ".ambient", "non-finite colour");
    if (!finite(s.diffuse)) return invalid(object + ".diffuse", "non-finite colour");
    if (!finite(s.specular)) return invalid(object + ".specular", "non-finite colour");
    if (!finite(s.emission)) return invalid(object + ".emission", "non-finite colour");
    if (!finite(s.shininess))
        return invalid(object + ".shininess", "shininess must be a finite number");
    if (s.shininess < 0.0)
        return invalid(object + ".shininess",
                       "shininess must be >= 0, got " + std::to_string(s.shininess));
    return {};
}

Result<void> validateMaps(const Scene& scene, const Material& mat, const std::string& obj) {
    for (const auto& [map, name] : {std::pair{&mat.metallicRoughnessMap, ".metallicRoughnessMap"},
                                    std::pair{&mat.normalMap, ".normalMap"},
                                    std::pair{&mat.occlusionMap, ".occlusionMap"},
                                    std::pair{&mat.emissiveMap, ".emissiveMap"}})
        if (map->texture < -1 || map->texture >= int(scene.textures.size()) ||
            !finite(map->uvTransform[0]) || !finite(map->uvTransform[1]) || !finite(map->uvTransform[2]))
            return invalid(obj + name, "texture " + std::to_string(map->texture) +
                                           " does not exist, or its uv transform is not finite");
    const PbrFactors* p = mat.pbr ? &*mat.pbr : nullptr;
    if ((mat.metallicRoughnessMap.texture >= 0 && !p) ||
        (p && (!finite(p->baseColor) || !(p->metallic >= 0.0 && p->metallic <= 1.0) ||
               !(p->roughness >= 0.0 && p->roughness <= 1.0))))
        return invalid(obj + ".pbr", "a metallic-roughness map needs factors: finite base colour, "
                                     "metallic and roughness in [0, 1]");
    if (!finite(mat.normalScale) || !(mat.occlusionStrength >= 0.0 && mat.occlusionStrength <= 1.0))
        return invalid(obj, "the normal scale must be finite and the occlusion strength in [0, 1]");
    return {};
}

Result<void> validateMaterials(const Scene& scene) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& mat = scene.materials[i];
        const std::string obj = at("materials", i);
        LANTERN_TRY(validateSide(mat.front, obj));
        if (mat.back) LANTERN_TRY(validateSide(*mat.back, obj + ".back"));
        if (!finite(mat.alphaCutoff) || mat.alphaCutoff < 0.0)
            return invalid(obj + ".alphaCutoff", "alpha cutoff must be a finite number >= 0");
        if (mat.baseColorTexture < -1 || mat.baseColorTexture >= int(scene.textures.size()))
            return invalid(obj + ".baseColorTexture",
                           "texture " + std::to_string(mat.baseColorTexture) + " does not exist");
        LANTERN_TRY(validateMaps(scene, mat, obj));
    }
    return {};
}

Result<void> validateTextures(const Scene& scene) {
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        if (t.width <= 0 || t.height <= 0 ||
            t.rgba8.size() != std::size_t(t.width) * std::size_t(t.height) * 4)
            return invalid(at("textures", i), "texture size and pixel data do not match");
    }
    return {};
}

Result<void> validateLight(const Light& l, const std::string& obj) {
    if (!finite(l.ambient) || !finite(l.diffuse) || !finite(l.specular))
        return invalid(obj, "non-finite light colour");
    if (!finite(l.attenuation))
        return invalid(obj + ".attenuation", "non-finite attenuation coefficient");
    if (l.attenuation.x < 0 || l.attenuation.y < 0 || l.attenuation.z < 0)
        return invalid(obj + ".attenuation", "attenuation coefficients must be >= 0");
    if (l.attenuation.x == 0 && l.attenuation.y == 0 && l.attenuation.z == 0)
        return invalid(obj + ".attenuation",
                       "attenuation coefficients are all zero (infinite light)");
    if (!finite(l.spotExponent) || l.spotExponent < 0)
        return invalid(obj + ".spotExponent", "spot exponent must be a finite number >= 0");
    if (!finite(l.spotCutoffDeg) ||
        !((l.spotCutoffDeg >= 0 && l.spotCutoffDeg <= 90) || l.spotCutoffDeg == 180))
        return invalid(obj + ".spotCutoffDeg",
                       "spot cutoff " + std::to_string(l.spotCutoffDeg) +
                           " is outside [0, 90] and not 180 (GL's no-cone value): a cone "
                           "wider than a half-space is not a spot light");
    if (std::isnan(l.range) || !(l.range > 0)) return invalid(obj + ".range", "range must be > 0");
    if (!finite(l.innerConeAngle) || !finite(l.outerConeAngle) || l.innerConeAngle < 0 ||
        !(l.innerConeAngle < l.outerConeAngle) || l.outerConeAngle > 1.5707963267948966)
        return invalid(obj, "spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    return {};
}

Result<void> validateLights(const Scene& scene) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        LANTERN_TRY(validateLight(scene.lights[i], at("lights", i)));
    return {};
}

Result<void> validateCameras(const Scene& scene) {
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        const std::string obj = at("cameras", i);
        LANTERN_TRY(checkProjection(scene.cameras[i].projection, obj));
        if (scene.cameras[i].lookAt)
            LANTERN_TRY(checkLookAt(*scene.cameras[i].lookAt, obj + ".lookAt"));
    }
    return {};
}

// One node's references and transform; its children are checked by validateNodes.

} // namespace

Result<void> validateAppearance(const Scene& scene) {
    LANTERN_TRY(validateMaterials(scene));
    LANTERN_TRY(validateTextures(scene));
    LANTERN_TRY(validateLights(scene));
    return validateCameras(scene);
}

} // namespace lantern::validation
