// glTF (after validation) -> Lantern's scene model: materials (LANTERN_materials_phong, the PBR
// fallback mapping, KHR_materials_unlit, alpha modes), base-colour textures decoded to RGBA8,
// KHR_lights_punctual lights (with LANTERN_lights_phong), cameras (glTF perspective/
// orthographic, LANTERN_camera), nodes, scenes (LANTERN_lighting) and animations. Every value
// is checked where it is read; messages carry the glTF object path.
#include "io/GltfInternal.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <set>
#include <stb_image.h>

namespace lantern::gltf {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 vec3(const std::vector<double>& v) {
    return {v[0], v[1], v[2]};
}
glm::dvec4 vec4(const std::vector<double>& v) {
    return {v[0], v[1], v[2], v.size() > 3 ? v[3] : 1.0};
}

bool allFinite(const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

/// Attaches the file to errors from the scene model's checkers (checkProjection, ...).
Error inFile(Error e, const Diagnostics& diag) {
    e.file = diag.file();
    return e;
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name) {
    auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

// --- Materials and textures -----------------------------------------------------------------

/// One side of LANTERN_materials_phong; defaults are GL's (MaterialSide's).
MaterialSide readPhongSide(const ExtensionReader& r) {
    r.warnUnknown({"ambient", "diffuse", "specular", "emission", "shininess", "back"});
    MaterialSide s;
    s.ambient = r.vec3("ambient", s.ambient);
    s.diffuse = r.rgba("diffuse", s.diffuse);
    s.specular = r.vec3("specular", s.specular);
    s.emission = r.vec3("emission", s.emission);
    s.shininess = r.number("shininess", s.shininess);
    if (s.shininess < 0.0) r.fail("shininess", "must be >= 0, got " + std::to_string(s.shininess));
    return s;
}

/// Decodes base-colour textures on first use and maps (glTF texture) -> Scene::textures.
class TextureTable {
public:
    TextureTable(const tinygltf::Model& model, const ImageStore& images, const RawFacts& raw,
                 const LoadOptions& options, const Diagnostics& diag, std::vector<Texture>& out)
        : m_model(model), m_images(images), m_raw(raw), m_options(options), m_diag(diag),
          m_out(out) {}

    /// The Scene::textures index for glTF texture `index`, -1 when it has no image we read.
    Result<int> get(int index, const std::string& usedBy) {
        if (auto it = m_done.find(index); it != m_done.end()) return it->second;
        const tinygltf::Texture& t = m_model.textures[std::size_t(index)];
        if (t.source < 0) {
            m_diag.warn(at("textures", std::size_t(index)),
                        "no source image (an extension's image format?); " + usedBy +
                            " is drawn without it");
            return m_done[index] = -1;
        }
        auto decoded = decode(t.source);
        if (!decoded) return std::move(decoded).error();
        Texture tex = std::move(*decoded);
        if (t.sampler >= 0) {
            const tinygltf::Sampler& s = m_model.samplers[std::size_t(t.sampler)];
            tex.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
            tex.clampToEdge = s.wrapS == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
                              s.wrapT == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
            if (s.wrapS == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ||
                s.wrapT == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
                m_diag.warn(at("samplers", std::size_t(t.sampler)),
                            "MIRRORED_REPEAT is drawn as REPEAT");
        }
        m_out.push_back(std::move(tex));
        return m_done[index] = int(m_out.size()) - 1;
    }

    /// The mean metallic (blue) and roughness (green) of a metallicRoughnessTexture, or
    /// nothing when the texture has no image Lantern reads.
    Result<std::optional<glm::dvec2>> meanMetallicRoughness(int index) {
        const tinygltf::Texture& t = m_model.textures[std::size_t(index)];
        if (t.source < 0) return std::optional<glm::dvec2>{};
        auto decoded = decode(t.source);
        if (!decoded) return std::move(decoded).error();
        double metallic = 0.0, roughness = 0.0;
        const std::size_t pixels = decoded->rgba8.size() / 4;
        for (std::size_t i = 0; i < pixels; ++i) {
            roughness += decoded->rgba8[i * 4 + 1];
            metallic += decoded->rgba8[i * 4 + 2];
        }
        const double scale = 1.0 / (255.0 * double(std::max<std::size_t>(pixels, 1)));
        return std::optional<glm::dvec2>(glm::dvec2(metallic * scale, roughness * scale));
    }

private:
    Result<Texture> decode(int source) {
        const tinygltf::Image& image = m_model.images[std::size_t(source)];
        const std::string obj = at("images", std::size_t(source));
        const unsigned char* bytes = nullptr;
        std::size_t size = 0;
        if (auto it = m_images.encoded.find(source); it != m_images.encoded.end()) {
            bytes = it->second.data();
            size = it->second.size();
        } else if (image.bufferView >= 0) {
            LANTERN_TRY(checkBufferView(m_model, image.bufferView, m_diag));
            const tinygltf::BufferView& bv = m_model.bufferViews[std::size_t(image.bufferView)];
            bytes = m_model.buffers[std::size_t(bv.buffer)].data.data() + bv.byteOffset;
            size = bv.byteLength;
        } else {
            auto problem = m_raw.imageProblems.find(source);
            return m_diag.error(obj + ".uri", problem != m_raw.imageProblems.end()
                                                  ? problem->second
                                                  : "\"" + image.uri + "\" could not be read");
        }
        if (size > std::size_t(INT_MAX)) return m_diag.error(obj, "encoded image is too large");
        int w = 0, h = 0, channels = 0;
        if (!stbi_info_from_memory(bytes, int(size), &w, &h, &channels))
            return m_diag.error(obj, std::string("cannot be decoded: ") + stbi_failure_reason());
        if (w <= 0 || h <= 0 || w > kMaxTextureSide || h > kMaxTextureSide)
            return m_diag.error(obj, std::to_string(w) + "x" + std::to_string(h) +
                                         " is outside the supported texture size (1 to " +
                                         std::to_string(kMaxTextureSide) + " per side)");
        const std::uint64_t rgbaBytes = std::uint64_t(w) * std::uint64_t(h) * 4;
        if (rgbaBytes > m_options.maxBytes)
            return m_diag.error(obj, "decoded image (" + std::to_string(rgbaBytes) +
                                         " bytes) exceeds --max-size (" +
                                         std::to_string(m_options.maxBytes) + " bytes)");
        stbi_uc* pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4);
        if (!pixels)
            return m_diag.error(obj, std::string("cannot be decoded: ") + stbi_failure_reason());
        Texture t;
        t.name = !image.name.empty() ? image.name : image.uri.size() < 200 ? image.uri : obj;
        t.width = w;
        t.height = h;
        t.rgba8.assign(pixels, pixels + rgbaBytes);
        stbi_image_free(pixels);
        return t;
    }

    const tinygltf::Model& m_model;
    const ImageStore& m_images;
    const RawFacts& m_raw;
    const LoadOptions& m_options;
    const Diagnostics& m_diag;
    std::vector<Texture>& m_out;
    std::map<int, int> m_done;
};

Result<Material> convertMaterial(const tinygltf::Model& model, std::size_t index,
                                 TextureTable& textures, const Diagnostics& diag) {
    const tinygltf::Material& src = model.materials[index];
    const std::string obj = at("materials", index);
    const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
    Material m;
    m.name = src.name;
    if (pbr.baseColorFactor.size() != 4 || !allFinite(pbr.baseColorFactor))
        return diag.error(obj + ".pbrMetallicRoughness.baseColorFactor",
                          "must be 4 finite numbers");
    for (auto [name, value] : {std::pair{"metallicFactor", pbr.metallicFactor},
                               std::pair{"roughnessFactor", pbr.roughnessFactor}})
        if (!(value >= 0.0 && value <= 1.0))
            return diag.error(obj + ".pbrMetallicRoughness." + name,
                              "must be a number in [0, 1], got " + std::to_string(value));
    if (src.emissiveFactor.size() != 3 || !allFinite(src.emissiveFactor))
        return diag.error(obj + ".emissiveFactor", "must be 3 finite numbers");
    if (!std::isfinite(src.alphaCutoff) || src.alphaCutoff < 0.0)
        return diag.error(obj + ".alphaCutoff", "must be a finite number >= 0");
    m.alphaMode = src.alphaMode == "BLEND"  ? AlphaMode::Blend
                  : src.alphaMode == "MASK" ? AlphaMode::Mask
                                            : AlphaMode::Opaque;
    m.alphaCutoff = src.alphaCutoff;
    m.doubleSided = src.doubleSided;
    m.unlit = extension(src.extensions, "KHR_materials_unlit") != nullptr;

    double emissiveStrength = 1.0;
    if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_emissive_strength")) {
        ExtensionReader r(*e, obj + ".extensions.KHR_materials_emissive_strength", diag);
        emissiveStrength = r.number("emissiveStrength", 1.0);
        if (emissiveStrength < 0.0) r.fail("emissiveStrength", "must be >= 0");
        LANTERN_TRY(r.status());
    }

    const glm::dvec4 baseColor = vec4(pbr.baseColorFactor);
    if (const tinygltf::Value* e = extension(src.extensions, "LANTERN_materials_phong")) {
        ExtensionReader r(*e, obj + ".extensions.LANTERN_materials_phong", diag);
        m.front = readPhongSide(r);
        if (auto back = r.child("back"))
            m.back = readPhongSide(*back);
        else if (r.has("back"))
            r.fail("back", "must be an object");
        LANTERN_TRY(r.status());
    } else if (m.unlit) {
        // KHR_materials_unlit: the colour is the base colour; lighting terms are unused.
        m.front.diffuse = baseColor;
        m.front.ambient = glm::dvec3(baseColor);
        m.front.specular = glm::dvec3(0.0);
        m.front.emission = glm::dvec3(0.0);
        m.ambientFollowsDiffuse = true;
    } else {
        // The PBR fallback (scene-format.md section 2). A metallicRoughnessTexture scales the
        // factors per texel; the Phong material is uniform, so it takes the texture's mean
        // (without it, the default factors 1 and 1 turn every textured PBR material into a
        // uniform white specular).
        double metallic = pbr.metallicFactor, roughness = pbr.roughnessFactor;
        if (pbr.metallicRoughnessTexture.index >= 0) {
            auto mean = textures.meanMetallicRoughness(pbr.metallicRoughnessTexture.index);
            if (!mean) return std::move(mean).error();
            if (*mean) {
                metallic *= (*mean)->x;
                roughness *= (*mean)->y;
            }
        }
        const glm::dvec3 base(baseColor);
        m.front.diffuse = glm::dvec4(base * (1.0 - metallic), baseColor.a);
        m.front.specular = glm::mix(glm::dvec3(0.04), base, metallic);
        const double r4 = roughness * roughness * roughness * roughness;
        m.front.shininess =
            r4 > 0.0 ? std::min(2.0 / r4 - 2.0, kMaxPbrShininess) : kMaxPbrShininess;
        m.front.ambient = glm::dvec3(m.front.diffuse);
        m.front.emission = vec3(src.emissiveFactor) * emissiveStrength;
        m.ambientFollowsDiffuse = true;
    }
    if (pbr.baseColorTexture.index >= 0) {
        auto t = textures.get(pbr.baseColorTexture.index, obj);
        if (!t) return std::move(t).error();
        m.baseColorTexture = *t;
    }
    return m;
}

// --- Lights -----------------------------------------------------------------------------------

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

// --- Cameras ----------------------------------------------------------------------------------

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
        const tinygltf::PerspectiveCamera& p = src.perspective;
        const std::string pobj = obj + ".perspective";
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
        c.projection = Projection::makePerspective(p.yfov, p.aspectRatio, p.znear, zfar);
        if (auto ok = checkProjection(c.projection, pobj); !ok)
            return inFile(std::move(ok).error(), diag);
    } else if (!replaced && src.type == "orthographic") {
        const tinygltf::OrthographicCamera& o = src.orthographic;
        const std::string oobj = obj + ".orthographic";
        for (auto [name, v] : {std::pair{"xmag", o.xmag}, std::pair{"ymag", o.ymag}})
            if (!(std::isfinite(v) && v != 0.0))
                return diag.error(oobj + "." + name, "must be a finite, non-zero number");
        if (!(std::isfinite(o.znear) && o.znear >= 0.0))
            return diag.error(oobj + ".znear", "must be a finite number >= 0");
        if (!(std::isfinite(o.zfar) && o.zfar > o.znear))
            return diag.error(oobj + ".zfar", "must be a finite number > znear (" +
                                                  std::to_string(o.znear) + "), got " +
                                                  std::to_string(o.zfar));
        c.projection = Projection::makeOrtho(-o.xmag, o.xmag, -o.ymag, o.ymag, o.znear, o.zfar);
    } else if (!replaced) {
        return diag.error(obj + ".type", "\"" + src.type + "\" is not perspective or orthographic");
    }

