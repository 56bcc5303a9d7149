// glTF 2.0 import: to be replaced by the full loader (issue 3).
#include <lantern/Io.h>

namespace lantern {

Result<Scene> loadGltf(const std::filesystem::path& path, const LoadOptions&) {
    return makeError(ErrorCode::Unsupported, "glTF loading is not built yet", {}, path.string());
}

} // namespace lantern
