// loadGltf: reads a .gltf/.glb within size bounds, runs the container checks, parses it with
// tinygltf through file-system callbacks confined to the scene's folder, then validates and
// converts it (GltfInternal.h lists the passes). Nothing escapes as an exception.
#include "io/GltfInternal.h"
#include "io/GltfLoad.h"

#include <cctype>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>

namespace lantern {
namespace gltf {
namespace {

/// What the file-system callbacks need: the only folder they may read from, the size bound,
/// and the first reason a read was refused (reported instead of tinygltf's "file not found").
struct FsContext {
    std::string folder; ///< absolute, without a trailing separator
    std::uint64_t maxBytes = 0;
    std::string refusal;
};

/// The relative part of `path` when it lies inside the folder, else nothing.
std::optional<std::string> insideFolder(const FsContext& ctx, const std::string& path) {
    const std::string prefix = ctx.folder + "/";
    if (path.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
    const std::string rest = path.substr(prefix.size());
    Diagnostics quiet("", {});
    if (!checkRelativeUri(rest, "", quiet)) return std::nullopt;
    return rest;
}

bool fileExists(const std::string& path, void* user) {
    auto& ctx = *static_cast<FsContext*>(user);
    // tinygltf also tries the working directory ("./uri"): never let it. (URIs that leave
    // the folder were refused with their object path before tinygltf ran.)
    const auto rest = insideFolder(ctx, path);
    return rest && resolveConfined(ctx.folder, *rest, ctx.maxBytes);
}

std::string expandFilePath(const std::string& path, void*) {
    return path;
}

// The scene file itself (named by the user: a symlink to it is followed; a folder, FIFO or
// device is refused without blocking).
Result<std::vector<unsigned char>> readSceneFile(const std::filesystem::path& path,
                                                 std::uint64_t maxBytes, const Diagnostics& diag) {
    auto bytes = readRegularFile(path, maxBytes, false);
    if (!bytes) {
        const Error& e = bytes.error();
        return diag.error(e.code, "", "the scene file " + e.message);
    }
    return bytes;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
    auto& ctx = *static_cast<FsContext*>(user);
    const auto rest = insideFolder(ctx, path);
    if (!rest) {
        *err = "outside the scene's folder";
        return false;
    }
    // Resolved to its real path inside the folder, then opened without following a link
    // there (a link swapped in meanwhile is refused) and checked to be a regular file.
    auto real = resolveConfined(ctx.folder, *rest, ctx.maxBytes);
    auto bytes = real ? readRegularFile(*real, ctx.maxBytes, true)
                      : Result<std::vector<unsigned char>>(std::move(real).error());
    if (!bytes) {
        *err = bytes.error().message;
        if (ctx.refusal.empty()) ctx.refusal = bytes.error().message;
        return false;
    }
    *out = std::move(*bytes);
    return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
    *err = "the loader never writes";
    return false;
}

/// Keeps the encoded bytes of URI images for later decoding; bufferView images are sliced
/// later from the validated buffer views (tinygltf hands this callback a pointer computed
/// from an unchecked offset, so it is not read here).
bool keepImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    auto& store = *static_cast<ImageStore*>(user);
    if (image->bufferView != -1) return true;
    if (bytes && size > 0) store.encoded[index].assign(bytes, bytes + size);
    return true;
}

/// tinygltf's multi-line message as one line, made printable and bounded (tinygltf quotes
/// URIs and data it failed on: a message never carries a file's raw bytes).
std::string oneLine(const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
            line.pop_back();
        if (line.empty()) continue;
        out += (out.empty() ? "" : "; ") + line;
    }
    return out.empty() ? "tinygltf refused the file without a reason" : printable(out, 240);
}

Result<Scene> loadBytes(std::vector<unsigned char> fileBytes, const std::filesystem::path& path,
                        const LoadOptions& options) {
    const Diagnostics diag(path.string(), options.log, options.maxBytes);
    std::vector<unsigned char>* bytes = &fileBytes;
    if (fileBytes.size() > options.maxBytes)
        return diag.error("", "\"" + path.filename().string() + "\" is " +
                                  std::to_string(fileBytes.size()) + " bytes, more than --max-size (" +
                                  std::to_string(options.maxBytes) + " bytes)");
    if (bytes->empty()) return diag.error("", "the file is empty");
    if (bytes->size() > std::numeric_limits<std::uint32_t>::max())
        return diag.error("", "files of 4 GiB or more cannot be read by tinygltf");

    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
    if (ec) return diag.error(ErrorCode::IoError, "", "cannot resolve the path: " + ec.message());
    Source source;
    source.folder = absolute.parent_path();
    source.maxBytes = options.maxBytes;

    std::string extension = path.extension().string();
    for (char& c : extension)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    std::string_view json;
    std::optional<GlbLayout> glb;
    if (isGlb(*bytes) || extension == ".glb") {
        auto layout = parseGlb(*bytes, diag);
        if (!layout) return std::move(layout).error();
        glb = *layout;
        source.glb = true;
        source.glbHasBin = glb->hasBin;
        json = std::string_view(reinterpret_cast<const char*>(bytes->data()) + glb->jsonOffset,
                                glb->jsonLength);
        // Unknown chunks after the ones tinygltf reads are dropped by shortening the length.
        const std::uint32_t length = std::uint32_t(glb->tinygltfLength);
        for (int i = 0; i < 4; ++i)
            (*bytes)[8 + std::size_t(i)] = (length >> (8 * i)) & 0xFF;
    } else {
        json = std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size());
    }
    LANTERN_TRY(checkJsonNesting(json, diag));
    auto raw = inspectJson(json, source, diag);
    if (!raw) return std::move(raw).error();