    if (ext) {
        if (ext->has("frustum") && ext->has("ortho"))
            return diag.error(ext->object(), "has both frustum and ortho (at most one is allowed)");
        for (const char* kind : {"frustum", "ortho"}) {
            if (!ext->has(kind)) continue;
            auto box = ext->child(kind);
            if (!box) return diag.error(ext->object() + "." + kind, "must be an object");
            box->warnUnknown({"left", "right", "bottom", "top", "near", "far"});
            double v[6];
            const char* names[6] = {"left", "right", "bottom", "top", "near", "far"};
            for (int i = 0; i < 6; ++i) {
                // Only a frustum's far plane may be left out: it is then at infinity.
                const bool optional = i == 5 && std::string(kind) == "frustum";
                if (!box->has(names[i]) && !optional)
                    return diag.error(box->object() + "." + names[i], "is missing");
                v[i] = box->number(names[i], kInfinity);
            }
            LANTERN_TRY(box->status());
            c.projection = std::string(kind) == "frustum"
                               ? Projection::makeFrustum(v[0], v[1], v[2], v[3], v[4], v[5])
                               : Projection::makeOrtho(v[0], v[1], v[2], v[3], v[4], v[5]);
            if (auto ok = checkProjection(c.projection, box->object()); !ok)
                return inFile(std::move(ok).error(), diag);
        }
        if (ext->has("lookAt")) {
            auto look = ext->child("lookAt");
            if (!look) return diag.error(ext->object() + ".lookAt", "must be an object");
            look->warnUnknown({"eye", "target", "up"});
            LookAt la;
            for (auto [name, field] : {std::pair{"eye", &la.eye}, std::pair{"target", &la.target},
                                       std::pair{"up", &la.up}}) {
                if (!look->has(name)) return diag.error(look->object() + "." + name, "is missing");
                *field = look->vec3(name, {});
            }
            LANTERN_TRY(look->status());
            if (auto ok = checkLookAt(la, look->object()); !ok)
                return inFile(std::move(ok).error(), diag);
            c.lookAt = la;
        }
    }
    return c;
}

