// glTF materials -> Lantern's: LANTERN_materials_phong, the PBR fallback mapping,
// KHR_materials_unlit, alpha modes, and the base-colour textures they use, decoded to RGBA8.
#include "io/gltf/GltfInternal.h"
#include "io/image/TextureDecode.h"
#include "scene/Fidelity.h"

#include <algorithm>
#include <cmath>

namespace lantern::gltf {
namespace {

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

TextureWrap wrapOf(int glWrap) {
    return glWrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE       ? TextureWrap::ClampToEdge
           : glWrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? TextureWrap::MirroredRepeat
                                                              : TextureWrap::Repeat;
}

/// Decodes base-colour textures on first use and maps (glTF texture) -> Scene::textures.
class TextureTable {
public:
    TextureTable(const tinygltf::Model& model, const ImageStore& images, const RawFacts& raw,
                 const LoadOptions& options, const Diagnostics& diag, std::vector<Texture>& out)
        : m_model(model), m_images(images), m_raw(raw), m_options(options), m_diag(diag),
          m_out(out) {}

    /// The Scene::textures index for glTF texture `index` read as sRGB colour or as linear
    /// data (a texture used both ways is kept twice), -1 when it has no image we read.
    Result<int> get(int index, const std::string& usedBy, bool srgb = true) {
        const auto key = std::pair{index, srgb};
        if (auto it = m_done.find(key); it != m_done.end()) return it->second;
        const tinygltf::Texture& t = m_model.textures[std::size_t(index)];
        // EXT_texture_webp's image when there is one (`source` is then its fallback).
        const int webp = extensionSource(t, "EXT_texture_webp");
        const int source = webp != -1 ? webp : t.source;
        if (source < 0) {
            m_diag.warn(at("textures", std::size_t(index)),
                        extensionSource(t, "KHR_texture_basisu") != -1
                            ? "has only a KHR_texture_basisu (KTX2) image, which Lantern cannot "
                              "decode, and no PNG or JPEG fallback; " + usedBy +
                                  " is drawn without it"
                            : "no source image (an extension's image format?); " + usedBy +
                                  " is drawn without it");
            return m_done[key] = -1;
        }
        auto decoded = decode(source);
        if (!decoded) return std::move(decoded).error();
        Texture tex = std::move(*decoded);
        tex.srgb = srgb;
        if (t.sampler >= 0) {
            const tinygltf::Sampler& s = m_model.samplers[std::size_t(t.sampler)];
            tex.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
            tex.wrapS = wrapOf(s.wrapS);
            tex.wrapT = wrapOf(s.wrapT);
        }
        m_out.push_back(std::move(tex));
        return m_done[key] = int(m_out.size()) - 1;
    }

    /// The mean metallic (blue) and roughness (green) of a metallicRoughnessTexture, or
    /// nothing when the texture has no image Lantern reads. The texture is decoded once, as
    /// the linear data phong shading reads per texel (get(index, usedBy, false)).
    Result<std::optional<glm::dvec2>> meanMetallicRoughness(int index, const std::string& usedBy) {
        auto t = get(index, usedBy, false);
        if (!t) return std::move(t).error();
        if (*t < 0) return std::optional<glm::dvec2>{};
        const std::vector<std::uint8_t>& rgba = m_out[std::size_t(*t)].rgba8;
        double metallic = 0.0, roughness = 0.0;
        const std::size_t pixels = rgba.size() / 4;
        for (std::size_t i = 0; i < pixels; ++i) {
            roughness += rgba[i * 4 + 1];
            metallic += rgba[i * 4 + 2];
        }
        const double scale = 1.0 / (255.0 * double(std::max<std::size_t>(pixels, 1)));
        return std::optional<glm::dvec2>(glm::dvec2(metallic * scale, roughness * scale));
    }

