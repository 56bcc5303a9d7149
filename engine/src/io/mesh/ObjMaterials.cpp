// The OBJ reader's materials (ObjInternal.h): MTL libraries read confined, MTL colours mapped
// straight onto the classic material (no PBR step: Ka ambient, Kd and d diffuse, Ks specular,
// Ke emission, Ns shininess; illum 0 unlit, 1 without specular), and the maps Lantern has a
// slot for decoded (map_Kd, map_Ke, norm and bump when it holds a normal map, map_d into the
// base colour's alpha); the others are named in a warning.
#include "io/FileAccess.h"
#include "io/image/TextureDecode.h"
#include "io/mesh/ObjInternal.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <sys/stat.h>

namespace lantern::mesh {
namespace {

/// An istream over bytes held elsewhere (no copy).
struct ByteBuf : std::streambuf {
    ByteBuf(std::vector<unsigned char>& b) {
        char* p = reinterpret_cast<char*>(b.data());
        setg(p, p, p + b.size());
    }
};

std::string shown(const std::string& name) { return "\"" + io::printable(name) + "\""; }

// The name's problem, if it may not be opened: absolute, a drive letter, a NUL, ".." (unless
// folders are allowed).
std::optional<std::string> nameProblem(const std::string& path, bool allowParent) {
    if (path.empty()) return "is empty";
    if (path.find('\0') != std::string::npos) return "contains a NUL character";
    if (path[0] == '/') return "is an absolute path; the files an OBJ names must lie in its folder";
    if (path.size() >= 2 && std::isalpha(static_cast<unsigned char>(path[0])) && path[1] == ':')
        return "is an absolute Windows path; the files an OBJ names must lie in its folder";
    for (std::size_t start = 0; !allowParent && start <= path.size();) {
        std::size_t end = path.find('/', start);
        if (end == std::string::npos) end = path.size();
        if (path.compare(start, end - start, "..") == 0)
            return "contains \"..\"; the files an OBJ names must lie in its folder (or one "
                   "given with --allow-folder)";
        start = end + 1;
    }
    return std::nullopt;
}

// One pass over an MTL library before tinyobjloader reads it: numbers it would carry as
// infinity or read as 0 ("nan", "inf") refused by line; the materials counted (for the
// budget); the names of those that state their illum (a material without one is lit).
Result<std::uint64_t> scanMtl(const std::vector<unsigned char>& bytes, const std::string& object,
                              const Diagnostics& diag, std::set<std::string>& illum) {
    TextCursor text(bytes.data(), bytes.size(), 0, '#');
    std::uint64_t materials = 0;
    std::string current;
    for (std::string_view key = text.next(); !key.empty(); key = text.next()) {
        const std::size_t line = text.line();
        std::string rest;
        for (std::string_view t = text.nextOnLine(); !t.empty(); t = text.nextOnLine()) {
            double x = 0.0;
            if (key != "newmtl" && parseNumber(t, x) && !std::isfinite(x))
                return diag.error(object, std::string(key) + " \"" + io::printable(t, 40) +
                                              "\" is not a finite number (line " + std::to_string(line) + ")");
            if (key == "newmtl" && rest.size() < 4096) rest += (rest.empty() ? "" : " ") + std::string(t);
        }
        if (key == "newmtl") {
            ++materials;
            current = rest;
        } else if (key == "illum") {
            illum.insert(current);
        }
        text.skipLine();
    }
    return materials;
}

/// A texture option block's -s and -o as a transform of Lantern's texture coordinates (v down):
/// MTL's u' = u s + o in its own (v up) coordinates.
glm::dmat3 uvTransformOf(const tinyobj::texture_option_t& t) {
    const double su = t.scale[0], sv = t.scale[1], ou = t.origin_offset[0], ov = t.origin_offset[1];
    return glm::dmat3(su, 0.0, 0.0, 0.0, sv, 0.0, ou, 1.0 - sv - ov, 1.0);
}

/// The textures an MTL library names, decoded once per (file, use).
class ObjTextures {
public:
    ObjTextures(const std::filesystem::path& folder, const LoadOptions& options,
                const Diagnostics& diag, std::vector<Texture>& out)
        : m_folder(folder), m_options(options), m_diag(diag), m_out(out) {}

