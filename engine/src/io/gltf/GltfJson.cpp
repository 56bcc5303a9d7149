// The glTF loader's JSON pass, on the document before tinygltf sees it: every number checked
// (finite, integers in range), external URIs confined to the scene's folder, the integers of
// the compression extensions, and the facts tinygltf discards (optional numbers' presence,
// primitives it would drop); placeholder buffers and Draco's indices hidden from tinygltf.
#include "io/gltf/GltfInternal.h"
#include "io/gltf/GltfSchema.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>

namespace lantern::gltf {
namespace {

bool isDataUri(std::string_view uri) { return uri.substr(0, 5) == "data:"; }

} // namespace
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
    auto resolved = resolveConfined(source.folder, relative, source.maxBytes, source.allowed);
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
    auto relative = checkRelativeUri(value, object + ".uri", diag, !source.allowed.empty());
    if (!relative) return std::move(relative).error();
    const std::string problem = externalFileProblem(*relative, source);
    if (problem.empty()) {
        // tinygltf keeps no bytes of an empty image file: say so if a material uses it.
        std::error_code ec;
        if (!buffers && std::filesystem::file_size(source.folder / *relative, ec) == 0 && !ec)
            facts.imageProblems[int(i)] = "\"" + printable(value) + "\" is empty (0 bytes)";
        return {};
    }
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

// The channels of KHR_animation_pointer (path "pointer"), with the pointers they drive.
std::vector<std::pair<std::string, std::string>> pointerChannels(const json& doc) {
    std::vector<std::pair<std::string, std::string>> out;
    const json* animations = arrayOf(doc, "animations");
    for (std::size_t a = 0; animations && a < animations->size(); ++a) {
        const json& anim = (*animations)[a];
        const json* channels = anim.is_object() ? arrayOf(anim, "channels") : nullptr;
        for (std::size_t c = 0; channels && c < channels->size(); ++c) {
            const json& ch = (*channels)[c];
            auto target = ch.is_object() ? ch.find("target") : ch.end();
            if (!ch.is_object() || target == ch.end() || !target->is_object() ||
                target->value("path", json()) != "pointer")
                continue;
            std::string pointer = "a property";
            const json pointerJson =
                target->value("/extensions/KHR_animation_pointer/pointer"_json_pointer, json());
            if (pointerJson.is_string()) pointer = pointerJson.get<std::string>();
            out.emplace_back(at("animations", a) + "." + at("channels", c), pointer);
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

std::uint64_t sizeOfArray(const json& doc, const char* key) {
    const json* a = arrayOf(doc, key);
    return a ? a->size() : 0;
}

// Values under "extras" and "extensions" members, which tinygltf keeps as tinygltf::Value
// trees (one Value per JSON value, in a map node or a vector slot).
std::uint64_t keptValues(const json& v, bool kept) {
    std::uint64_t n = kept ? 1 : 0;
    if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it)
            n += keptValues(it.value(), kept || it.key() == "extras" || it.key() == "extensions");
    } else if (v.is_array()) {
        for (const json& e : v) n += keptValues(e, kept);
    }
    return n;
}

// RawFacts::modelBytes and modelGrowthBytes: tinygltf's objects by the counts in the document.
void countModelBytes(const json& doc, const std::vector<std::size_t>& primitiveCounts,
                     RawFacts& facts) {
    // A std::vector filled by push_back: its capacity is the power of two at or above `count`
    // (libstdc++ doubles), and at its last growth it also holds the old block, half that.
    const auto vector = [&facts](std::uint64_t count, std::uint64_t each) {
        if (count == 0) return;
        std::uint64_t capacity = 1;
        while (capacity < count) capacity *= 2;
        facts.modelBytes += capacity * each;
        facts.modelGrowthBytes += capacity / 2 * each;
    };
    vector(sizeOfArray(doc, "accessors"), sizeof(tinygltf::Accessor));
    vector(sizeOfArray(doc, "animations"), sizeof(tinygltf::Animation));
    vector(sizeOfArray(doc, "buffers"), sizeof(tinygltf::Buffer));
    vector(sizeOfArray(doc, "bufferViews"), sizeof(tinygltf::BufferView));
    vector(sizeOfArray(doc, "cameras"), sizeof(tinygltf::Camera));
    vector(sizeOfArray(doc, "images"), sizeof(tinygltf::Image));
    vector(sizeOfArray(doc, "materials"), sizeof(tinygltf::Material));
    vector(sizeOfArray(doc, "meshes"), sizeof(tinygltf::Mesh));
    vector(sizeOfArray(doc, "nodes"), sizeof(tinygltf::Node));
    vector(sizeOfArray(doc, "samplers"), sizeof(tinygltf::Sampler));
    vector(sizeOfArray(doc, "scenes"), sizeof(tinygltf::Scene));
    vector(sizeOfArray(doc, "skins"), sizeof(tinygltf::Skin));
    vector(sizeOfArray(doc, "textures"), sizeof(tinygltf::Texture));
    for (std::size_t count : primitiveCounts) vector(count, sizeof(tinygltf::Primitive));
    if (const json* animations = arrayOf(doc, "animations")) {
        for (const json& a : *animations) {
            if (!a.is_object()) continue;
            vector(sizeOfArray(a, "channels"), sizeof(tinygltf::AnimationChannel));
            vector(sizeOfArray(a, "samplers"), sizeof(tinygltf::AnimationSampler));
        }
    }
    auto ext = doc.find("extensions");
    if (ext != doc.end() && ext->is_object()) {
        auto lights = ext->find("KHR_lights_punctual");
        if (lights != ext->end() && lights->is_object())
            vector(sizeOfArray(*lights, "lights"), sizeof(tinygltf::Light));
    }
    // A Value in a map node (key, value, tree links) or a vector slot with spare capacity.
    facts.modelBytes += keptValues(doc, false) * (sizeof(tinygltf::Value) + 96);
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
    facts.pointerChannels = pointerChannels(*doc);
    auto counts = primitiveCounts(*doc, diag);
    if (!counts) return std::move(counts).error();
    facts.primitiveCounts = std::move(*counts);
    countModelBytes(*doc, facts.primitiveCounts, facts);
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

} // namespace lantern::gltf