// --- Nodes and scenes ----------------------------------------------------------------------

Result<Node> convertNode(const tinygltf::Node& src, std::size_t index, const Diagnostics& diag) {
    const std::string obj = at("nodes", index);
    Node n;
    n.name = src.name;
    n.mesh = src.mesh;
    n.camera = src.camera;
    n.children = src.children;
    if (auto it = src.extensions.find("KHR_lights_punctual"); it != src.extensions.end())
        n.light = it->second.Get("light").GetNumberAsInt();
    if (src.skin >= 0) diag.warn(obj + ".skin", "skinning is not supported; ignored");
    for (auto [name, values] :
         {std::pair{"matrix", &src.matrix}, std::pair{"translation", &src.translation},
          std::pair{"rotation", &src.rotation}, std::pair{"scale", &src.scale}})
        if (!allFinite(*values))
            return diag.error(obj + "." + name, "contains a non-finite number");
    if (!src.matrix.empty()) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                m[c][r] = src.matrix[std::size_t(c * 4 + r)];
        if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
            return diag.error(obj + ".matrix", "last row must be 0, 0, 0, 1 (a projective "
                                               "matrix is not a node transform)");
        n.matrix = m;
        return n;
    }
    if (!src.translation.empty()) n.translation = vec3(src.translation);
    if (!src.scale.empty()) n.scale = vec3(src.scale);
    if (!src.rotation.empty()) {
        const glm::dquat q(src.rotation[3], src.rotation[0], src.rotation[1], src.rotation[2]);
        const double len = glm::length(q);
        if (!(len > 0.0)) return diag.error(obj + ".rotation", "quaternion has zero length");
        if (std::abs(len - 1.0) > 1e-3)
            diag.warn(obj + ".rotation",
                      "quaternion length " + std::to_string(len) + " is not 1; normalised");
        n.rotation = q / len;
    }
    return n;
}

