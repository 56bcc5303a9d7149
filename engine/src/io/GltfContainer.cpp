// The glTF loader's first pass, on the bytes before tinygltf sees them: the GLB container's
// chunk structure, the JSON nesting depth, external URIs confined to the scene's folder, and
// the facts tinygltf discards (optional numbers' presence, primitives it would drop).
#include "io/GltfInternal.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern::gltf {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A; // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;  // "BIN\0"

std::uint32_t readU32(const std::vector<unsigned char>& b, std::size_t offset) {
    // GLB is little-endian; assemble byte by byte so the host's order does not matter.
    return std::uint32_t(b[offset]) | std::uint32_t(b[offset + 1]) << 8 |
           std::uint32_t(b[offset + 2]) << 16 | std::uint32_t(b[offset + 3]) << 24;
}

std::string chunkName(std::uint32_t type) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        const char c = char((type >> (8 * i)) & 0xFF);
        s += (c >= 32 && c < 127) ? c : '?';
    }
    return "\"" + s + "\"";
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

bool isDataUri(std::string_view uri) {
    return uri.substr(0, 5) == "data:";
}

} // namespace

void Diagnostics::warn(const std::string& object, const std::string& message) const {
    if (!m_log) return;
    std::string line = m_file + ": ";
    if (!object.empty()) line += object + ": ";
    line += message;
    m_log(LogLevel::Warning, line);
}

Result<void> Diagnostics::charge(std::uint64_t count, std::uint64_t each, const std::string& object,
                                 const std::string& what) const {
    Budget& b = *m_budget;
    const std::uint64_t left = b.limit - std::min(b.used, b.limit);
    if (each != 0 && count > left / each)
        return error(object, what + " would need " +
                                 (count > ~std::uint64_t(0) / each
                                      ? std::string("more than 2^64")
                                      : std::to_string(count * each)) +
                                 " bytes, more than the " + std::to_string(left) +
                                 " left of the scene's budget (--max-size, " +
                                 std::to_string(b.limit) + " bytes in all)");
    b.used += count * each;
    return {};
}

std::string at(std::string_view array, std::size_t index) {
    return std::string(array) + "[" + std::to_string(index) + "]";
}

bool isGlb(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
}

Result<GlbLayout> parseGlb(const std::vector<unsigned char>& bytes, const Diagnostics& diag) {
    const std::size_t size = bytes.size();
    if (size < 12)
        return diag.error("GLB header", "file is " + std::to_string(size) +
                                            " bytes, shorter than the 12-byte GLB header");
    if (readU32(bytes, 0) != kGlbMagic) return diag.error("GLB header", "magic is not \"glTF\"");
    const std::uint32_t version = readU32(bytes, 4);
    if (version != 2)
        return diag.error("GLB header", "container version " + std::to_string(version) +
                                            " is not supported (only 2)");
    const std::uint32_t length = readU32(bytes, 8);
    if (length != size)
        return diag.error("GLB header", "declared length " + std::to_string(length) +
                                            " differs from the file size " + std::to_string(size));
    if (size < 20)
        return diag.error("GLB header", "no JSON chunk (the file ends after the header)");

    GlbLayout layout;
    bool haveJson = false;
    std::size_t chunkIndex = 0;
    std::size_t offset = 12;
    std::size_t understoodEnd = 0;
    while (offset < size) {
        const std::string object = "GLB " + at("chunks", chunkIndex);
        if (size - offset < 8)
            return diag.error(object, "truncated chunk header (" + std::to_string(size - offset) +
                                          " bytes left, 8 needed)");
        const std::uint32_t chunkLength = readU32(bytes, offset);
        const std::uint32_t chunkType = readU32(bytes, offset + 4);
        const std::size_t dataOffset = offset + 8;
        if (chunkLength > size - dataOffset)
            return diag.error(object, "chunk length " + std::to_string(chunkLength) +
                                          " runs past the end of the file");
        if (chunkLength % 4 != 0)
            return diag.error(object, "chunk length " + std::to_string(chunkLength) +
                                          " is not a multiple of 4");
        if (chunkIndex == 0) {
            if (chunkType != kChunkJson)
                return diag.error(object, "first chunk is " + chunkName(chunkType) +
                                              ", not the JSON chunk");
            if (chunkLength == 0) return diag.error(object, "JSON chunk is empty");
            layout.jsonOffset = dataOffset;
            layout.jsonLength = chunkLength;
            haveJson = true;
            understoodEnd = dataOffset + chunkLength;
        } else if (chunkType == kChunkJson) {
            return diag.error(object, "second JSON chunk (only one is allowed)");
        } else if (chunkType == kChunkBin) {
            if (layout.hasBin) return diag.error(object, "second BIN chunk (only one is allowed)");
            if (chunkIndex != 1)
                return diag.error(object, "BIN chunk must directly follow the JSON chunk");
            layout.hasBin = true;
            layout.binOffset = dataOffset;
            layout.binLength = chunkLength;
            understoodEnd = dataOffset + chunkLength;
        } else {
            diag.warn(object, "unknown chunk type " + chunkName(chunkType) + " ignored");
        }
        offset = dataOffset + chunkLength;
        ++chunkIndex;
    }
    if (!haveJson) return diag.error("GLB", "no JSON chunk");
    layout.tinygltfLength = understoodEnd;
    return layout;
}