    /// The mean colour of a texture (linear; sRGB colour decoded first), or nothing when it
    /// has no image Lantern reads: what a map that cannot be applied leaves in its factor.
    Result<std::optional<glm::dvec4>> meanColour(int index, const std::string& usedBy, bool srgb) {
        auto t = get(index, usedBy, srgb);
        if (!t) return std::move(t).error();
        if (*t < 0) return std::optional<glm::dvec4>{};
        const std::vector<std::uint8_t>& rgba = m_out[std::size_t(*t)].rgba8;
        const std::size_t pixels = std::max<std::size_t>(rgba.size() / 4, 1);
        glm::dvec4 sum(0.0);
        for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
            for (int c = 0; c < 4; ++c) {
                const double v = rgba[i + std::size_t(c)] / 255.0;
                sum[c] += srgb && c < 3 ? (v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4)) : v;
            }
        return std::optional<glm::dvec4>(sum / double(pixels));
    }

    const Diagnostics& diagnostics() const { return m_diag; }

    /// Maps on the material's second TEXCOORD set, and maps drawn with their texture's mean
    /// because they read a third (the fidelity report's texcoord-sets).
    std::vector<std::string> secondSetMaps, meanMaps;

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
        auto decoded = io::decodeTexture(bytes, size, obj, m_options.maxBytes, m_diag);
        if (!decoded) return decoded;
        Texture t = std::move(*decoded);
        t.name = !image.name.empty() ? image.name : image.uri.size() < 200 ? image.uri : obj;
        return t;
    }

    const tinygltf::Model& m_model;
    const ImageStore& m_images;
    const RawFacts& m_raw;
    const LoadOptions& m_options;
    const Diagnostics& m_diag;
    std::vector<Texture>& m_out;
    std::map<std::pair<int, bool>, int> m_done;
};

// The factors and the alpha cutoff are numbers in range.
Result<void> checkMaterialFactors(const tinygltf::Material& src, const std::string& obj,
                                  const Diagnostics& diag) {
    const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
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
    return {};
}

// KHR_texture_transform on a texture reference (identity without it); `texCoord` in it is
// read by texCoordOf.
Result<glm::dmat3> uvTransformOf(const tinygltf::TextureInfo& info, const std::string& obj,
                                 const Diagnostics& diag) {
    const tinygltf::Value* e = extension(info.extensions, "KHR_texture_transform");
    if (!e) return glm::dmat3(1.0);
    ExtensionReader r(*e, obj + ".extensions.KHR_texture_transform", diag);
    r.warnUnknown({"offset", "rotation", "scale", "texCoord"});
    const glm::dvec2 offset = r.vec2("offset", glm::dvec2(0.0));
    const double rotation = r.number("rotation", 0.0);
    const glm::dvec2 scale = r.vec2("scale", glm::dvec2(1.0));
    if (r.has("texCoord") && !(e->Get("texCoord").IsInt() && e->Get("texCoord").GetNumberAsInt() >= 0))
        r.fail("texCoord", "must be an integer >= 0");
    // Finite is checked by the reader; so large a value would overflow in the matrix.
    if (std::max(std::abs(offset.x), std::abs(offset.y)) > 1e30) r.fail("offset", "magnitude above 1e30");
    if (std::abs(rotation) > 1e30) r.fail("rotation", "magnitude above 1e30");
    if (std::max(std::abs(scale.x), std::abs(scale.y)) > 1e30) r.fail("scale", "magnitude above 1e30");
    LANTERN_TRY(r.status());
    return textureTransform(offset, rotation, scale);
}

// KHR_materials_emissive_strength's factor (1 without the extension).
Result<double> emissiveStrengthOf(const tinygltf::Material& src, const std::string& obj,
                                  const Diagnostics& diag) {
    double emissiveStrength = 1.0;
    if (const tinygltf::Value* e = extension(src.extensions, "KHR_materials_emissive_strength")) {
        ExtensionReader r(*e, obj + ".extensions.KHR_materials_emissive_strength", diag);
        emissiveStrength = r.number("emissiveStrength", 1.0);
        if (emissiveStrength < 0.0) r.fail("emissiveStrength", "must be >= 0");
        LANTERN_TRY(r.status());
    }
    return emissiveStrength;
}