Result<std::optional<LightingModel>> convertLighting(const tinygltf::Scene& src, std::size_t index,
                                                     const Diagnostics& diag) {
    const tinygltf::Value* e = extension(src.extensions, "LANTERN_lighting");
    if (!e) return std::optional<LightingModel>{};
    ExtensionReader r(*e, at("scenes", index) + ".extensions.LANTERN_lighting", diag);
    r.warnUnknown({"globalAmbient", "localViewer", "twoSided", "shading", "specular"});
    LightingModel model;
    model.globalAmbient = r.vec3("globalAmbient", model.globalAmbient);
    model.localViewer = r.boolean("localViewer", model.localViewer);
    model.twoSided = r.boolean("twoSided", model.twoSided);
    const std::string shading = r.string("shading", "phong");
    const std::string specular = r.string("specular", "blinn");
    LANTERN_TRY(r.status());
    const auto mode = parseShadingMode(shading);
    if (!mode)
        return diag.error(r.object() + ".shading",
                          "\"" + shading + "\" is not flat, gouraud or phong");
    model.shading = *mode;
    const auto spec = parseSpecularModel(specular);
    if (!spec)
        return diag.error(r.object() + ".specular", "\"" + specular + "\" is not blinn or phong");
    model.specular = *spec;
    return std::optional<LightingModel>(model);
}

