// glTF lights and cameras -> Lantern's: KHR_lights_punctual lights (with
// LANTERN_lights_phong), and glTF perspective and orthographic cameras (with LANTERN_camera).
#include "io/gltf/GltfInternal.h"

#include <cmath>

namespace lantern::gltf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// glTF's perspective projection; no zfar (`hasZfar` false) is an infinite one.
Result<Projection> perspectiveProjection(const tinygltf::PerspectiveCamera& p, bool hasZfar,
                                         const std::string& pobj, const Diagnostics& diag) {
    if (!(std::isfinite(p.yfov) && p.yfov > 0.0 && p.yfov < kPi))
        return diag.error(pobj + ".yfov",
                          "must be in (0, pi) radians, got " + std::to_string(p.yfov));
    if (!(std::isfinite(p.znear) && p.znear > 0.0))
        return diag.error(pobj + ".znear", "must be a finite number > 0");
    if (!(std::isfinite(p.aspectRatio) && p.aspectRatio >= 0.0))
        return diag.error(pobj + ".aspectRatio", "must be a finite number > 0");
    double zfar = kInfinity; // glTF: no zfar is an infinite projection
    if (hasZfar) {
        if (!(std::isfinite(p.zfar) && p.zfar > p.znear))
            return diag.error(pobj + ".zfar", "must be a finite number > znear (" +
                                                  std::to_string(p.znear) + "), got " +
                                                  std::to_string(p.zfar));
        zfar = p.zfar;
    }
    const Projection projection = Projection::makePerspective(p.yfov, p.aspectRatio, p.znear, zfar);
    if (auto ok = checkProjection(projection, pobj); !ok)
        return inFile(std::move(ok).error(), diag);
    return projection;
}

Result<Projection> orthographicProjection(const tinygltf::OrthographicCamera& o,
                                          const std::string& oobj, const Diagnostics& diag) {
    for (auto [name, v] : {std::pair{"xmag", o.xmag}, std::pair{"ymag", o.ymag}})
        if (!(std::isfinite(v) && v != 0.0))
            return diag.error(oobj + "." + name, "must be a finite, non-zero number");
    if (!(std::isfinite(o.znear) && o.znear >= 0.0))
        return diag.error(oobj + ".znear", "must be a finite number >= 0");
    if (!(std::isfinite(o.zfar) && o.zfar > o.znear))
        return diag.error(oobj + ".zfar", "must be a finite number > znear (" +
                                              std::to_string(o.znear) + "), got " +
                                              std::to_string(o.zfar));
    return Projection::makeOrtho(-o.xmag, o.xmag, -o.ymag, o.ymag, o.znear, o.zfar);
}

// LANTERN_camera's "frustum" or "ortho" block (`kind`): GL's glFrustum/glOrtho planes.
Result<Projection> readProjectionBox(const ExtensionReader& box, const char* kind,
                                     const Diagnostics& diag) {
    box.warnUnknown({"left", "right", "bottom", "top", "near", "far"});
    double v[6];
    const char* names[6] = {"left", "right", "bottom", "top", "near", "far"};
    for (int i = 0; i < 6; ++i) {
        // Only a frustum's far plane may be left out: it is then at infinity.
        const bool optional = i == 5 && std::string(kind) == "frustum";
        if (!box.has(names[i]) && !optional)
            return diag.error(box.object() + "." + names[i], "is missing");
        v[i] = box.number(names[i], kInfinity);
    }
    LANTERN_TRY(box.status());
    const Projection projection = std::string(kind) == "frustum"
                                      ? Projection::makeFrustum(v[0], v[1], v[2], v[3], v[4], v[5])
                                      : Projection::makeOrtho(v[0], v[1], v[2], v[3], v[4], v[5]);
    if (auto ok = checkProjection(projection, box.object()); !ok)
        return inFile(std::move(ok).error(), diag);
    return projection;
}

// LANTERN_camera's "lookAt" block: eye, target and up, all required.
Result<LookAt> readLookAt(const ExtensionReader& look, const Diagnostics& diag) {
    look.warnUnknown({"eye", "target", "up"});
    LookAt la;
    for (auto [name, field] :
         {std::pair{"eye", &la.eye}, std::pair{"target", &la.target}, std::pair{"up", &la.up}}) {
        if (!look.has(name)) return diag.error(look.object() + "." + name, "is missing");
        *field = look.vec3(name, {});
    }
    LANTERN_TRY(look.status());
    if (auto ok = checkLookAt(la, look.object()); !ok) return inFile(std::move(ok).error(), diag);
    return la;
}

// LANTERN_camera: a frustum or ortho block replaces the glTF projection; a lookAt places the
// camera.
Result<void> applyLanternCamera(const ExtensionReader& ext, const Diagnostics& diag, Camera& c) {
    if (ext.has("frustum") && ext.has("ortho"))
        return diag.error(ext.object(), "has both frustum and ortho (at most one is allowed)");
    for (const char* kind : {"frustum", "ortho"}) {
        if (!ext.has(kind)) continue;
        auto box = ext.child(kind);
        if (!box) return diag.error(ext.object() + "." + kind, "must be an object");
        auto projection = readProjectionBox(*box, kind, diag);
        if (!projection) return std::move(projection).error();
        c.projection = *projection;
    }
    if (ext.has("lookAt")) {
        auto look = ext.child("lookAt");
        if (!look) return diag.error(ext.object() + ".lookAt", "must be an object");
        auto la = readLookAt(*look, diag);
        if (!la) return std::move(la).error();
        c.lookAt = *la;
    }
    return {};
}

} // namespace

