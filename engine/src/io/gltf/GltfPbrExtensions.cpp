// The KHR_materials_* extensions beyond unlit and emissive strength, read and approximated in
// the classic equation, one documented rule each (docs/scene-format-support.md, "The other
// KHR_materials extensions"):
//   specular, ior    the dielectric F0 the PBR mapping starts from (0.04 without them);
//   clearcoat        a second, white lobe folded into the one specular term: its F0 added, the
//                    shininess moved towards the coat's;
//   sheen            the sheen colour added to the diffuse (and ambient) colour;
//   transmission     see-through as alpha blending: the dielectric share lets light through;
//   volume           what is seen through shrinks by the volume's mean absorption; the surface
//                    takes its tint (blending cannot tint what lies behind).
// Their textures are not read (the factors are); the rules are the fidelity report's names.
#include "io/gltf/GltfInternal.h"

#include <algorithm>
#include <cmath>

namespace lantern::gltf {
namespace {

// A member block of an extension, read with its checks; nothing when the material lacks it.
std::optional<ExtensionReader> block(const tinygltf::Material& src, const char* name,
                                     const std::string& obj, const Diagnostics& diag) {
    const tinygltf::Value* e = extension(src.extensions, name);
    if (!e) return std::nullopt;
    return ExtensionReader(*e, obj + ".extensions." + name, diag);
}

void inUnit(const ExtensionReader& r, const char* key, double v) {
    if (!(v >= 0.0 && v <= 1.0)) r.fail(key, "must be in [0, 1], got " + std::to_string(v));
}

} // namespace

Result<PbrExtensions> readPbrExtensions(const tinygltf::Material& src, const std::string& obj,
                                        const Diagnostics& diag) {
    PbrExtensions x;
    double ior = 1.5;
    if (auto r = block(src, "KHR_materials_ior", obj, diag)) {
        ior = r->number("ior", 1.5);
        if (!(ior == 0.0 || ior >= 1.0)) r->fail("ior", "must be 0 or at least 1");
        LANTERN_TRY(r->status());
    }
    // ior 0 is the spec's "infinite": a perfect mirror's F0 of 1.
    const double f0 = ior == 0.0 ? 1.0 : std::pow((ior - 1.0) / (ior + 1.0), 2.0);
    x.dielectricF0 = glm::dvec3(f0);
    if (auto r = block(src, "KHR_materials_specular", obj, diag)) {
        const double factor = r->number("specularFactor", 1.0);
        const glm::dvec3 colour = r->vec3("specularColorFactor", glm::dvec3(1.0));
        inUnit(*r, "specularFactor", factor);
        if (colour.x < 0 || colour.y < 0 || colour.z < 0)
            r->fail("specularColorFactor", "must be >= 0");
        LANTERN_TRY(r->status());
        x.dielectricF0 = glm::min(x.dielectricF0 * colour, glm::dvec3(1.0)) * factor;
    }
    if (auto r = block(src, "KHR_materials_clearcoat", obj, diag)) {
        x.clearcoat = r->number("clearcoatFactor", 0.0);
        x.clearcoatRoughness = r->number("clearcoatRoughnessFactor", 0.0);
        inUnit(*r, "clearcoatFactor", x.clearcoat);
        inUnit(*r, "clearcoatRoughnessFactor", x.clearcoatRoughness);
        LANTERN_TRY(r->status());
    }
    if (auto r = block(src, "KHR_materials_sheen", obj, diag)) {
        x.sheenColor = r->vec3("sheenColorFactor", glm::dvec3(0.0));
        const double roughness = r->number("sheenRoughnessFactor", 0.0);
        if (x.sheenColor.x < 0 || x.sheenColor.y < 0 || x.sheenColor.z < 0)
            r->fail("sheenColorFactor", "must be >= 0");
        inUnit(*r, "sheenRoughnessFactor", roughness);
        LANTERN_TRY(r->status());
    }
    if (auto r = block(src, "KHR_materials_transmission", obj, diag)) {
        x.transmission = r->number("transmissionFactor", 0.0);
        inUnit(*r, "transmissionFactor", x.transmission);
        LANTERN_TRY(r->status());
    }
    if (auto r = block(src, "KHR_materials_volume", obj, diag)) {
        x.thickness = r->number("thicknessFactor", 0.0);
        x.attenuationColor = r->vec3("attenuationColor", glm::dvec3(1.0));
        x.attenuationDistance = r->number("attenuationDistance", kInfinity);
        if (x.thickness < 0) r->fail("thicknessFactor", "must be >= 0");
        if (!(x.attenuationDistance > 0)) r->fail("attenuationDistance", "must be > 0");
        if (glm::any(glm::lessThan(x.attenuationColor, glm::dvec3(0.0))) ||
            glm::any(glm::greaterThan(x.attenuationColor, glm::dvec3(1.0))))
            r->fail("attenuationColor", "must be in [0, 1]");
        LANTERN_TRY(r->status());
    }
    return x;
}

void applyPbrExtensions(const PbrExtensions& x, double metallic, Material& m) {
    MaterialSide& side = m.front;
    if (x.clearcoat > 0.0) {
        // The coat: a white dielectric lobe (F0 0.04) of its own roughness, folded into the one
        // specular term (energy-normalised as the base's: (s + 8) / 8).
        const PhongFromPbr coat = phongFromPbr(glm::dvec3(1.0), 0.0, x.clearcoatRoughness);
        side.specular += x.clearcoat * coat.specular;
        side.shininess = std::exp(std::log(side.shininess) * (1.0 - x.clearcoat) +
                                  std::log(coat.shininess) * x.clearcoat);
    }
    if (x.sheenColor != glm::dvec3(0.0)) {
        const glm::dvec3 sheen = 0.2 * x.sheenColor;
        side.diffuse += glm::dvec4(sheen, 0.0);
        side.ambient += sheen;
    }
    if (x.transmission > 0.0) {
        // What the dielectric share transmits is seen through (blended). A volume absorbs on
        // the way, attenuationColor^(thickness / attenuationDistance) (Beer-Lambert): blending
        // cannot tint what lies behind, so the share seen through shrinks by the mean of that
        // transmittance and the surface takes its tint.
        glm::dvec3 tint(1.0);
        if (x.thickness > 0.0 && std::isfinite(x.attenuationDistance))
            tint = glm::pow(x.attenuationColor, glm::dvec3(x.thickness / x.attenuationDistance));
        const double through = x.transmission * (1.0 - metallic) * (tint.x + tint.y + tint.z) / 3.0;
        const glm::dvec3 body = glm::mix(glm::dvec3(1.0), tint, x.transmission * (1.0 - metallic));
        side.diffuse = glm::dvec4(glm::dvec3(side.diffuse) * body, side.diffuse.a * (1.0 - through));
        side.ambient *= body;
        if (m.alphaMode == AlphaMode::Opaque) m.alphaMode = AlphaMode::Blend;
        if (m.pbr) m.pbr->baseColor.a = side.diffuse.a;
    }
}

} // namespace lantern::gltf