// --- Animations -----------------------------------------------------------------------------

Result<AnimationSampler> convertSampler(const tinygltf::Model& model,
                                        const tinygltf::AnimationSampler& src, AnimationPath path,
                                        const std::string& obj, const Diagnostics& diag) {
    AnimationSampler s;
    s.interpolation = src.interpolation == "STEP"          ? Interpolation::Step
                      : src.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                           : Interpolation::Linear;
    auto times = readDoubles(model, src.input, obj + ".input", diag);
    if (!times) return std::move(times).error();
    for (std::size_t k = 0; k < times->size(); ++k) {
        const double t = (*times)[k];
        if (t < 0.0)
            return diag.error(obj + ".input", "key time " + std::to_string(k) + " (" +
                                                  std::to_string(t) + ") is negative");
        if (k > 0 && !(t > (*times)[k - 1]))
            return diag.error(obj + ".input", "key times are not strictly increasing at key " +
                                                  std::to_string(k) + " (" + std::to_string(t) +
                                                  " after " + std::to_string((*times)[k - 1]) +
                                                  ")");
    }
    s.times = std::move(*times);
    auto values = readDoubles(model, src.output, obj + ".output", diag);
    if (!values) return std::move(values).error();
    const std::size_t n = path == AnimationPath::Rotation ? 4 : 3;
    s.values.resize(values->size() / n);
    for (std::size_t i = 0; i < s.values.size(); ++i)
        s.values[i] = glm::dvec4((*values)[i * n], (*values)[i * n + 1], (*values)[i * n + 2],
                                 n == 4 ? (*values)[i * n + 3] : 0.0);
    return s;
}