Result<void> checkJsonNesting(std::string_view json, const Diagnostics& diag) {
    int depth = 0;
    bool inString = false, escaped = false;
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"')
            inString = true;
        else if (c == '{' || c == '[') {
            if (++depth > kMaxJsonDepth)
                return diag.error("JSON", "nested more than " + std::to_string(kMaxJsonDepth) +
                                              " levels deep (at byte " + std::to_string(i) + ")");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
    return {};
}

std::string percentDecode(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size()) {
            const int hi = hexValue(text[i + 1]), lo = hexValue(text[i + 2]);
            if (hi >= 0 && lo >= 0) {
                out += char(hi * 16 + lo);
                i += 2;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

std::string printable(std::string_view text, std::size_t limit) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (out.size() >= limit) return out + "...";
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 32 && c < 127) {
            out += char(c);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", unsigned(c));
            out += buf;
        }
    }
    return out;
}

namespace {

const char* fileKind(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISLNK(mode)) return "a symbolic link";
    return "not a regular file";
}

std::string sizeProblem(std::uint64_t size, std::uint64_t maxBytes) {
    return "is " + std::to_string(size) + " bytes, more than --max-size (" +
           std::to_string(maxBytes) + " bytes)";
}

} // namespace

Result<std::vector<unsigned char>> readRegularFile(const std::filesystem::path& path,
                                                   std::uint64_t maxBytes, bool noFollow) {
    const int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC | (noFollow ? O_NOFOLLOW : 0);
    const int fd = ::open(path.c_str(), flags);
    if (fd < 0) {
        const int e = errno;
        if (e == ENOENT) return makeError(ErrorCode::InvalidInput, "does not exist");
        if (e == ELOOP && noFollow) return makeError(ErrorCode::InvalidInput, "is a symbolic link");
        return makeError(ErrorCode::IoError, std::string("cannot be opened: ") + std::strerror(e));
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        const std::string kind = fileKind(st.st_mode);
        ::close(fd);
        return makeError(ErrorCode::InvalidInput, "is " + kind + ", not a regular file");
    }
    if (std::uint64_t(st.st_size) > maxBytes) {
        ::close(fd);
        return makeError(ErrorCode::InvalidInput, sizeProblem(std::uint64_t(st.st_size), maxBytes));
    }
    std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int e = n < 0 ? errno : 0;
            ::close(fd);
            return makeError(ErrorCode::IoError,
                             e ? std::string("cannot be read: ") + std::strerror(e)
                               : std::string("became shorter while it was read"));
        }
        done += std::size_t(n);
    }
    ::close(fd);
    return bytes;
}

