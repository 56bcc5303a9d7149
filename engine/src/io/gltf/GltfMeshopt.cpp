// EXT_meshopt_compression (and KHR_meshopt_compression, the same JSON): buffer views whose data
// meshoptimizer decodes from a compressed range of another buffer. Every parameter is checked
// before meshoptimizer sees it (its preconditions are asserts, not errors), the decoded total is
// charged to the load's budget before allocating, views into placeholder (fallback) buffers must
// all be compressed, and filtered data must be read as the type the filter writes.
#include "io/gltf/GltfInternal.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cstring>

namespace lantern::gltf {

int addDecodedBuffer(tinygltf::Model& model, std::vector<unsigned char> data) {
    tinygltf::Buffer buffer;
    buffer.name = "(decoded)";
    buffer.data = std::move(data);
    model.buffers.push_back(std::move(buffer));
    return int(model.buffers.size()) - 1;
}

namespace {

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

/// A compressed view's extension, read and checked against the rules of the specification.
struct Compressed {
    int view = 0;
    std::string object; ///< "bufferViews[i].extensions.EXT_meshopt_compression"
    int buffer = 0;
    std::size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
    std::string filterName = "NONE";
    const char* name = kMeshoptExtensions[0]; ///< which of the two extensions
};

/// An integer member >= `minimum`; `fallback` when absent and not required.
Result<std::size_t> integer(const tinygltf::Value& ext, const char* key, bool required,
                            int minimum, const std::string& object, const Diagnostics& diag) {
    const std::string path = object + "." + key;
    if (!ext.Has(key)) {
        if (required) return diag.error(path, "is missing");
        return std::size_t(0);
    }
    const tinygltf::Value& v = ext.Get(key);
    if (!v.IsInt()) return diag.error(path, "is not an integer");
    if (v.GetNumberAsInt() < minimum)
        return diag.error(path, std::to_string(v.GetNumberAsInt()) + " is less than " +
                                    std::to_string(minimum));
    return std::size_t(v.GetNumberAsInt());
}

Result<void> readModeAndFilter(const tinygltf::Value& ext, Compressed& c, const Diagnostics& diag) {
    if (!ext.Has("mode") || !ext.Get("mode").IsString())
        return diag.error(c.object + ".mode", "is missing or not a string");
    const std::string mode = ext.Get("mode").Get<std::string>();
    if (mode == "ATTRIBUTES")
        c.mode = Mode::Attributes;
    else if (mode == "TRIANGLES")
        c.mode = Mode::Triangles;
    else if (mode == "INDICES")
        c.mode = Mode::Indices;
    else
        return diag.error(c.object + ".mode",
                          "\"" + mode + "\" is not ATTRIBUTES, TRIANGLES or INDICES");
    if (ext.Has("filter")) {
        if (!ext.Get("filter").IsString())
            return diag.error(c.object + ".filter", "is not a string");
        c.filterName = ext.Get("filter").Get<std::string>();
    }
    const std::pair<const char*, Filter> filters[] = {{"NONE", Filter::None},
                                                      {"OCTAHEDRAL", Filter::Octahedral},
                                                      {"QUATERNION", Filter::Quaternion},
                                                      {"EXPONENTIAL", Filter::Exponential}};
    for (const auto& [name, filter] : filters)
        if (c.filterName == name) {
            c.filter = filter;
            return {};
        }
    return diag.error(c.object + ".filter",
                      "\"" + c.filterName +
                          "\" is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL (the filters "
                          "meshoptimizer 0.18 decodes)");
}

/// The layout rules of the specification ("For the extension object to be valid...").
Result<void> checkLayout(const tinygltf::BufferView& view, const Compressed& c,
                         const Diagnostics& diag) {
    const std::size_t s = c.byteStride;
    if (view.byteStride != 0 && view.byteStride != s)
        return diag.error(c.object + ".byteStride",
                          std::to_string(s) + " differs from the bufferView's byteStride " +
                              std::to_string(view.byteStride));
    if (view.byteLength != s * c.count)
        return diag.error(c.object, "byteStride " + std::to_string(s) + " x count " +
                                        std::to_string(c.count) + " is not the bufferView's " +
                                        "byteLength " + std::to_string(view.byteLength));
    if (c.mode == Mode::Attributes && (s % 4 != 0 || s > 256))
        return diag.error(c.object + ".byteStride", std::to_string(s) +
                                                        " is not a multiple of 4 in [4, 256] "
                                                        "(mode ATTRIBUTES)");
    if (c.mode != Mode::Attributes && s != 2 && s != 4)
        return diag.error(c.object + ".byteStride",
                          std::to_string(s) + " is not 2 or 4 (index data)");
    if (c.mode == Mode::Triangles && c.count % 3 != 0)
        return diag.error(c.object + ".count",
                          std::to_string(c.count) + " is not a multiple of 3 (mode TRIANGLES)");
    if (c.mode != Mode::Attributes && c.filter != Filter::None)
        return diag.error(c.object + ".filter",
                          c.filterName + " on index data (only NONE is allowed)");
    const bool strideOk = c.filter == Filter::None ||
                          (c.filter == Filter::Octahedral && (s == 4 || s == 8)) ||
                          (c.filter == Filter::Quaternion && s == 8) ||
                          (c.filter == Filter::Exponential && s % 4 == 0);
    if (!strideOk)
        return diag.error(c.object + ".byteStride",
                          std::to_string(s) + " does not suit the " + c.filterName +
                              " filter (OCTAHEDRAL: 4 or 8, QUATERNION: 8, EXPONENTIAL: a "
                              "multiple of 4)");
    return {};
}

/// Reads and checks view `v`'s extension `name`; its source range must lie in a buffer with data.
Result<Compressed> readCompressed(const tinygltf::Model& model, std::size_t v, const char* name,
                                  const tinygltf::Value& ext, const RawFacts& raw,
                                  const Diagnostics& diag) {
    Compressed c;
    c.view = int(v);
    c.object = at("bufferViews", v) + ".extensions." + name;
    if (!ext.IsObject()) return diag.error(c.object, "is not an object");
    auto buffer = integer(ext, "buffer", true, 0, c.object, diag);
    auto offset = integer(ext, "byteOffset", false, 0, c.object, diag);
    auto length = integer(ext, "byteLength", true, 1, c.object, diag);
    auto stride = integer(ext, "byteStride", true, 1, c.object, diag);
    auto count = integer(ext, "count", true, 1, c.object, diag);
    for (auto* r : {&buffer, &offset, &length, &stride, &count})
        if (!*r) return std::move(*r).error();
    c.buffer = int(*buffer);
    c.byteOffset = *offset;
    c.byteLength = *length;
    c.byteStride = *stride;
    c.count = *count;
    LANTERN_TRY(readModeAndFilter(ext, c, diag));
    if (std::size_t(c.buffer) >= model.buffers.size())
        return diag.error(c.object + ".buffer", "buffer " + std::to_string(c.buffer) +
                                                    " does not exist (the file has " +
                                                    std::to_string(model.buffers.size()) + ")");
    if (raw.placeholderBuffers.count(c.buffer))
        return diag.error(c.object + ".buffer", at("buffers", std::size_t(c.buffer)) +
                                                    " is a fallback buffer without data; "
                                                    "compressed data cannot come from it");
    const std::size_t size = model.buffers[std::size_t(c.buffer)].data.size();
    if (c.byteOffset > size || c.byteLength > size - c.byteOffset)
        return diag.error(c.object, "byteOffset " + std::to_string(c.byteOffset) +
                                        " + byteLength " + std::to_string(c.byteLength) +
                                        " exceeds the " + std::to_string(size) + " bytes of " +
                                        at("buffers", std::size_t(c.buffer)));
    LANTERN_TRY(checkLayout(model.bufferViews[v], c, diag));
    return c;
}

/// Why meshoptimizer refused a stream, from its return code.
std::string decodeFailure(int rc) {
    switch (rc) {
    case -1:
        return "the compressed data has an encoding version meshoptimizer 0.18 does not decode";
    case -2:
        return "the compressed data is malformed or truncated";
    case -3:
        return "the compressed data does not end where its byteLength says";
    default:
        return "the compressed data cannot be decoded (meshoptimizer returned " +
               std::to_string(rc) + ")";
    }
}

/// Decodes one view into `out` (byteStride x count bytes) and applies its filter.
Result<void> decode(const tinygltf::Model& model, const Compressed& c, unsigned char* out,
                    const Diagnostics& diag) {
    const unsigned char* src = model.buffers[std::size_t(c.buffer)].data.data() + c.byteOffset;
    int rc = 0;
    if (c.mode == Mode::Attributes)
        rc = meshopt_decodeVertexBuffer(out, c.count, c.byteStride, src, c.byteLength);
    else if (c.mode == Mode::Triangles)
        rc = meshopt_decodeIndexBuffer(out, c.count, c.byteStride, src, c.byteLength);
    else
        rc = meshopt_decodeIndexSequence(out, c.count, c.byteStride, src, c.byteLength);
    if (rc != 0) return diag.error(c.object, decodeFailure(rc));
    if (c.filter == Filter::Octahedral)
        meshopt_decodeFilterOct(out, c.count, c.byteStride);
    else if (c.filter == Filter::Quaternion)
        meshopt_decodeFilterQuat(out, c.count, c.byteStride);
    else if (c.filter == Filter::Exponential)
        meshopt_decodeFilterExp(out, c.count, c.byteStride);
    return {};
}

/// The view's compression extension (EXT_ or KHR_), or null; both at once is refused.
Result<const char*> extensionOf(const tinygltf::BufferView& view, std::size_t v,
                                const Diagnostics& diag) {
    const char* found = nullptr;
    for (const char* name : kMeshoptExtensions)
        if (extension(view.extensions, name)) {
            if (found)
                return diag.error(at("bufferViews", v) + ".extensions",
                                  "has both EXT_meshopt_compression and KHR_meshopt_compression");
            found = name;
        }
    return found;
}

/// Whether view `v`'s uncompressed fallback may replace its decoded data when it cannot be
/// decoded: the extension is only used (not in extensionsRequired) and the view's own buffer
/// holds data (it is not a placeholder).
bool mayFallBack(const tinygltf::Model& model, const tinygltf::BufferView& view, const char* name,
                 const RawFacts& raw) {
    const auto& required = model.extensionsRequired;
    return std::find(required.begin(), required.end(), name) == required.end() &&
           !raw.placeholderBuffers.count(view.buffer);
}

/// The warning for a view read from its fallback data instead: why it was not decoded.
void warnFallback(const tinygltf::BufferView& view, const char* name, const Error& why,
                  const Diagnostics& diag) {
    diag.warn(why.object, why.message + "; " + name +
                              " is not required, so the view's uncompressed fallback data in " +
                              at("buffers", std::size_t(view.buffer)) + " is used");
}

/// Every compressed view, checked; views into placeholders that are not compressed are refused.
/// A view whose extension breaks a rule, when it may fall back, is left to read its fallback.
Result<std::vector<Compressed>> compressedViews(const tinygltf::Model& model, const RawFacts& raw,
                                                const Diagnostics& diag) {
    std::vector<Compressed> out;
    for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
        const tinygltf::BufferView& view = model.bufferViews[v];
        auto name = extensionOf(view, v, diag);
        if (!name) return std::move(name).error();
        auto placeholder = raw.placeholderBuffers.find(view.buffer);
        if (!*name) {
            if (placeholder != raw.placeholderBuffers.end())
                return diag.error(at("bufferViews", v),
                                  "refers to " + at("buffers", std::size_t(view.buffer)) +
                                      ", a meshopt fallback buffer without data, but is not "
                                      "compressed (its data exists nowhere)");
            continue;
        }
        if (placeholder != raw.placeholderBuffers.end() &&
            (view.byteOffset > placeholder->second ||
             view.byteLength > placeholder->second - view.byteOffset))
            return diag.error(at("bufferViews", v),
                              "byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                                  std::to_string(view.byteLength) + " exceeds the byteLength " +
                                  std::to_string(placeholder->second) + " of " +
                                  at("buffers", std::size_t(view.buffer)));
        auto c = readCompressed(model, v, *name, *extension(view.extensions, *name), raw, diag);
        if (!c) {
            if (!mayFallBack(model, view, *name, raw)) return std::move(c).error();
            warnFallback(view, *name, c.error(), diag);
            continue;
        }
        c->name = *name;
        out.push_back(std::move(*c));
    }
    return out;
}

/// Accessors over a filtered view must read it as the filter writes it: OCTAHEDRAL signed
/// normalized components of byteStride/4 bytes, QUATERNION SHORT, EXPONENTIAL FLOAT.
Result<void> checkFilteredReads(const tinygltf::Model& model, const std::vector<Compressed>& views,
                                const Diagnostics& diag) {
    std::map<int, const Compressed*> filtered;
    for (const Compressed& c : views)
        if (c.filter != Filter::None) filtered[c.view] = &c;
    if (filtered.empty()) return {};
    for (std::size_t i = 0; i < model.accessors.size(); ++i) {
        const tinygltf::Accessor& a = model.accessors[i];
        auto it = filtered.find(a.bufferView);
        if (it == filtered.end()) continue;
        const Compressed& c = *it->second;
        const int type = a.componentType;
        const bool ok =
            (c.filter == Filter::Octahedral &&
             (c.byteStride == 4 ? type == kByte : type == kShort)) ||
            (c.filter == Filter::Quaternion && type == kShort) ||
            (c.filter == Filter::Exponential && type == kFloat);
        if (!ok)
            return diag.error(at("accessors", i),
                              "reads " + at("bufferViews", std::size_t(c.view)) + ", decoded by the " +
                                  c.filterName + " filter with byteStride " +
                                  std::to_string(c.byteStride) + ", as " +
                                  componentTypeName(type) + " (expected " +
                                  (c.filter == Filter::Exponential ? "FLOAT"
                                   : c.filter == Filter::Quaternion || c.byteStride == 8
                                       ? "SHORT"
                                       : "BYTE") +
                                  ")");
    }
    return {};
}

} // namespace