Result<Animation> convertAnimation(const tinygltf::Model& model, std::size_t index,
                                   const Diagnostics& diag) {
    const tinygltf::Animation& src = model.animations[index];
    const std::string obj = at("animations", index);
    Animation a;
    a.name = src.name;
    // Samplers are converted for the channels Lantern plays, once per (sampler, path): a
    // sampler's output is read as vec3 or quaternion depending on the path it drives.
    std::map<std::pair<int, AnimationPath>, int> converted;
    for (std::size_t c = 0; c < src.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = src.channels[c];
        const std::string cobj = obj + "." + at("channels", c);
        if (ch.target_node < 0) continue; // glTF: a channel without a node is ignored
        AnimationPath path;
        if (ch.target_path == "translation")
            path = AnimationPath::Translation;
        else if (ch.target_path == "rotation")
            path = AnimationPath::Rotation;
        else if (ch.target_path == "scale")
            path = AnimationPath::Scale;
        else {
            diag.warn(cobj, "morph-target weights are not animated (not supported); channel "
                            "skipped");
            continue;
        }
        if (!model.nodes[std::size_t(ch.target_node)].matrix.empty())
            return diag.error(cobj + ".target.node",
                              "node " + std::to_string(ch.target_node) +
                                  " has a matrix; only translation/rotation/scale nodes can be "
                                  "animated");
        const auto key = std::pair{ch.sampler, path};
        auto found = converted.find(key);
        if (found == converted.end()) {
            auto s = convertSampler(model, src.samplers[std::size_t(ch.sampler)], path,
                                    obj + "." + at("samplers", std::size_t(ch.sampler)), diag);
            if (!s) return std::move(s).error();
            a.samplers.push_back(std::move(*s));
            found = converted.emplace(key, int(a.samplers.size()) - 1).first;
        }
        a.channels.push_back({ch.target_node, path, found->second});
    }
    return a;
}

} // namespace

// --- ExtensionReader ------------------------------------------------------------------------

void ExtensionReader::fail(const std::string& key, const std::string& message) const {
    if (!*m_error) *m_error = m_diag.error(path(key), message);
}

Result<void> ExtensionReader::status() const {
    if (*m_error) return **m_error;
    return {};
}

double ExtensionReader::number(const std::string& key, double fallback) const {
    if (!m_value.Has(key)) return fallback;
    const tinygltf::Value& v = m_value.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) {
        fail(key, "must be a finite number");
        return fallback;
    }
    return v.GetNumberAsDouble();
}

std::optional<std::vector<double>> ExtensionReader::numbers(const std::string& key, std::size_t n,
                                                            std::size_t alsoN) const {
    if (!m_value.Has(key)) return std::nullopt;
    const tinygltf::Value& v = m_value.Get(key);
    const std::size_t len = v.IsArray() ? v.ArrayLen() : 0;
    if (!v.IsArray() || !(len == n || (alsoN != 0 && len == alsoN))) {
        fail(key, "must be an array of " + std::to_string(n) +
                      (alsoN ? " (or " + std::to_string(alsoN) + ")" : std::string()) + " numbers");
        return std::nullopt;
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < len; ++i) {
        const tinygltf::Value& e = v.Get(int(i));
        if (!e.IsNumber() || !std::isfinite(e.GetNumberAsDouble())) {
            fail(key, "element " + std::to_string(i) + " is not a finite number");
            return std::nullopt;
        }
        out.push_back(e.GetNumberAsDouble());
    }
    return out;
}

glm::dvec3 ExtensionReader::vec3(const std::string& key, const glm::dvec3& fallback) const {
    const auto v = numbers(key, 3, 0);
    return v ? glm::dvec3((*v)[0], (*v)[1], (*v)[2]) : fallback;
}

glm::dvec4 ExtensionReader::rgba(const std::string& key, const glm::dvec4& fallback) const {
    const auto v = numbers(key, 4, 3);
    return v ? glm::dvec4((*v)[0], (*v)[1], (*v)[2], v->size() > 3 ? (*v)[3] : 1.0) : fallback;
}

bool ExtensionReader::boolean(const std::string& key, bool fallback) const {
    if (!m_value.Has(key)) return fallback;
    const tinygltf::Value& v = m_value.Get(key);
    if (!v.IsBool()) {
        fail(key, "must be true or false");
        return fallback;
    }
    return v.Get<bool>();
}