Result<std::filesystem::path> resolveConfined(const std::filesystem::path& folder,
                                              const std::string& relative,
                                              std::uint64_t maxBytes) {
    const std::string shown = "\"" + printable(relative) + "\"";
    auto realOf = [](const std::filesystem::path& p) -> std::optional<std::filesystem::path> {
        char buf[PATH_MAX];
        if (!::realpath(p.c_str(), buf)) return std::nullopt;
        return std::filesystem::path(buf);
    };
    const auto realFolder = realOf(folder);
    if (!realFolder)
        return makeError(ErrorCode::IoError, "the scene's folder cannot be resolved: " +
                                                 std::string(std::strerror(errno)));
    const std::filesystem::path named = folder / relative;
    struct stat st {};
    if (::lstat(named.c_str(), &st) != 0)
        return makeError(ErrorCode::InvalidInput, shown + " does not exist in the scene's folder");
    const auto real = realOf(named);
    if (!real)
        return makeError(ErrorCode::InvalidInput,
                         shown + " cannot be resolved (a broken or looping symbolic link?)");
    const std::string inside = realFolder->string() == "/" ? "/" : realFolder->string() + "/";
    if (real->string().compare(0, inside.size(), inside) != 0)
        return makeError(ErrorCode::InvalidInput,
                         shown + " is a symbolic link that leads outside the scene's folder");
    if (::stat(real->c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        return makeError(ErrorCode::InvalidInput,
                         shown + " is " + fileKind(st.st_mode) + ", not a regular file");
    if (std::uint64_t(st.st_size) > maxBytes)
        return makeError(ErrorCode::InvalidInput,
                         shown + " " + sizeProblem(std::uint64_t(st.st_size), maxBytes));
    return *real;
}

Result<std::string> checkRelativeUri(std::string_view uri, const std::string& object,
                                     const Diagnostics& diag) {
    const std::string path = percentDecode(uri);
    const std::string shown = "\"" + printable(uri) + "\"";
    if (path.empty()) return diag.error(object, "URI is empty");
    if (path.find('\0') != std::string::npos)
        return diag.error(object, "URI " + shown + " contains a NUL character");
    // A scheme ("http:", "file:") is a colon before the first slash. Only relative paths and
    // data: URIs are read: a scene file must not make the loader fetch or open anything else.
    const std::size_t colon = path.find(':'), slash = path.find('/');
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
        return diag.error(object, "URI " + shown +
                                      " has a scheme; only relative paths and data: URIs are read");
    if (path[0] == '/' || path[0] == '\\')
        return diag.error(object, "URI " + shown +
                                      " is an absolute path; external files must lie in the "
                                      "scene's folder");
    // ".." anywhere as a path component (either separator) could leave the folder.
    std::size_t start = 0;
    while (start <= path.size()) {
        std::size_t end = path.find_first_of("/\\", start);
        if (end == std::string::npos) end = path.size();
        if (path.compare(start, end - start, "..") == 0)
            return diag.error(object, "URI " + shown +
                                          " contains \"..\"; external files must lie in the "
                                          "scene's folder");
        start = end + 1;
    }
    return path;
}

namespace {

using nlohmann::json;

// The document, or the parser's message; its top level must be an object.
Result<json> parseJson(std::string_view text, const Diagnostics& diag) {
    json doc;
    try {
        doc = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        // nlohmann's message names the line and column ("parse error at line 1, column 2").
        std::string what = e.what();
        if (const std::size_t bracket = what.find("] "); bracket != std::string::npos)
            what = what.substr(bracket + 2);
        return diag.error("JSON", what);
    }
    if (!doc.is_object()) return diag.error("JSON", "the top level is not a JSON object");
    return doc;
}

// The top-level array `name`, or null when absent or not an array.
const json* arrayOf(const json& doc, const char* name) {
    auto it = doc.find(name);
    return (it != doc.end() && it->is_array()) ? &*it : nullptr;
}

// Whether a buffer is marked as a meshopt fallback (its views' data is decoded from elsewhere).
bool isMeshoptFallback(const json& buffer) {
    auto extensions = buffer.find("extensions");
    if (extensions == buffer.end() || !extensions->is_object()) return false;
    for (const char* name : kMeshoptExtensions) {
        auto e = extensions->find(name);
        if (e == extensions->end() || !e->is_object()) continue;
        auto fallback = e->find("fallback");
        if (fallback != e->end() && fallback->is_boolean() && fallback->get<bool>()) return true;
    }
    return false;
}

// A meshopt fallback buffer without data: recorded with its byteLength (the bound its views
// must lie within) for the meshopt pass, which refuses any view into it that is not compressed.
Result<void> recordPlaceholder(const json& buffer, std::size_t i, const std::string& object,
                               const Diagnostics& diag, RawFacts& facts) {
    auto length = buffer.find("byteLength");
    if (length == buffer.end() || !length->is_number_unsigned())
        return diag.error(object + ".byteLength", "is missing or not a non-negative integer");
    facts.placeholderBuffers[int(i)] = length->get<std::uint64_t>();
    return {};
}

// Buffer `i` without a uri: only a GLB's buffer 0 may have none, and then the file has a BIN
// chunk; or a meshopt fallback buffer (a placeholder).
Result<void> checkBufferWithoutUri(const json& buffer, std::size_t i, const std::string& object,
                                   const Source& source, const Diagnostics& diag,
                                   RawFacts& facts) {
    if (isMeshoptFallback(buffer) && !(source.glb && i == 0))
        return recordPlaceholder(buffer, i, object, diag, facts);
    if (!source.glb)
        return diag.error(object, "has no uri: a .gltf buffer's data must come from "
                                  "a file or a data: URI (or it is a meshopt fallback buffer, "
                                  "extensions.EXT_meshopt_compression.fallback)");
    if (i != 0)
        return diag.error(object, "has no uri: only buffer 0 can refer to the GLB's "
                                  "BIN chunk");
    if (!source.glbHasBin)
        return diag.error(object, "refers to the GLB's BIN chunk, but the file has "
                                  "none");
    return {};
}

// Why the external file `relative` cannot be read (missing, outside the folder through a
// symlink, not a regular file, over the size bound); empty when it can.
std::string externalFileProblem(const std::string& relative, const Source& source) {
    auto resolved = resolveConfined(source.folder, relative, source.maxBytes);
    return resolved ? std::string() : resolved.error().message;
}

// One buffer or image (item `i` of `kind`): its URI stays inside the folder; a buffer's file must
// exist and fit the size bound; an image's missing file is recorded in `facts` (an error only
// if a material uses it).
Result<void> checkExternalItem(const json& item, const char* kind, std::size_t i,
                               const Source& source, const Diagnostics& diag, RawFacts& facts) {
    const bool buffers = std::string_view(kind) == "buffers";
    const std::string object = at(kind, i);
    auto uri = item.find("uri");
    if (uri == item.end() || !uri->is_string()) {
        if (!buffers) return {};
        return checkBufferWithoutUri(item, i, object, source, diag, facts);
    }
    const std::string& value = uri->get_ref<const std::string&>();
    if (isDataUri(value)) {
        // tinygltf would take a data: URI it cannot decode for a file name.
        if (!tinygltf::IsDataURI(value))
            return diag.error(object + ".uri",
                              "data: URI with an unsupported MIME type or encoding "
                              "(read: base64 with application/octet-stream, "
                              "application/gltf-buffer or an image type)");
        return {};
    }
    auto relative = checkRelativeUri(value, object + ".uri", diag);
    if (!relative) return std::move(relative).error();
    const std::string problem = externalFileProblem(*relative, source);
    if (problem.empty()) return {};
    // A missing image is an error only when a material uses it; a file that escapes the
    // folder, is not a regular file or is too large is refused whatever uses it.
    if (buffers || problem.find("does not exist") == std::string::npos)
        return diag.error(object + ".uri", problem);
    facts.imageProblems[int(i)] = problem; // an error only if a material uses it
    return {};
}

// External files: the URI must stay inside the folder; buffers must exist and fit the
// size bound (tinygltf's own message would be a bare "file not found").
Result<void> checkExternalFiles(const json& doc, const Source& source, const Diagnostics& diag,
                                RawFacts& facts) {
    for (const char* kind : {"buffers", "images"}) {
        const json* items = arrayOf(doc, kind);
        if (!items) continue;
        for (std::size_t i = 0; i < items->size(); ++i) {
            const json& item = (*items)[i];
            if (!item.is_object()) continue;
            LANTERN_TRY(checkExternalItem(item, kind, i, source, diag, facts));
        }
    }
    return {};
}

// glTF's integer properties (indices into arrays, offsets, lengths, counts, enums): tinygltf
// reads them into int or size_t, so 4294967296 became 0, 0.5 was dropped and -4 read as 0.
// Indices must be integers in 0..INT_MAX; offsets, lengths and counts in 0..2^53.
enum class IntKind { None, Index, Size, IndexMap /* an object of indices: attributes */ };

IntKind integerKind(std::string_view key) {
    static const char* const indices[] = {
        "scene", "buffer", "bufferView", "componentType", "mesh", "camera", "skin", "material",
        "indices", "mode", "sampler", "source", "index", "texCoord", "input", "output", "node",
        "inverseBindMatrices", "skeleton", "magFilter", "minFilter", "wrapS", "wrapT", "light",
        "children", "nodes", "joints", "target"};
    static const char* const sizes[] = {"byteOffset", "byteLength", "byteStride", "count"};
    if (key == "attributes" || key == "targets") return IntKind::IndexMap;
    for (const char* k : indices)
        if (key == k) return IntKind::Index;
    for (const char* k : sizes)
        if (key == k) return IntKind::Size;
    return IntKind::None;
}

// The largest magnitude accepted for any other number (colours, intensities, transforms,
// camera parameters): 1e30, beyond the 1e-20..1e20 scales the image tests draw, and far below
// where double composition overflows (1e300 in a transform put Inf into EXR headers; in a
// light it turned the image black).
constexpr double kMaxMagnitude = 1e30;

Result<void> checkInteger(const json& v, IntKind kind, const std::string& path,
                          const Diagnostics& diag) {
    if (!v.is_number()) return {}; // a wrong type is reported by the structural checks
    const double limit = kind == IntKind::Index ? 2147483647.0 : 9007199254740992.0;
    const double d = v.get<double>();
    const bool integral = v.is_number_integer() || (std::isfinite(d) && d == std::floor(d));
    if (!integral)
        return diag.error(path, "is " + printable(v.dump(), 40) + ", not an integer");
    if (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() < 0)
        return diag.error(path, "is " + v.dump() + "; it must be 0 or more");
    if (d < 0) return diag.error(path, "is " + printable(v.dump(), 40) + "; it must be 0 or more");
    if (d > limit)
        return diag.error(path, "is " + printable(v.dump(), 40) + ", more than the largest " +
                                    (kind == IntKind::Index ? "index" : "size") + " (" +
                                    std::to_string(std::uint64_t(limit)) + ")");
    return {};
}

// Walks the document once (linear; its depth is bounded by checkJsonNesting), checking
// integer properties and number magnitudes, skipping "extras" (the application's own data)
// and accessors' min/max (they describe the data, which is checked when read).
Result<void> checkNumbers(const json& v, std::string& path, IntKind kind, bool inAccessor,
                          const Diagnostics& diag) {
    if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it) {
            if (it.key() == "extras") continue;
            const std::size_t mark = path.size();
            path += "." + printable(it.key(), 40);
            const bool accessorBounds = inAccessor && (it.key() == "min" || it.key() == "max");
            const IntKind child = kind == IntKind::IndexMap ? IntKind::Index : integerKind(it.key());
            Result<void> r = accessorBounds ? Result<void>()
                                            : checkNumbers(it.value(), path, child, inAccessor, diag);
            path.resize(mark);
            if (!r) return r;
        }
        return {};
    }
    if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::size_t mark = path.size();
            path += "[" + std::to_string(i) + "]";
            // An array passes its kind to numbers and to index maps (targets), not to objects.
            const IntKind element =
                v[i].is_object() && kind != IntKind::IndexMap ? IntKind::None : kind;
            Result<void> r = checkNumbers(v[i], path, element, inAccessor, diag);
            path.resize(mark);
            if (!r) return r;
        }
        return {};
    }
    if (!v.is_number()) return {};
    if (kind == IntKind::Index || kind == IntKind::Size) return checkInteger(v, kind, path, diag);
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > kMaxMagnitude)
        return diag.error(path, "is " + printable(v.dump(), 40) +
                                    "; numbers beyond +-1e30 would become infinite on the way to "
                                    "an image");
    if (path.size() >= 12 && path.compare(path.size() - 12, 12, ".aspectRatio") == 0 && !(d > 0))
        return diag.error(path, "is " + v.dump() + "; an aspect ratio must be greater than 0");
    return {};
}