Result<Light> convertLight(const tinygltf::Light& src, std::size_t index, const Diagnostics& diag) {
    const std::string obj = "extensions.KHR_lights_punctual." + at("lights", index);
    Light l;
    l.name = src.name;
    if (src.type == "directional")
        l.type = LightType::Directional;
    else if (src.type == "point")
        l.type = LightType::Point;
    else if (src.type == "spot")
        l.type = LightType::Spot;
    else
        return diag.error(obj + ".type", "\"" + src.type + "\" is not directional, point or spot");
    std::vector<double> color = src.color.empty() ? std::vector<double>{1, 1, 1} : src.color;
    if (color.size() != 3 || !allFinite(color))
        return diag.error(obj + ".color", "must be 3 finite numbers");
    if (!std::isfinite(src.intensity) || src.intensity < 0.0)
        return diag.error(obj + ".intensity", "must be a finite number >= 0");
    // tinygltf reads an absent range as 0: both mean "unlimited".
    if (std::isnan(src.range) || src.range < 0.0) return diag.error(obj + ".range", "must be > 0");
    l.range = src.range > 0.0 && std::isfinite(src.range) ? src.range : kInfinity;
    if (l.type == LightType::Spot) {
        const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner < outer && outer <= kPi / 2))
            return diag.error(obj + ".spot", "cone angles must satisfy 0 <= innerConeAngle (" +
                                                 std::to_string(inner) + ") < outerConeAngle (" +
                                                 std::to_string(outer) + ") <= pi/2");
        l.innerConeAngle = inner;
        l.outerConeAngle = outer;
    }
    // LANTERN_lights_shadow: the light casts shadows ("castShadows", true by default).
    if (const tinygltf::Value* e = extension(src.extensions, "LANTERN_lights_shadow")) {
        ExtensionReader r(*e, obj + ".extensions.LANTERN_lights_shadow", diag);
        r.warnUnknown({"castShadows"});
        l.castShadows = r.boolean("castShadows", true);
        LANTERN_TRY(r.status());
    }
    if (const tinygltf::Value* e = extension(src.extensions, "LANTERN_lights_phong")) {
        ExtensionReader r(*e, obj + ".extensions.LANTERN_lights_phong", diag);
        r.warnUnknown(
            {"ambient", "diffuse", "specular", "attenuation", "spotExponent", "spotCutoffDeg"});
        const glm::dvec3 att = r.vec3("attenuation", {1, 0, 0});
        const double exponent = r.number("spotExponent", 0.0);
        const double cutoff = r.number("spotCutoffDeg", 180.0);
        l.ambient = r.vec3("ambient", {0, 0, 0});
        l.diffuse = r.vec3("diffuse", {1, 1, 1});
        l.specular = r.vec3("specular", {1, 1, 1});
        LANTERN_TRY(r.status());
        if (att.x < 0 || att.y < 0 || att.z < 0)
            return diag.error(r.object() + ".attenuation",
                              "coefficients must be >= 0 (a negative one can make the light "
                              "infinitely bright at some distance)");
        if (att == glm::dvec3(0.0))
            return diag.error(r.object() + ".attenuation",
                              "coefficients are all zero (1/0: an infinitely bright light)");
        if (exponent < 0.0) return diag.error(r.object() + ".spotExponent", "must be >= 0");
        if (!((cutoff >= 0.0 && cutoff <= 90.0) || cutoff == 180.0))
            return diag.error(r.object() + ".spotCutoffDeg",
                              std::to_string(cutoff) +
                                  " is outside [0, 90] and not 180 (GL's no-cone value): a cone "
                                  "wider than a half-space is not a spot light");
        if (l.type != LightType::Spot && cutoff != 180.0)
            diag.warn(r.object() + ".spotCutoffDeg",
                      "ignored: the light's KHR_lights_punctual type is " + src.type);
        if (l.type == LightType::Spot && cutoff == 180.0)
            diag.warn(r.object(), "spot light without spotCutoffDeg (default 180, no cone): it "
                                  "lights in every direction like GL's");
        l.falloff = LightFalloff::Gl;
        l.attenuation = att;
        l.spotExponent = exponent;
        l.spotCutoffDeg = cutoff;
    } else {
        l.falloff = LightFalloff::Gltf;
        l.ambient = glm::dvec3(0.0);
        l.diffuse = l.specular = vec3(color) * src.intensity;
    }
    return l;
}

Result<Camera> convertCamera(const tinygltf::Camera& src, std::size_t index, bool hasZfar,
                             const Diagnostics& diag) {
    const std::string obj = at("cameras", index);
    Camera c;
    c.name = src.name;
    const tinygltf::Value* lantern = extension(src.extensions, "LANTERN_camera");
    std::optional<ExtensionReader> ext;
    if (lantern) ext.emplace(*lantern, obj + ".extensions.LANTERN_camera", diag);
    const bool replaced = ext && (ext->has("frustum") || ext->has("ortho"));
    if (ext) ext->warnUnknown({"frustum", "ortho", "lookAt"});

    if (!replaced && src.type == "perspective") {
        auto p = perspectiveProjection(src.perspective, hasZfar, obj + ".perspective", diag);
        if (!p) return std::move(p).error();
        c.projection = *p;
    } else if (!replaced && src.type == "orthographic") {
        auto o = orthographicProjection(src.orthographic, obj + ".orthographic", diag);
        if (!o) return std::move(o).error();
        c.projection = *o;
    } else if (!replaced) {
        return diag.error(obj + ".type", "\"" + src.type + "\" is not perspective or orthographic");
    }
    if (ext) LANTERN_TRY(applyLanternCamera(*ext, diag, c));
    return c;
}

} // namespace lantern::gltf