    /// The texture index of `name` read as sRGB colour or linear data; -1 when the file is
    /// missing (a warning) or, with `normalMap`, holds a grey height map (a warning).
    Result<int> get(const std::string& name, const std::string& object, bool srgb,
                    bool normalMap = false) {
        const std::string key = name + (srgb ? "|srgb" : "|linear");
        if (auto it = m_done.find(key); it != m_done.end()) return it->second;
        int channels = 0;
        auto t = decode(name, object, &channels);
        if (!t) return std::move(t).error();
        if (!*t) return m_done[key] = -1;
        if (normalMap && channels <= 2) {
            m_diag.warn(object, shown(name) + " is a grey height (bump) map; Lantern reads "
                                "tangent-space normal maps only: not applied");
            return m_done[key] = -1;
        }
        (*t)->srgb = srgb;
        m_out.push_back(std::move(**t));
        return m_done[key] = int(m_out.size()) - 1;
    }

    /// map_Kd (or white) with map_d's alpha (its own alpha when it has one, else its luminance):
    /// -1 when map_d cannot be applied (missing, or a size unlike map_Kd's: a warning).
    Result<int> withAlpha(const std::string& colour, const std::string& alpha, const std::string& object) {
        const std::string key = colour + "|" + alpha + "|alpha";
        if (auto it = m_done.find(key); it != m_done.end()) return it->second;
        int channels = 0;
        auto a = decode(alpha, object + ".map_d", &channels);
        if (!a) return std::move(a).error();
        std::optional<Texture> base;
        if (!colour.empty()) {
            auto c = decode(colour, object + ".map_Kd", nullptr);
            if (!c) return std::move(c).error();
            base = std::move(*c);
        }
        if (!*a || (!colour.empty() && !base)) return m_done[key] = -1;
        if (base && (base->width != (*a)->width || base->height != (*a)->height)) {
            m_diag.warn(object + ".map_d", "is " + std::to_string((*a)->width) + "x" +
                                               std::to_string((*a)->height) + ", map_Kd " +
                                               std::to_string(base->width) + "x" + std::to_string(base->height) +
                                               ": not applied");
            return m_done[key] = -1;
        }
        Texture t = base ? std::move(*base) : Texture{};
        if (!base) t = whiteLike(**a);
        const std::vector<std::uint8_t>& src = (*a)->rgba8;
        for (std::size_t i = 0; i + 3 < src.size(); i += 4)
            t.rgba8[i + 3] = channels == 2 || channels == 4
                                 ? src[i + 3]
                                 : std::uint8_t(0.2126 * src[i] + 0.7152 * src[i + 1] + 0.0722 * src[i + 2] + 0.5);
        m_out.push_back(std::move(t));
        return m_done[key] = int(m_out.size()) - 1;
    }

private:
    Texture whiteLike(const Texture& a) {
        Texture t;
        t.name = a.name;
        t.width = a.width;
        t.height = a.height;
        t.rgba8.assign(a.rgba8.size(), 255);
        return t;
    }

    Result<std::optional<Texture>> decode(const std::string& name, const std::string& object,
                                          int* channels) {
        auto bytes = readNamedFile(name, object, m_folder, m_options, m_diag);
        if (!bytes) return std::move(bytes).error();
        if (!*bytes) {
            m_diag.warn(object, shown(name) + " does not exist in the OBJ's folder: drawn without it");
            return std::optional<Texture>();
        }
        auto t = io::decodeTexture((*bytes)->data(), (*bytes)->size(), object + " " + shown(name),
                                   m_options.maxBytes, m_diag, channels);
        if (!t) return std::move(t).error();
        t->name = name.substr(0, 200);
        return std::optional<Texture>(std::move(*t));
    }