Result<void> checkAllNumbers(const json& doc, const Diagnostics& diag) {
    for (auto it = doc.begin(); it != doc.end(); ++it) {
        if (it.key() == "extras") continue;
        std::string path = printable(it.key(), 40);
        // Top-level arrays ("nodes", "scenes") hold objects; "scene" is an index.
        LANTERN_TRY(checkNumbers(it.value(), path, integerKind(it.key()),
                                 it.key() == "accessors", diag));
    }
    return {};
}

// Per camera: whether its perspective block has a zfar (tinygltf does not keep the difference
// between an absent zfar and its default).
std::vector<bool> perspectiveHasZfar(const json& doc) {
    std::vector<bool> out;
    if (const json* cameras = arrayOf(doc, "cameras")) {
        for (const json& c : *cameras) {
            bool hasZfar = false;
            if (c.is_object()) {
                auto p = c.find("perspective");
                if (p != c.end() && p->is_object()) hasZfar = p->contains("zfar");
            }
            out.push_back(hasZfar);
        }
    }
    return out;
}

// Per mesh: the number of primitives written. tinygltf drops a primitive without an attributes
// object silently, which would shift every later primitive's index: refuse instead.
Result<std::vector<std::size_t>> primitiveCounts(const json& doc, const Diagnostics& diag) {
    std::vector<std::size_t> counts;
    if (const json* meshes = arrayOf(doc, "meshes")) {
        for (std::size_t m = 0; m < meshes->size(); ++m) {
            const json& mesh = (*meshes)[m];
            std::size_t count = 0;
            if (mesh.is_object()) {
                auto prims = mesh.find("primitives");
                if (prims != mesh.end() && prims->is_array()) {
                    count = prims->size();
                    for (std::size_t p = 0; p < prims->size(); ++p) {
                        const json& prim = (*prims)[p];
                        const std::string object = at("meshes", m) + "." + at("primitives", p);
                        if (!prim.is_object()) return diag.error(object, "is not an object");
                        auto attrs = prim.find("attributes");
                        if (attrs == prim.end() || !attrs->is_object())
                            return diag.error(object + ".attributes",
                                              "is missing or not an object");
                    }
                }
            }
            counts.push_back(count);
        }
    }
    return counts;
}

