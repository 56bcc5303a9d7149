// SceneLoad.h: the one way a scene file comes into the engine. Every format (glTF in
// io/gltf/, the mesh formats in io/mesh/) fills the same scene model through a loader of the
// same shape, chosen here by the file's name (or, for a name that says nothing, its first
// bytes); "builtin:NAME" is a built-in scene. lantern::loadScene (api/Io.cpp) is this.
#pragma once

#include <lantern/FileOptions.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::io {

/// A scene format: its name, the file extensions it owns (lower case, with the dot), and its
/// loader. A loader reads only what the options allow, names the file, the object and the
/// problem in every error, and never throws (loadScene catches for it all the same).
struct SceneFormat {
    const char* name;
    std::vector<std::string> extensions;
    Result<Scene> (*load)(const std::filesystem::path& path, const LoadOptions& options);
};

/// The formats Lantern reads, in the order `lantern info --formats` lists them.
const std::vector<SceneFormat>& sceneFormats();

/// The format of `path`: by its extension, or when the extension is none of theirs, by the
/// first bytes of the file (a glTF's JSON or GLB magic, "ply", "OFF", an STL's "solid" or
/// binary layout). InvalidInput naming the file when no format claims it.
Result<const SceneFormat*> sceneFormatOf(const std::filesystem::path& path);

/// "builtin:NAME", or a file of any format above.
Result<Scene> loadScene(std::string_view pathOrBuiltin, const LoadOptions& options);

} // namespace lantern::io
