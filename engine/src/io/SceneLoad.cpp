// The one way a scene file comes in (io/SceneLoad.h): the format table, the choice of format,
// and the exception frame every loader runs in.
#include "io/SceneLoad.h"

#include "io/FileAccess.h"
#include "io/gltf/GltfLoad.h"
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

// The format whose files start like `head`, or null.
const SceneFormat* formatByContent(const std::string& head) {
    std::size_t i = 0;
    while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
    const std::string_view text = std::string_view(head).substr(i);
    const char* name = nullptr;
    if (head.rfind("glTF", 0) == 0 || text.rfind("{", 0) == 0) name = "glTF";
    for (const SceneFormat& f : sceneFormats())
        if (name && std::string_view(f.name) == name) return &f;
    return nullptr;
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
    };
    return formats;
}

Result<const SceneFormat*> sceneFormatOf(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    for (const SceneFormat& f : sceneFormats())
        if (std::find(f.extensions.begin(), f.extensions.end(), ext) != f.extensions.end())
            return &f;
    auto head = readFileStart(path, 64);
    if (!head) {
        Error e = std::move(head).error();
        e.message = "the scene file " + e.message;
        e.file = path.string();
        return e;
    }
    if (const SceneFormat* f = formatByContent(*head)) return f;
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