Result<void> decodeMeshopt(tinygltf::Model& model, const RawFacts& raw, const Diagnostics& diag) {
    auto views = compressedViews(model, raw, diag);
    if (!views) return std::move(views).error();
    if (views->empty()) return {};
    LANTERN_TRY(checkFilteredReads(model, *views, diag));
    // One buffer for every decoded view. Each view keeps its offset modulo 16 so that accessor
    // alignment is judged as in the file.
    std::vector<std::size_t> offsets;
    std::size_t total = 0;
    for (const Compressed& c : *views) {
        const std::size_t bytes = c.byteStride * c.count;
        const std::size_t offset = ((total + 15) & ~std::size_t(15)) +
                                   model.bufferViews[std::size_t(c.view)].byteOffset % 16;
        // Charged with its alignment padding, before the decoded buffer is allocated.
        LANTERN_TRY(diag.charge(offset - total + std::uint64_t(bytes), 1, c.object,
                                "decoding the compressed view"));
        offsets.push_back(offset);
        total = offset + bytes;
    }
    std::vector<unsigned char> decoded(total, 0);
    std::vector<bool> fellBack(views->size(), false);
    for (std::size_t k = 0; k < views->size(); ++k) {
        const Compressed& c = (*views)[k];
        auto done = decode(model, c, decoded.data() + offsets[k], diag);
        if (done) continue;
        const tinygltf::BufferView& view = model.bufferViews[std::size_t(c.view)];
        if (!mayFallBack(model, view, c.name, raw)) return std::move(done).error();
        warnFallback(view, c.name, done.error(), diag);
        fellBack[k] = true;
    }
    const int buffer = addDecodedBuffer(model, std::move(decoded));
    for (std::size_t k = 0; k < views->size(); ++k) {
        if (fellBack[k]) continue;
        tinygltf::BufferView& view = model.bufferViews[std::size_t((*views)[k].view)];
        view.buffer = buffer;
        view.byteOffset = offsets[k];
    }
    return {};
}

} // namespace lantern::gltf