// An integer member of a compression extension must fit tinygltf's int (it keeps the low 32
// bits of larger ones, which would turn 2^32 + 8 into 8).
Result<void> checkIntMember(const json& value, const std::string& object, const Diagnostics& diag) {
    if (!value.is_number_integer()) return {}; // other types: refused by the decoding pass
    const bool fits = value.is_number_unsigned()
                          ? value.get<std::uint64_t>() <= std::uint64_t(INT32_MAX)
                          : value.get<std::int64_t>() >= 0 &&
                                value.get<std::int64_t>() <= std::int64_t(INT32_MAX);
    if (!fits)
        return diag.error(object, value.dump() + " is outside [0, " + std::to_string(INT32_MAX) +
                                      "]");
    return {};
}

// The integers of every meshopt and Draco extension object (see checkIntMember).
Result<void> checkCompressionIntegers(const json& doc, const Diagnostics& diag) {
    auto members = [&](const json& ext, const std::string& object) -> Result<void> {
        if (!ext.is_object()) return {};
        for (const auto& [key, value] : ext.items()) {
            LANTERN_TRY(checkIntMember(value, object + "." + key, diag));
            if (key == "attributes" && value.is_object())
                for (const auto& [name, id] : value.items())
                    LANTERN_TRY(checkIntMember(id, object + ".attributes." + name, diag));
        }
        return {};
    };
    auto extensionsOf = [](const json& item) -> const json* {
        auto e = item.is_object() ? item.find("extensions") : item.end();
        return (item.is_object() && e != item.end() && e->is_object()) ? &*e : nullptr;
    };
    if (const json* views = arrayOf(doc, "bufferViews"))
        for (std::size_t v = 0; v < views->size(); ++v)
            if (const json* ext = extensionsOf((*views)[v]))
                for (const char* name : kMeshoptExtensions)
                    if (ext->contains(name))
                        LANTERN_TRY(members((*ext)[name],
                                            at("bufferViews", v) + ".extensions." + name));
    if (const json* meshes = arrayOf(doc, "meshes"))
        for (std::size_t m = 0; m < meshes->size(); ++m) {
            const json& mesh = (*meshes)[m];
            const json* prims = mesh.is_object() ? arrayOf(mesh, "primitives") : nullptr;
            for (std::size_t p = 0; prims && p < prims->size(); ++p)
                if (const json* ext = extensionsOf((*prims)[p]);
                    ext && ext->contains("KHR_draco_mesh_compression"))
                    LANTERN_TRY(members((*ext)["KHR_draco_mesh_compression"],
                                        at("meshes", m) + "." + at("primitives", p) +
                                            ".extensions.KHR_draco_mesh_compression"));
        }
    return {};
}