    const std::filesystem::path& m_folder;
    const LoadOptions& m_options;
    const Diagnostics& m_diag;
    std::vector<Texture>& m_out;
    std::map<std::string, int> m_done;
};

glm::dvec3 rgb(const tinyobj::real_t* c) { return glm::dvec3(c[0], c[1], c[2]); }

// The colours, straight from the MTL: no PBR step. `illum` says whether the material states its
// illumination model; without it the material is lit in full (illum 2).
Result<Material> classicOf(const tinyobj::material_t& m, bool illum, const std::string& object,
                           const Diagnostics& diag) {
    Material out;
    out.name = m.name;
    for (const auto& [key, c] : {std::pair{"Ka", m.ambient}, std::pair{"Kd", m.diffuse},
                                 std::pair{"Ks", m.specular}, std::pair{"Ke", m.emission}})
        if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
            return diag.error(object + "." + key, "is not finite");
    if (!std::isfinite(m.shininess) || !std::isfinite(m.dissolve))
        return diag.error(object, "Ns or d is not finite");
    double d = m.dissolve, ns = m.shininess;
    if (d < 0.0 || d > 1.0) {
        diag.warn(object + ".d", "is " + std::to_string(d) + ", outside 0-1: clamped");
        d = std::clamp(d, 0.0, 1.0);
    }
    if (ns < 0.0) {
        diag.warn(object + ".Ns", "is " + std::to_string(ns) + ", below 0: 0 is used");
        ns = 0.0;
    }
    out.front.ambient = rgb(m.ambient);
    out.front.diffuse = glm::dvec4(rgb(m.diffuse), d);
    const int model = illum ? m.illum : 2;
    out.front.specular = model == 1 ? glm::dvec3(0.0) : rgb(m.specular);
    out.front.emission = rgb(m.emission);
    out.front.shininess = ns;
    out.unlit = model == 0;  // "colour on, ambient off": the diffuse colour as it is
    if (d < 1.0) out.alphaMode = AlphaMode::Blend;
    return out;
}

// The maps Lantern has a slot for; the others named in one warning.
// Returns whether the material names maps that are not read.
Result<bool> readMaps(const tinyobj::material_t& m, const std::string& object,
                      ObjTextures& textures, Material& out, const Diagnostics& diag) {
    if (!m.alpha_texname.empty()) {
        auto t = textures.withAlpha(m.diffuse_texname, m.alpha_texname, object);
        if (!t) return std::move(t).error();
        out.baseColorTexture = *t;
        if (*t >= 0) out.alphaMode = AlphaMode::Blend;
    }
    if (!m.diffuse_texname.empty() && out.baseColorTexture < 0) {
        auto t = textures.get(m.diffuse_texname, object + ".map_Kd", true);
        if (!t) return std::move(t).error();
        out.baseColorTexture = *t;
    }
    out.baseColorUvTransform = uvTransformOf(m.diffuse_texopt);
    if (!m.emissive_texname.empty()) {
        auto t = textures.get(m.emissive_texname, object + ".map_Ke", true);
        if (!t) return std::move(t).error();
        out.emissiveMap = TextureMap{*t, uvTransformOf(m.emissive_texopt)};
    }
    const bool norm = !m.normal_texname.empty();
    const std::string& normal = norm ? m.normal_texname : m.bump_texname;
    if (!normal.empty()) {
        const auto& opt = norm ? m.normal_texopt : m.bump_texopt;
        auto t = textures.get(normal, object + (norm ? ".norm" : ".bump"), false, true);
        if (!t) return std::move(t).error();
        out.normalMap = TextureMap{*t, uvTransformOf(opt)};
        out.normalScale = std::isfinite(opt.bump_multiplier) ? opt.bump_multiplier : 1.0;
    }
    std::string skipped;
    for (const auto& [key, name] : {std::pair{"map_Ks", &m.specular_texname},
                                    std::pair{"map_Ka", &m.ambient_texname},
                                    std::pair{"map_Ns", &m.specular_highlight_texname},
                                    std::pair{"disp", &m.displacement_texname},
                                    std::pair{"refl", &m.reflection_texname},
                                    std::pair{"map_Pr", &m.roughness_texname},
                                    std::pair{"map_Pm", &m.metallic_texname},
                                    std::pair{"map_Ps", &m.sheen_texname}})
        if (!name->empty()) skipped += std::string(skipped.empty() ? "" : ", ") + key;
    if (!skipped.empty())
        diag.warn(object, skipped + " not read (Lantern's material has no slot for them: the "
                                    "colours alone are used)");
    return !skipped.empty();
}

} // namespace

Result<std::vector<Material>> convertObjMaterials(const std::vector<tinyobj::material_t>& mtl,
                                                  const std::set<std::string>& illum,
                                                  const std::filesystem::path& folder,
                                                  const LoadOptions& options,
                                                  const Diagnostics& diag,
                                                  std::vector<Texture>& textures,
                                                  std::vector<std::string>& skippedMaps) {
    LANTERN_TRY(diag.charge(mtl.size(), sizeof(Material), "materials", "the materials"));
    ObjTextures table(folder, options, diag, textures);
    std::vector<Material> out;
    out.reserve(mtl.size());
    for (const tinyobj::material_t& m : mtl) {
        const std::string object = "materials " + shown(m.name);
        auto material = classicOf(m, illum.count(m.name) > 0, object, diag);
        if (!material) return std::move(material).error();
        auto skipped = readMaps(m, object, table, *material, diag);
        if (!skipped) return std::move(skipped).error();
        if (*skipped) skippedMaps.push_back(object);
        out.push_back(std::move(*material));
    }
    return out;
}

Result<std::optional<std::vector<unsigned char>>> readNamedFile(
    const std::string& name, const std::string& object, const std::filesystem::path& folder,
    const LoadOptions& options, const Diagnostics& diag) {
    std::string path = name;
    std::replace(path.begin(), path.end(), '\\', '/');  // names written on Windows
    if (auto problem = nameProblem(path, !options.allowedFolders.empty()))
        return diag.error(object, shown(name) + " " + *problem);
    struct stat st {};
    if (::lstat((folder / path).c_str(), &st) != 0 && errno == ENOENT)
        return std::optional<std::vector<unsigned char>>();
    auto real = io::resolveConfined(folder, path, options.maxBytes, options.allowedFolders);
    if (!real) return diag.error(object, real.error().message);
    auto bytes = io::readConfinedFile(*real, std::min(options.maxBytes, diag.left()));
    if (!bytes) return diag.error(object, shown(name) + " " + bytes.error().message);
    LANTERN_TRY(diag.charge(bytes->size(), 1, object, "the file's bytes"));
    return std::optional<std::vector<unsigned char>>(std::move(*bytes));
}

bool ConfinedMtlReader::operator()(const std::string& name,
                                   std::vector<tinyobj::material_t>* materials,
                                   std::map<std::string, int>* names, std::string* warn,
                                   std::string* err) {
    if (m_failure) return false;
    const std::string object = "mtllib " + shown(name);
    auto bytes = readNamedFile(name, object, m_folder, m_options, m_diag);
    if (!bytes) {
        m_failure = std::move(bytes).error();
        return false;
    }
    if (!*bytes) {
        m_diag.warn(object, "does not exist in the OBJ's folder: its materials are drawn with the "
                            "default material");
        return false;
    }
    auto count = scanMtl(**bytes, object, m_diag, m_illum);
    auto charged = count ? m_diag.charge(*count, 2 * sizeof(tinyobj::material_t) + 64, object,
                                         std::to_string(*count) + " materials")
                         : Result<void>(count.error());
    if (!charged) {
        m_failure = std::move(charged).error();
        return false;
    }
    ByteBuf buf(**bytes);
    std::istream in(&buf);
    tinyobj::LoadMtl(names, materials, &in, warn, err);
    return true;
}

} // namespace lantern::mesh