// A glTF texture reference of any kind (normal and occlusion textures have their own types).
tinygltf::TextureInfo infoOf(int index, int texCoord, const tinygltf::ExtensionMap& extensions) {
    tinygltf::TextureInfo info;
    info.index = index;
    info.texCoord = texCoord;
    info.extensions = extensions;
    return info;
}

// The metallic-roughness, normal, occlusion and emissive maps (phong shading; gouraud and
// flat apply the emissive map and the factors). A map reads the material's set
// (materialTexcoordSet) or its second (materialSecondTexcoordSet, TextureMap::secondSet); one
// that reads a third is left out with a warning: a primitive keeps two sets.
Result<void> readMaps(const tinygltf::Material& src, const std::string& obj,
                      TextureTable& textures, const Diagnostics& diag, Material& m) {
    const int set = materialTexcoordSet(src), second = materialSecondTexcoordSet(src);
    auto meanInstead = [&](const tinygltf::TextureInfo& info, const std::string& name,
                           const std::string& where, bool srgb) -> Result<void> {
        auto mean = textures.meanColour(info.index, where, srgb);
        if (!mean) return std::move(mean).error();
        if (!*mean) return {};
        textures.meanMaps.push_back(where);
        if (name == "emissiveTexture") m.front.emission *= glm::dvec3(**mean);
        if (name == "occlusionTexture")
            m.front.ambient *= 1.0 + src.occlusionTexture.strength * ((**mean).r - 1.0);
        return {};  // metallic-roughness: the classic colours are the means' already; normal: none
    };
    auto read = [&](const tinygltf::TextureInfo& info, const std::string& name, bool srgb,
                    TextureMap& out) -> Result<void> {
        if (info.index < 0) return {};
        const std::string where = obj + "." + name;
        const int own = texCoordOf(info);
        if (own != set && own != second) {
            // Left out, its texture's mean stays in the factor it scales: a map dropped with
            // a factor of 1 would draw white where the map darkens.
            diag.warn(where, "reads TEXCOORD_" + std::to_string(own) +
                                 ", a third set beside the material's TEXCOORD_" +
                                 std::to_string(set) + " and TEXCOORD_" + std::to_string(second) +
                                 " (a primitive keeps two); drawn with its texture's mean");
            return meanInstead(info, name, where, srgb);
        }
        auto t = textures.get(info.index, where, srgb);
        if (!t) return std::move(t).error();
        auto uv = uvTransformOf(info, where, diag);
        if (!uv) return std::move(uv).error();
        out = TextureMap{*t, *uv, own != set};
        if (own != set) textures.secondSetMaps.push_back(where);
        return {};
    };
    const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
    if (m.pbr)
        LANTERN_TRY(read(pbr.metallicRoughnessTexture, "pbrMetallicRoughness.metallicRoughnessTexture",
                         false, m.metallicRoughnessMap));
    const auto& n = src.normalTexture;
    LANTERN_TRY(read(infoOf(n.index, n.texCoord, n.extensions), "normalTexture", false, m.normalMap));
    if (!std::isfinite(n.scale)) return diag.error(obj + ".normalTexture.scale", "must be finite");
    m.normalScale = n.scale;
    const auto& o = src.occlusionTexture;
    LANTERN_TRY(read(infoOf(o.index, o.texCoord, o.extensions), "occlusionTexture", false, m.occlusionMap));
    if (!(o.strength >= 0.0 && o.strength <= 1.0))
        return diag.error(obj + ".occlusionTexture.strength", "must be in [0, 1]");
    m.occlusionStrength = o.strength;
    return read(src.emissiveTexture, "emissiveTexture", true, m.emissiveMap);
}

// LANTERN_materials_phong: the front side and, when given, the back side.
Result<void> readPhongMaterial(const tinygltf::Value& e, const std::string& obj,
                               const Diagnostics& diag, Material& m) {
    ExtensionReader r(e, obj + ".extensions.LANTERN_materials_phong", diag);
    m.front = readPhongSide(r);
    if (auto back = r.child("back"))
        m.back = readPhongSide(*back);
    else if (r.has("back"))
        r.fail("back", "must be an object");
    return r.status();
}