// tinygltf 2.7.0 (built without Draco) refuses a primitive whose indices accessor has no
// bufferView, which is how KHR_draco_mesh_compression primitives are written: their indices are
// taken out of the JSON it reads and put back after it (restoreDracoIndices, GltfDraco.cpp).
void hideDracoIndices(json& doc, RawFacts& facts) {
    auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array()) return;
    for (std::size_t m = 0; m < meshes->size(); ++m) {
        json& mesh = (*meshes)[m];
        auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
        if (!mesh.is_object() || prims == mesh.end() || !prims->is_array()) continue;
        for (std::size_t p = 0; p < prims->size(); ++p) {
            json& prim = (*prims)[p];
            if (!prim.is_object()) continue;
            auto ext = prim.find("extensions");
            auto indices = prim.find("indices");
            if (ext == prim.end() || !ext->is_object() ||
                !ext->contains("KHR_draco_mesh_compression") || indices == prim.end() ||
                !indices->is_number_unsigned() || indices->get<std::uint64_t>() > INT32_MAX)
                continue;
            facts.dracoIndices[{int(m), int(p)}] = indices->get<int>();
            prim.erase(indices);
        }
    }
}

} // namespace

Result<RawFacts> inspectJson(std::string_view text, const Source& source, const Diagnostics& diag) {
    auto doc = parseJson(text, diag);
    if (!doc) return std::move(doc).error();
    RawFacts facts;
    LANTERN_TRY(checkAllNumbers(*doc, diag));
    LANTERN_TRY(checkExternalFiles(*doc, source, diag, facts));
    LANTERN_TRY(checkCompressionIntegers(*doc, diag));
    facts.perspectiveHasZfar = perspectiveHasZfar(*doc);
    auto counts = primitiveCounts(*doc, diag);
    if (!counts) return std::move(counts).error();
    facts.primitiveCounts = std::move(*counts);
    // Four zero bytes: tinygltf refuses a buffer without data, and nothing reads these.
    for (const auto& [index, length] : facts.placeholderBuffers) {
        json& buffer = (*doc)["buffers"][std::size_t(index)];
        buffer["uri"] = "data:application/octet-stream;base64,AAAAAA==";
        buffer["byteLength"] = 4;
    }
    hideDracoIndices(*doc, facts);
    if (!facts.placeholderBuffers.empty() || !facts.dracoIndices.empty())
        facts.jsonForTinygltf = doc->dump();
    return facts;
}

Result<std::vector<unsigned char>> rebuildGlb(const std::vector<unsigned char>& bytes,
                                              const GlbLayout& layout, const std::string& json,
                                              const Diagnostics& diag) {
    std::string text = json;
    while (text.size() % 4 != 0)
        text += ' ';
    const std::uint64_t total =
        20 + std::uint64_t(text.size()) + (layout.hasBin ? 8 + std::uint64_t(layout.binLength) : 0);
    if (total > std::numeric_limits<std::uint32_t>::max())
        return diag.error("GLB", "files of 4 GiB or more cannot be read by tinygltf");
    std::vector<unsigned char> out;
    out.reserve(std::size_t(total));
    auto u32 = [&](std::uint64_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back((v >> (8 * i)) & 0xFF);
    };
    u32(kGlbMagic);
    u32(2);
    u32(total);
    u32(text.size());
    u32(kChunkJson);
    out.insert(out.end(), text.begin(), text.end());
    if (layout.hasBin) {
        u32(layout.binLength);
        u32(kChunkBin);
        const auto bin = bytes.begin() + std::ptrdiff_t(layout.binOffset);
        out.insert(out.end(), bin, bin + std::ptrdiff_t(layout.binLength));
    }
    return out;
}

} // namespace lantern::gltf