std::string ExtensionReader::string(const std::string& key, const std::string& fallback) const {
    if (!m_value.Has(key)) return fallback;
    const tinygltf::Value& v = m_value.Get(key);
    if (!v.IsString()) {
        fail(key, "must be a string");
        return fallback;
    }
    return v.Get<std::string>();
}

std::optional<ExtensionReader> ExtensionReader::child(const std::string& key) const {
    if (!m_value.Has(key) || !m_value.Get(key).IsObject()) return std::nullopt;
    ExtensionReader c(m_value.Get(key), path(key), m_diag);
    c.m_error = m_error;
    return c;
}

void ExtensionReader::warnUnknown(std::initializer_list<const char*> known) const {
    for (const std::string& k : m_value.Keys())
        if (std::none_of(known.begin(), known.end(), [&](const char* n) { return k == n; }))
            m_diag.warn(path(k), "unknown member ignored");
}

// --- The whole model --------------------------------------------------------------------------

Result<Scene> convertModel(const tinygltf::Model& model, const RawFacts& raw,
                           const ImageStore& images, const LoadOptions& options,
                           const Diagnostics& diag) {
    Scene scene;
    scene.sourcePath = diag.file();
    if (!model.skins.empty())
        diag.warn("skins", std::to_string(model.skins.size()) +
                               " skin(s) ignored: skinning is not supported");

    TextureTable textures(model, images, raw, options, diag, scene.textures);
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        auto m = convertMaterial(model, i, textures, diag);
        if (!m) return inFile(std::move(m).error(), diag);
        scene.materials.push_back(std::move(*m));
    }
    for (std::size_t i = 0; i < model.meshes.size(); ++i) {
        auto m = convertMesh(model, i, diag);
        if (!m) return std::move(m).error();
        scene.meshes.push_back(std::move(*m));
    }
    for (std::size_t i = 0; i < model.lights.size(); ++i) {
        auto l = convertLight(model.lights[i], i, diag);
        if (!l) return inFile(std::move(l).error(), diag);
        scene.lights.push_back(std::move(*l));
    }
    for (std::size_t i = 0; i < model.cameras.size(); ++i) {
        const bool hasZfar = i < raw.perspectiveHasZfar.size() && raw.perspectiveHasZfar[i];
        auto c = convertCamera(model.cameras[i], i, hasZfar, diag);
        if (!c) return inFile(std::move(c).error(), diag);
        scene.cameras.push_back(std::move(*c));
    }
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        auto n = convertNode(model.nodes[i], i, diag);
        if (!n) return std::move(n).error();
        scene.nodes.push_back(std::move(*n));
    }
    for (std::size_t i = 0; i < model.scenes.size(); ++i) {
        SceneRoot root;
        root.name = model.scenes[i].name;
        root.nodes = model.scenes[i].nodes;
        auto lighting = convertLighting(model.scenes[i], i, diag);
        if (!lighting) return inFile(std::move(lighting).error(), diag);
        root.lighting = *lighting;
        scene.roots.push_back(std::move(root));
    }
    if (scene.roots.empty() && !scene.nodes.empty()) {
        // glTF lets a file have nodes but no scene; draw every node that has no parent.
        std::vector<bool> isChild(scene.nodes.size(), false);
        for (const Node& n : scene.nodes)
            for (int c : n.children)
                isChild[std::size_t(c)] = true;
        SceneRoot root;
        root.name = "all root nodes";
        for (std::size_t i = 0; i < scene.nodes.size(); ++i)
            if (!isChild[i]) root.nodes.push_back(int(i));
        diag.warn("scenes", "the file defines no scene; drawing all " +
                                std::to_string(root.nodes.size()) + " root nodes");
        scene.roots.push_back(std::move(root));
    }
    scene.defaultRoot = model.defaultScene >= 0 ? model.defaultScene : 0;
    for (std::size_t i = 0; i < model.animations.size(); ++i) {
        auto a = convertAnimation(model, i, diag);
        if (!a) return std::move(a).error();
        scene.animations.push_back(std::move(*a));
    }
    return scene;
}

} // namespace lantern::gltf