// KHR_materials_unlit: the colour is the base colour; lighting terms are unused.
void makeUnlit(const glm::dvec4& baseColor, Material& m) {
    m.front.diffuse = baseColor;
    m.front.ambient = glm::dvec3(baseColor);
    m.front.specular = glm::dvec3(0.0);
    m.front.emission = glm::dvec3(0.0);
    m.ambientFollowsDiffuse = true;
}

// The PBR fallback (docs/scene-format-support.md, "Materials"): metallic-roughness into the
// classic equation. With f0 = mix(0.04, base, m) and w = r^2 (the share of a metal's
// reflection spread so wide that it reads as diffuse): diffuse = base(1-m) + f0 w m;
// shininess = clamp(2/r^4 - 2, 1, 1e4) (Blinn-Phong's equivalent of the microfacet width, at
// least 1 so the lobe always falls off); specular = f0 (1 - w m) (s+8)/8, the lobe normalised
// so that a rougher surface has a wider and dimmer highlight. A metallicRoughnessTexture
// scales the factors; the Phong material is uniform, so it takes the texture's mean.
Result<void> mapPbr(const tinygltf::Material& src, const std::string& obj,
                    const glm::dvec4& baseColor, double emissiveStrength, TextureTable& textures,
                    Material& m) {
    const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
    double metallic = pbr.metallicFactor, roughness = pbr.roughnessFactor;
    if (pbr.metallicRoughnessTexture.index >= 0) {
        auto mean = textures.meanMetallicRoughness(pbr.metallicRoughnessTexture.index,
                                                   obj + ".pbrMetallicRoughness.metallicRoughnessTexture");
        if (!mean) return std::move(mean).error();
        if (*mean) {
            metallic *= (*mean)->x;
            roughness *= (*mean)->y;
        }
    }
    auto extensions = readPbrExtensions(src, obj, textures.diagnostics());
    if (!extensions) return std::move(extensions).error();
    const PhongFromPbr p =
        phongFromPbr(glm::dvec3(baseColor), metallic, roughness, extensions->dielectricF0);
    m.front.diffuse = glm::dvec4(p.diffuse, baseColor.a);
    m.front.specular = p.specular;
    m.front.shininess = p.shininess;
    m.front.ambient = p.diffuse;
    m.front.emission = vec3(src.emissiveFactor) * emissiveStrength;
    m.ambientFollowsDiffuse = true;
    const glm::dvec3& f0 = extensions->dielectricF0;
    m.pbr = PbrFactors{baseColor, pbr.metallicFactor, pbr.roughnessFactor, (f0.x + f0.y + f0.z) / 3.0};
    applyPbrExtensions(*extensions, metallic, m);
    return {};
}

Result<Material> convertMaterial(const tinygltf::Model& model, std::size_t index,
                                 TextureTable& textures, const Diagnostics& diag) {
    const tinygltf::Material& src = model.materials[index];
    const std::string obj = at("materials", index);
    const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
    Material m;
    m.name = src.name;
    LANTERN_TRY(checkMaterialFactors(src, obj, diag));
    m.alphaMode = src.alphaMode == "BLEND"  ? AlphaMode::Blend
                  : src.alphaMode == "MASK" ? AlphaMode::Mask
                                            : AlphaMode::Opaque;
    m.alphaCutoff = src.alphaCutoff;
    m.doubleSided = src.doubleSided;
    m.unlit = extension(src.extensions, "KHR_materials_unlit") != nullptr;
    auto emissiveStrength = emissiveStrengthOf(src, obj, diag);
    if (!emissiveStrength) return std::move(emissiveStrength).error();

    const glm::dvec4 baseColor = vec4(pbr.baseColorFactor);
    if (const tinygltf::Value* e = extension(src.extensions, "LANTERN_materials_phong"))
        LANTERN_TRY(readPhongMaterial(*e, obj, diag, m));
    else if (m.unlit)
        makeUnlit(baseColor, m);
    else
        LANTERN_TRY(mapPbr(src, obj, baseColor, *emissiveStrength, textures, m));
    if (!m.unlit) LANTERN_TRY(readMaps(src, obj, textures, diag, m));
    if (pbr.baseColorTexture.index >= 0) {
        auto t = textures.get(pbr.baseColorTexture.index, obj);
        if (!t) return std::move(t).error();
        m.baseColorTexture = *t;
        auto uv = uvTransformOf(pbr.baseColorTexture, obj + ".pbrMetallicRoughness.baseColorTexture", diag);
        if (!uv) return std::move(uv).error();
        m.baseColorUvTransform = *uv;
    }
    return m;
}

} // namespace