    FsContext fs;
    fs.folder = source.folder.string();
    fs.maxBytes = options.maxBytes;
    ImageStore images;

    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks(
        tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &fs});
    parser.SetImageLoader(&keepImage, &images);
    tinygltf::Model model;
    std::string err, warn;
    const bool parsed = glb ? parser.LoadBinaryFromMemory(&model, &err, &warn, bytes->data(),
                                                          unsigned(glb->tinygltfLength), fs.folder)
                            : parser.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                                         unsigned(json.size()), fs.folder);
    if (!parsed) {
        std::string message = oneLine(err);
        if (!fs.refusal.empty()) message += " (" + fs.refusal + ")";
        return diag.error("", "not a readable glTF file: " + message);
    }
    if (!warn.empty()) diag.warn("", "tinygltf: " + oneLine(warn));
    bytes->clear();
    bytes->shrink_to_fit();
    // The buffers tinygltf holds count against the load's budget (each was bounded alone).
    for (std::size_t i = 0; i < model.buffers.size(); ++i)
        LANTERN_TRY(diag.charge(model.buffers[i].data.size(), 1, at("buffers", i), "holding the data"));

    LANTERN_TRY(validateModel(model, *raw, options, diag));
    auto scene = convertModel(model, *raw, images, options, diag);
    if (!scene) return std::move(scene).error();
    if (auto valid = scene->validate(); !valid) {
        Error e = std::move(valid).error();
        e.file = diag.file();
        return e;
    }
    return scene;
}

Result<Scene> load(const std::filesystem::path& path, const LoadOptions& options) {
    const Diagnostics diag(path.string(), options.log);
    auto bytes = readSceneFile(path, options.maxBytes, diag);
    if (!bytes) return std::move(bytes).error();
    return loadBytes(std::move(*bytes), path, options);
}

} // namespace

Result<Scene> loadGltfBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                            const LoadOptions& options) {
    try {
        return loadBytes(std::move(bytes), path, options);
    } catch (const std::bad_alloc&) {
        return makeError(ErrorCode::OutOfMemory, "out of memory while loading", {}, path.string());
    } catch (const std::exception& e) {
        return makeError(ErrorCode::InvalidInput, std::string("cannot be loaded: ") + e.what(), {},
                         path.string());
    }
}

} // namespace gltf

Result<Scene> loadGltf(const std::filesystem::path& path, const LoadOptions& options) {
    // tinygltf and the standard library may throw (allocation failures, JSON type errors in
    // paths the checks do not reach); the API promises Result, never an exception.
    try {
        return gltf::load(path, options);
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

} // namespace lantern
