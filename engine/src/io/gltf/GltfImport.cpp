// loadGltf: reads a .gltf/.glb within size bounds, runs the container checks, parses it with
// tinygltf through file-system callbacks confined to the scene's folder, decodes compressed
// data, then validates and converts it (GltfInternal.h lists the passes). Nothing escapes as an
// exception.
#include "io/gltf/GltfInternal.h"
#include "io/gltf/GltfLoad.h"

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
    std::vector<std::filesystem::path> allowed;  ///< LoadOptions::allowedFolders
    std::uint64_t maxBytes = 0;
    std::string refusal;
};

/// The relative part of `path` when it lies inside the folder, else nothing.
std::optional<std::string> insideFolder(const FsContext& ctx, const std::string& path) {
    const std::string prefix = ctx.folder + "/";
    if (path.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
    const std::string rest = path.substr(prefix.size());
    Diagnostics quiet("", {});
    if (!checkRelativeUri(rest, "", quiet, !ctx.allowed.empty())) return std::nullopt;
    return rest;
}

bool fileExists(const std::string& path, void* user) {
    auto& ctx = *static_cast<FsContext*>(user);
    // tinygltf also tries the working directory ("./uri"): never let it. (URIs that leave
    // the folder were refused with their object path before tinygltf ran.)
    const auto rest = insideFolder(ctx, path);
    return rest && resolveConfined(ctx.folder, *rest, ctx.maxBytes, ctx.allowed);
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
    // Resolved to its real path inside the folder, then opened component by component
    // without following a link (one swapped in meanwhile is refused) and checked to be a
    // regular file.
    auto real = resolveConfined(ctx.folder, *rest, ctx.maxBytes, ctx.allowed);
    auto bytes = real ? readConfinedFile(*real, ctx.maxBytes)
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

/// The file as tinygltf will read it: its JSON, and for a GLB the container (header length cut
/// after the chunks tinygltf understands). Both point into `bytes`, or into `storage` when the
/// JSON had to be rewritten for tinygltf (meshopt placeholder buffers).
struct TinygltfInput {
    std::string_view json;
    std::optional<GlbLayout> glb;
    const unsigned char* glbData = nullptr;
    std::size_t glbLength = 0;
};

/// Runs tinygltf on the input with the confined file-system callbacks and the image store.
Result<tinygltf::Model> parseModel(const TinygltfInput& in, FsContext& fs, ImageStore& images,
                                   const Diagnostics& diag) {
    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks(
        tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &fs});
    parser.SetImageLoader(&keepImage, &images);
    tinygltf::Model model;
    std::string err, warn;
    const bool parsed =
        in.glb ? parser.LoadBinaryFromMemory(&model, &err, &warn, in.glbData,
                                             unsigned(in.glbLength), fs.folder)
               : parser.LoadASCIIFromString(&model, &err, &warn, in.json.data(),
                                            unsigned(in.json.size()), fs.folder);
    if (!parsed) {
        std::string message = oneLine(err);
        if (!fs.refusal.empty()) message += " (" + fs.refusal + ")";
        return diag.error("", "not a readable glTF file: " + message);
    }
    if (!warn.empty()) diag.warn("", "tinygltf: " + oneLine(warn));
    return model;
}

/// Locates the JSON (and GLB chunks) in the file's bytes; a GLB's header length is rewritten
/// to end after the chunks tinygltf reads.
Result<TinygltfInput> locateJson(std::vector<unsigned char>& bytes,
                                 const std::filesystem::path& path, const Diagnostics& diag) {
    std::string extension = path.extension().string();
    for (char& c : extension)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    TinygltfInput in;
    if (!isGlb(bytes) && extension != ".glb") {
        in.json = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        return in;
    }
    auto layout = parseGlb(bytes, diag);
    if (!layout) return std::move(layout).error();
    in.glb = *layout;
    in.json = std::string_view(reinterpret_cast<const char*>(bytes.data()) + layout->jsonOffset,
                               layout->jsonLength);
    // Unknown chunks after the ones tinygltf reads are dropped by shortening the length.
    const std::uint32_t length = std::uint32_t(layout->tinygltfLength);
    for (int i = 0; i < 4; ++i)
        bytes[8 + std::size_t(i)] = (length >> (8 * i)) & 0xFF;
    in.glbData = bytes.data();
    in.glbLength = layout->tinygltfLength;
    return in;
}

/// Points the input at a rewritten JSON (kept in `json`), rebuilding a GLB around it in `glb`.
Result<void> useRewrittenJson(const std::vector<unsigned char>& bytes, const std::string& json,
                              std::vector<unsigned char>& glb, TinygltfInput& in,
                              const Diagnostics& diag) {
    in.json = json;
    if (!in.glb) return {};
    auto rebuilt = rebuildGlb(bytes, *in.glb, json, diag);
    if (!rebuilt) return std::move(rebuilt).error();
    glb = std::move(*rebuilt);
    in.glbData = glb.data();
    in.glbLength = glb.size();
    return {};
}

// The bytes of the scene's objects convertModel will make from `model` (their fixed size; the
// geometry is charged as each accessor is read).
std::uint64_t sceneBytes(const tinygltf::Model& model) {
    std::uint64_t primitives = 0, animations = 0;
    for (const tinygltf::Mesh& m : model.meshes) primitives += m.primitives.size();
    for (const tinygltf::Animation& a : model.animations)
        animations += sizeof(Animation) + a.channels.size() * sizeof(AnimationChannel) +
                      a.samplers.size() * sizeof(AnimationSampler);
    return model.nodes.size() * sizeof(Node) + model.meshes.size() * sizeof(Mesh) +
           2 * primitives * sizeof(Primitive) + model.materials.size() * sizeof(Material) +
           model.lights.size() * sizeof(Light) + model.cameras.size() * sizeof(Camera) +
           model.skins.size() * sizeof(Skin) + model.textures.size() * sizeof(Texture) +
           model.scenes.size() * sizeof(SceneRoot) + animations;
}

Result<Scene> loadBytes(std::vector<unsigned char> bytes, const std::filesystem::path& path,
                        const LoadOptions& options) {
    const Diagnostics diag(path.string(), options.log, options.maxBytes);
    if (bytes.size() > options.maxBytes)
        return diag.error("", "\"" + path.filename().string() + "\" is " +
                                  std::to_string(bytes.size()) + " bytes, more than --max-size (" +
                                  std::to_string(options.maxBytes) + " bytes)");
    if (bytes.empty()) return diag.error("", "the file is empty");
    if (bytes.size() > std::numeric_limits<std::uint32_t>::max())
        return diag.error("", "files of 4 GiB or more cannot be read by tinygltf");

    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
    if (ec) return diag.error(ErrorCode::IoError, "", "cannot resolve the path: " + ec.message());
    auto in = locateJson(bytes, path, diag);
    if (!in) return std::move(in).error();
    Source source;
    source.folder = absolute.parent_path();
    source.maxBytes = options.maxBytes;
    for (const std::filesystem::path& a : options.allowedFolders)
        source.allowed.push_back(std::filesystem::absolute(a, ec).lexically_normal());
    source.glb = bool(in->glb);
    source.glbHasBin = in->glb && in->glb->hasBin;
    // The parsed document, then tinygltf's model, then Lantern's scene are charged before
    // each is built, from counts taken on the bytes and then on the document; a document is
    // returned to the budget once freed (the budget follows what is held at once).
    auto shape = scanJson(in->json, diag);
    if (!shape) return std::move(shape).error();
    const std::uint64_t document = shape->documentBytes();
    LANTERN_TRY(diag.charge(document, 1, "JSON", "parsing the document"));
    auto raw = inspectJson(in->json, source, diag);
    if (!raw) return std::move(raw).error();
    diag.release(document);
    std::vector<unsigned char> rebuiltGlb;
    if (!raw->jsonForTinygltf.empty()) {
        LANTERN_TRY(diag.charge(2 * raw->jsonForTinygltf.size(), 1, "JSON",
                                "rewriting the document for tinygltf"));
        LANTERN_TRY(useRewrittenJson(bytes, raw->jsonForTinygltf, rebuiltGlb, *in, diag));
    }
    LANTERN_TRY(diag.charge(document, 1, "JSON", "parsing the document (tinygltf)"));
    LANTERN_TRY(diag.charge(raw->modelBytes + raw->modelGrowthBytes, 1, "JSON",
                            "building tinygltf's model of " + std::to_string(shape->values()) +
                                " JSON values"));
    LANTERN_TRY(diag.charge(shape->contentBytes(), 1, "JSON", "the model's lists and names"));

    FsContext fs;
    fs.folder = source.folder.string();
    fs.maxBytes = options.maxBytes;
    fs.allowed = source.allowed;
    ImageStore images;
    auto model = parseModel(*in, fs, images, diag);
    if (!model) return std::move(model).error();
    diag.release(document + raw->modelGrowthBytes);
    // The file's bytes are in the model now; what follows may allocate as much again.
    std::vector<unsigned char>().swap(bytes);
    std::vector<unsigned char>().swap(rebuiltGlb);
    std::string().swap(raw->jsonForTinygltf);
    // The buffers tinygltf holds count against the load's budget (each was bounded alone).
    for (std::size_t i = 0; i < model->buffers.size(); ++i)
        LANTERN_TRY(
            diag.charge(model->buffers[i].data.size(), 1, at("buffers", i), "holding the data"));

    restoreDracoIndices(*model, *raw);
    // Decoded meshopt views and Draco primitives are charged to the same budget.
    LANTERN_TRY(decodeMeshopt(*model, *raw, diag));
    LANTERN_TRY(decodeDraco(*model, diag));
    LANTERN_TRY(validateModel(*model, *raw, options, diag));
    LANTERN_TRY(diag.charge(sceneBytes(*model) + shape->contentBytes(), 1, "JSON",
                            "converting the model into the scene"));
    auto scene = convertModel(*model, *raw, images, options, diag);
    if (!scene) return std::move(scene).error();
    noteFeatures(*model, *raw, in->glb.has_value(), *scene);
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

Result<Scene> loadGltf(const std::filesystem::path& path, const LoadOptions& options) {
    return load(path, options);
}

} // namespace gltf
} // namespace lantern
