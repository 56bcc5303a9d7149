// The one way a scene file comes in (io/SceneLoad.h): the format table, the choice of format,
// and the exception frame every loader runs in.
#include "io/SceneLoad.h"

#include "io/FileAccess.h"
#include "io/gltf/GltfLoad.h"
#include "io/mesh/MeshLoad.h"
#include "scene/Fidelity.h"
#include "scene/Builtins.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <new>

namespace lantern::io {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// True when `text` starts with `word` followed by a space or a line end (or nothing).
bool startsWithWord(std::string_view text, std::string_view word) {
    return text.substr(0, word.size()) == word &&
           (text.size() == word.size() || std::isspace(static_cast<unsigned char>(text[word.size()])));
}

// The format whose files start like `head` (a file of `size` bytes), or null.
const SceneFormat* formatByContent(const std::string& head, std::uint64_t size) {
    std::size_t i = 0;
    while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
    const std::string_view text = std::string_view(head).substr(i);
    const auto* bytes = reinterpret_cast<const unsigned char*>(head.data());
    // [ST][C][N]OFF: the keyword of an OFF file, alone or before its counts.
    const std::size_t off = text.find("OFF");
    const bool offKeyword = off != std::string_view::npos && off <= 4 &&
                            text.substr(0, off).find_first_not_of("STCN") == std::string_view::npos &&
                            startsWithWord(text.substr(off), "OFF");
    const char* name = nullptr;
    if (head.rfind("glTF", 0) == 0 || text.rfind("{", 0) == 0) name = "glTF";
    else if (startsWithWord(head, "ply")) name = "PLY";
    else if (offKeyword) name = "OFF";
    // A binary STL is known by its size (its header may say "solid" too), an ASCII one by "solid".
    else if (mesh::looksLikeBinaryStl(bytes, head.size(), size) || startsWithWord(text, "solid")) name = "STL";
    for (const SceneFormat& f : sceneFormats())
        if (name && std::string_view(f.name) == name) return &f;
    return nullptr;
}

// --up z: a node above each root node turns the file's +Z into +Y (-90 degrees about X). One
// per root node, so that a node listed by several scenes still has one parent.
void turnZUp(Scene& scene) {
    // Exact, column by column: x stays, y goes to -z, z goes to +y.
    const glm::dmat4 turn(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1);
    std::vector<int> upOf(scene.nodes.size(), -1);
    for (SceneRoot& root : scene.roots)
        for (int& n : root.nodes) {
            if (n < 0 || std::size_t(n) >= upOf.size()) continue;
            if (upOf[std::size_t(n)] < 0) {
                Node up;
                up.name = "up: +Z to +Y";
                up.matrix = turn;
                up.children = {n};
                upOf[std::size_t(n)] = int(scene.nodes.size());
                scene.nodes.push_back(std::move(up));
            }
            n = upOf[std::size_t(n)];
        }
}

std::string extensionList() {
    std::string list;
    for (const SceneFormat& f : sceneFormats())
        for (const std::string& e : f.extensions) list += (list.empty() ? "" : ", ") + e;
    return list;
}

} // namespace

const std::vector<SceneFormat>& sceneFormats() {
    static const std::vector<SceneFormat> formats = {
        {"glTF", {".gltf", ".glb"}, &gltf::loadGltf},
        {"OBJ", {".obj"}, &mesh::load<&mesh::readObj>},
        {"PLY", {".ply"}, &mesh::load<&mesh::readPly>},
        {"STL", {".stl"}, &mesh::load<&mesh::readStl>},
        {"OFF", {".off"}, &mesh::load<&mesh::readOff>},
    };
    return formats;
}

Result<const SceneFormat*> sceneFormatOf(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    for (const SceneFormat& f : sceneFormats())
        if (std::find(f.extensions.begin(), f.extensions.end(), ext) != f.extensions.end())
            return &f;
    auto head = readFileStart(path, 96);
    if (!head) {
        Error e = std::move(head).error();
        e.message = "the scene file " + e.message;
        e.file = path.string();
        return e;
    }
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (const SceneFormat* f = formatByContent(*head, ec ? 0 : size)) return f;
    return makeError(ErrorCode::InvalidInput,
                     "not a scene file Lantern reads: its name ends in \"" + ext +
                         "\" and its first bytes are none of the formats' (" + extensionList() +
                         ")",
                     {}, path.string());
}

Result<Scene> loadScene(std::string_view pathOrBuiltin, const LoadOptions& options) {
    constexpr std::string_view prefix = "builtin:";
    if (pathOrBuiltin.substr(0, prefix.size()) == prefix)
        return scene::builtinScene(pathOrBuiltin.substr(prefix.size()));
    const std::filesystem::path path{std::string(pathOrBuiltin)};
    // Loaders (tinygltf, the mesh libraries and the standard library) may throw on paths the
    // checks do not reach; the API promises Result, never an exception.
    try {
        auto format = sceneFormatOf(path);
        if (!format) return std::move(format).error();
        auto scene = (*format)->load(path, options);
        if (scene && !options.variant.empty())
            LANTERN_TRY(selectMaterialVariant(*scene, options.variant));
        if (scene && options.up == UpAxis::Z) {
            turnZUp(*scene);
            scene::noteFeature(*scene, "up-axis", "--up z");
        }
        return scene;
    } catch (const std::bad_alloc&) {
        return makeError(ErrorCode::OutOfMemory, "out of memory while loading", {}, path.string());
    } catch (const std::exception& e) {
        return makeError(ErrorCode::InvalidInput, std::string("cannot be loaded: ") + e.what(), {},
                         path.string());
    } catch (...) {
        return makeError(ErrorCode::InvalidInput, "cannot be loaded (unknown failure)", {},
                         path.string());
    }
}

} // namespace lantern::io

namespace lantern {

const char* toString(UpAxis up) noexcept { return up == UpAxis::Z ? "z" : "y"; }

std::optional<UpAxis> parseUpAxis(std::string_view text) noexcept {
    if (text == "y" || text == "Y") return UpAxis::Y;
    if (text == "z" || text == "Z") return UpAxis::Z;
    return std::nullopt;
}

} // namespace lantern