Result<void> convertMaterials(const tinygltf::Model& model, const RawFacts& raw,
                              const ImageStore& images, const LoadOptions& options,
                              const Diagnostics& diag, Scene& scene) {
    TextureTable textures(model, images, raw, options, diag, scene.textures);
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        auto m = convertMaterial(model, i, textures, diag);
        if (!m) return inFile(std::move(m).error(), diag);
        scene.materials.push_back(std::move(*m));
    }
    for (const std::string& where : textures.secondSetMaps)
        scene::noteFeature(scene, "texcoord-sets", where);
    for (const std::string& where : textures.meanMaps)
        scene::noteFeature(scene, "texcoord-sets", where, Fidelity::Approximated,
                           "map-mean-for-third-set");
    return {};
}

int materialTexcoordSet(const tinygltf::Material& m) {
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    if (pbr.baseColorTexture.index >= 0) return texCoordOf(pbr.baseColorTexture);
    if (pbr.metallicRoughnessTexture.index >= 0) return texCoordOf(pbr.metallicRoughnessTexture);
    for (const auto& [index, texCoord, extensions] :
         {std::tuple{m.normalTexture.index, m.normalTexture.texCoord, &m.normalTexture.extensions},
          std::tuple{m.occlusionTexture.index, m.occlusionTexture.texCoord, &m.occlusionTexture.extensions}})
        if (index >= 0) return texCoordOf(infoOf(index, texCoord, *extensions));
    return m.emissiveTexture.index >= 0 ? texCoordOf(m.emissiveTexture) : 0;
}

int materialSecondTexcoordSet(const tinygltf::Material& m) {
    const int first = materialTexcoordSet(m);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    for (const tinygltf::TextureInfo& info :
         {pbr.metallicRoughnessTexture, infoOf(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions),
          infoOf(m.occlusionTexture.index, m.occlusionTexture.texCoord, m.occlusionTexture.extensions),
          m.emissiveTexture})
        if (info.index >= 0 && texCoordOf(info) != first) return texCoordOf(info);
    return -1;
}

int texCoordOf(const tinygltf::TextureInfo& info) {
    if (const tinygltf::Value* e = extension(info.extensions, "KHR_texture_transform"))
        if (e->Has("texCoord") && e->Get("texCoord").IsInt() && e->Get("texCoord").GetNumberAsInt() >= 0)
            return e->Get("texCoord").GetNumberAsInt();
    return info.texCoord;
}

glm::dmat3 textureTransform(const glm::dvec2& offset, double rotation, const glm::dvec2& scale) {
    const double c = std::cos(rotation), s = std::sin(rotation);
    // Column-major: columns are (u', v', 1) images of the unit vectors and the origin.
    return glm::dmat3(c * scale.x, -s * scale.x, 0.0, s * scale.y, c * scale.y, 0.0, offset.x, offset.y, 1.0);
}

PhongFromPbr phongFromPbr(const glm::dvec3& base, double metallic, double roughness,
                          const glm::dvec3& dielectricF0) {
    const double w = roughness * roughness;
    const glm::dvec3 f0 = glm::mix(dielectricF0, base, metallic);
    PhongFromPbr p;
    p.diffuse = base * (1.0 - metallic) + f0 * (w * metallic);
    const double r4 = w * w;
    p.shininess = r4 > 0.0 ? std::clamp(2.0 / r4 - 2.0, kMinPbrShininess, kMaxPbrShininess) : kMaxPbrShininess;
    p.specular = f0 * ((1.0 - w * metallic) * (p.shininess + 8.0) / 8.0);
    return p;
}

} // namespace lantern::gltf
