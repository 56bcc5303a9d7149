// KHR_draco_mesh_compression: primitives whose attributes and indices draco::Decoder decodes from
// a buffer view. The accessors they name (usually without a bufferView) are pointed at the
// decoded data, so that every later pass reads them like any other accessor. Counts are checked
// against the accessors twice: from the stream's header before decoding (GltfDracoHeader.cpp),
// so that a lying stream cannot make the decoder allocate beyond what the accessors declare (and
// the budget allows), and from the decoded mesh after.
#include "io/gltf/GltfInternal.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cstring>

namespace lantern::gltf {
namespace {

/// A primitive's extension, read and checked against the primitive.
struct DracoPrimitive {
    std::string primitive; ///< "meshes[m].primitives[p]"
    std::string object;    ///< primitive + ".extensions.KHR_draco_mesh_compression"
    int bufferView = -1;
    struct Attribute {
        std::string name;
        int id = 0;       ///< the attribute's unique id in the Draco stream
        int accessor = 0; ///< the primitive's accessor for it
    };
    std::vector<Attribute> attributes;
    int indices = -1;
};

/// Which Draco stream an accessor was filled from: (bufferView, unique id; -1 for indices).
using Filled = std::map<int, std::pair<int, int>>;

/// An accessor to fill: with the attribute of unique id `id`, or the indices (id -1).
struct Target {
    int accessor = 0, id = -1;
    std::string object; ///< the primitive's attribute or indices, for messages
};

Result<DracoPrimitive> readExtension(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                     const tinygltf::Value& ext, std::string primitive,
                                     const Diagnostics& diag) {
    DracoPrimitive d;
    d.primitive = std::move(primitive);
    d.object = d.primitive + ".extensions.KHR_draco_mesh_compression";
    if (!ext.IsObject()) return diag.error(d.object, "is not an object");
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        return diag.error(d.object, "the primitive's mode must be TRIANGLES or TRIANGLE_STRIP, "
                                    "not " + std::to_string(prim.mode));
    const tinygltf::Value& view = ext.Get("bufferView");
    if (!view.IsInt()) return diag.error(d.object + ".bufferView", "is missing or not an integer");
    d.bufferView = view.GetNumberAsInt();
    if (d.bufferView < 0 || std::size_t(d.bufferView) >= model.bufferViews.size())
        return diag.error(d.object + ".bufferView",
                          "bufferView " + std::to_string(d.bufferView) +
                              " does not exist (the file has " +
                              std::to_string(model.bufferViews.size()) + ")");
    const tinygltf::Value& attributes = ext.Get("attributes");
    if (!attributes.IsObject())
        return diag.error(d.object + ".attributes", "is missing or not an object");
    for (const std::string& name : attributes.Keys()) {
        const std::string aobj = d.object + ".attributes." + name;
        const tinygltf::Value& id = attributes.Get(name);
        if (!id.IsInt() || id.GetNumberAsInt() < 0)
            return diag.error(aobj, "is not a non-negative integer");
        auto it = prim.attributes.find(name);
        if (it == prim.attributes.end())
            return diag.error(aobj, "the primitive has no " + name +
                                        " attribute (the extension's are a subset of its own)");
        if (it->second < 0 || std::size_t(it->second) >= model.accessors.size())
            return diag.error(aobj, "the primitive's accessor " + std::to_string(it->second) +
                                        " does not exist");
        d.attributes.push_back({name, id.GetNumberAsInt(), it->second});
    }
    if (d.attributes.empty()) return diag.error(d.object + ".attributes", "is empty");
    // POSITION first: the counts are reported against it (the JSON's keys come sorted).
    std::stable_partition(d.attributes.begin(), d.attributes.end(),
                          [](const DracoPrimitive::Attribute& a) { return a.name == "POSITION"; });
    d.indices = prim.indices;
    if (d.indices >= 0 && std::size_t(d.indices) >= model.accessors.size())
        return diag.error(d.object, "the primitive's indices accessor " +
                                        std::to_string(d.indices) + " does not exist");
    return d;
}

/// The bytes an accessor holds once filled (count x element size); checks its type first.
Result<std::size_t> accessorBytes(const tinygltf::Model& model, int index, bool indices,
                                  const std::string& object, const Diagnostics& diag) {
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    const std::string name = at("accessors", std::size_t(index));
    const bool typeOk =
        indices ? a.type == TINYGLTF_TYPE_SCALAR &&
                      (a.componentType == kUnsignedByte || a.componentType == kUnsignedShort ||
                       a.componentType == kUnsignedInt)
                : componentCount(a.type) >= 1 && componentCount(a.type) <= 4 &&
                      componentSize(a.componentType) != 0;
    if (!typeOk)
        return diag.error(object, name + " is " + typeName(a.type) + " of " +
                                      componentTypeName(a.componentType) + ", which cannot hold " +
                                      (indices ? "Draco indices (UNSIGNED_BYTE/SHORT/INT scalars)"
                                               : "a Draco attribute (scalars or vectors)"));
    if (a.count == 0) return diag.error(name + ".count", "must be >= 1");
    return a.count * elementSize(a.type, a.componentType);
}

/// The accessors this primitive fills (those another primitive filled from the same stream are
/// left as they are); refuses an accessor filled from two different streams.
Result<std::vector<Target>> accessorsToFill(const DracoPrimitive& d, const Filled& filled,
                                            const Diagnostics& diag) {
    std::vector<Target> out;
    auto add = [&](int accessor, int id, const std::string& what) -> Result<void> {
        auto it = filled.find(accessor);
        if (it == filled.end()) {
            out.push_back({accessor, id,
                           d.primitive + (id < 0 ? ".indices" : ".attributes." + what)});
            return {};
        }
        if (it->second != std::pair{d.bufferView, id})
            return diag.error(d.object, at("accessors", std::size_t(accessor)) + " (" + what +
                                            ") is also filled from another Draco stream");
        return {};
    };
    for (const auto& a : d.attributes)
        LANTERN_TRY(add(a.accessor, a.id, a.name));
    if (d.indices >= 0) LANTERN_TRY(add(d.indices, -1, "indices"));
    return out;
}

/// The header's counts against the accessors, before the decoder allocates for them.
Result<void> checkHeaderCounts(const tinygltf::Model& model, const DracoPrimitive& d,
                               const DracoHeader& h, const Diagnostics& diag) {
    const tinygltf::Accessor& first = model.accessors[std::size_t(d.attributes[0].accessor)];
    const std::string firstName = at("accessors", std::size_t(d.attributes[0].accessor)) + " (" +
                                  d.attributes[0].name + ")";
    const std::uint64_t corners = 3 * h.faces;
    if (d.indices >= 0 && corners != model.accessors[std::size_t(d.indices)].count)
        return diag.error(d.object, "the Draco stream has " + std::to_string(h.faces) +
                                        " triangles (" + std::to_string(corners) + " indices) but " +
                                        at("accessors", std::size_t(d.indices)) +
                                        " (indices) has count " +
                                        std::to_string(model.accessors[std::size_t(d.indices)].count));
    if (d.indices < 0 && corners != first.count)
        return diag.error(d.object, "the Draco stream has " + std::to_string(h.faces) +
                                        " triangles for a primitive without indices whose " +
                                        firstName + " has count " + std::to_string(first.count));
    if (!h.edgebreaker && h.vertices != first.count)
        return diag.error(d.object, "the Draco stream has " + std::to_string(h.vertices) +
                                        " points but " + firstName + " has count " +
                                        std::to_string(first.count));
    return {};
}

int dracoComponentType(draco::DataType type) {
    switch (type) {
    case draco::DT_INT8:
        return kByte;
    case draco::DT_UINT8:
        return kUnsignedByte;
    case draco::DT_INT16:
        return kShort;
    case draco::DT_UINT16:
        return kUnsignedShort;
    case draco::DT_UINT32:
        return kUnsignedInt;
    case draco::DT_FLOAT32:
        return kFloat;
    default:
        return 0;
    }
}

/// Converts every point's value of `att` to T (Draco's conversion, range-checked) into `out`.
template <typename T>
bool convertAll(const draco::PointAttribute& att, std::size_t points, int components,
                unsigned char* out) {
    T value[4];
    for (std::size_t i = 0; i < points; ++i) {
        const draco::AttributeValueIndex avi = att.mapped_index(draco::PointIndex(std::uint32_t(i)));
        if (avi.value() >= att.size() ||
            !att.ConvertValue<T>(avi, std::int8_t(components), value))
            return false;
        std::memcpy(out + i * sizeof(T) * std::size_t(components), value,
                    sizeof(T) * std::size_t(components));
    }
    return true;
}

/// One attribute's values for every point, as the accessor's component type.
Result<void> writeAttribute(const draco::Mesh& mesh, const tinygltf::Accessor& a, int id,
                            const std::string& object, unsigned char* out,
                            const Diagnostics& diag) {
    const draco::PointAttribute* att = mesh.GetAttributeByUniqueId(std::uint32_t(id));
    if (!att) return diag.error(object, "attribute id " + std::to_string(id) +
                                            " is not in the Draco data");
    const int components = componentCount(a.type);
    if (att->num_components() != components)
        return diag.error(object, "the Draco attribute has " +
                                      std::to_string(att->num_components()) +
                                      " components but its accessor is " + typeName(a.type));
    bool ok = false;
    switch (a.componentType) {
    case kByte:
        ok = convertAll<std::int8_t>(*att, a.count, components, out);
        break;
    case kUnsignedByte:
        ok = convertAll<std::uint8_t>(*att, a.count, components, out);
        break;
    case kShort:
        ok = convertAll<std::int16_t>(*att, a.count, components, out);
        break;
    case kUnsignedShort:
        ok = convertAll<std::uint16_t>(*att, a.count, components, out);
        break;
    case kUnsignedInt:
        ok = convertAll<std::uint32_t>(*att, a.count, components, out);
        break;
    default:
        ok = convertAll<float>(*att, a.count, components, out);
        break;
    }
    if (!ok)
        return diag.error(object, "the Draco attribute's values (" +
                                      componentTypeName(dracoComponentType(att->data_type())) +
                                      ") cannot be converted to its accessor's " +
                                      componentTypeName(a.componentType));
    return {};
}

/// The triangles as indices of the accessor's component type.
Result<void> writeIndices(const draco::Mesh& mesh, int componentType, const std::string& object,
                          unsigned char* out, const Diagnostics& diag) {
    const int bytes = componentSize(componentType);
    const std::uint64_t limit = (std::uint64_t(1) << (8 * bytes)) - 1;
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t index = mesh.face(f)[j].value();
            if (index > limit)
                return diag.error(object, "index " + std::to_string(index) + " does not fit " +
                                              componentTypeName(componentType));
            std::memcpy(out, &index, std::size_t(bytes)); // little-endian, as glTF
            out += bytes;
        }
    return {};
}

/// Without an indices accessor, the triangles must be the points in order.
Result<void> checkPointOrder(const draco::Mesh& mesh, const std::string& object,
                             const Diagnostics& diag) {
    std::uint32_t next = 0;
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int j = 0; j < 3; ++j)
            if (mesh.face(f)[j].value() != next++)
                return diag.error(object, "the Draco triangles do not take the points in order, "
                                          "and the primitive has no indices accessor to hold them");
    return {};
}

Result<std::unique_ptr<draco::Mesh>> decodeStream(const unsigned char* data, std::size_t size,
                                                  const std::string& object,
                                                  const Diagnostics& diag) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        return diag.error(object, "the Draco data cannot be decoded: " +
                                      decoded.status().error_msg_string());
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) return diag.error(object, "the Draco data holds no mesh");
    return mesh;
}

/// The decoded mesh's counts against the accessors it fills.
Result<void> checkDecodedCounts(const tinygltf::Model& model, const DracoPrimitive& d,
                                const draco::Mesh& mesh, const Diagnostics& diag) {
    if (d.indices >= 0 &&
        3 * std::uint64_t(mesh.num_faces()) != model.accessors[std::size_t(d.indices)].count)
        return diag.error(d.object, "the decoded mesh has " + std::to_string(mesh.num_faces()) +
                                        " triangles but " + at("accessors", std::size_t(d.indices)) +
                                        " (indices) has count " +
                                        std::to_string(model.accessors[std::size_t(d.indices)].count));
    for (const auto& a : d.attributes) {
        const std::size_t count = model.accessors[std::size_t(a.accessor)].count;
        if (mesh.num_points() != count)
            return diag.error(d.object, "the decoded mesh has " +
                                            std::to_string(mesh.num_points()) + " points but " +
                                            at("accessors", std::size_t(a.accessor)) + " (" +
                                            a.name + ") has count " + std::to_string(count));
    }
    if (d.indices < 0) LANTERN_TRY(checkPointOrder(mesh, d.object, diag));
    return {};
}

/// Writes the accessors' data into one decoded buffer and points each accessor at a view of it.
Result<void> fill(tinygltf::Model& model, const draco::Mesh& mesh,
                  const std::vector<Target>& targets, const Diagnostics& diag) {
    std::vector<std::size_t> offsets;
    std::size_t total = 0;
    for (const Target& t : targets) {
        const tinygltf::Accessor& a = model.accessors[std::size_t(t.accessor)];
        offsets.push_back(total);
        total += (a.count * elementSize(a.type, a.componentType) + 3) & ~std::size_t(3);
    }
    std::vector<unsigned char> data(total, 0);
    for (std::size_t k = 0; k < targets.size(); ++k) {
        const Target& t = targets[k];
        const tinygltf::Accessor& a = model.accessors[std::size_t(t.accessor)];
        if (t.id < 0)
            LANTERN_TRY(writeIndices(mesh, a.componentType, t.object, data.data() + offsets[k], diag));
        else
            LANTERN_TRY(writeAttribute(mesh, a, t.id, t.object, data.data() + offsets[k], diag));
    }
    const int buffer = addDecodedBuffer(model, std::move(data));
    for (std::size_t k = 0; k < targets.size(); ++k) {
        tinygltf::Accessor& a = model.accessors[std::size_t(targets[k].accessor)];
        tinygltf::BufferView view;
        view.name = "(decoded)";
        view.buffer = buffer;
        view.byteOffset = offsets[k];
        view.byteLength = a.count * elementSize(a.type, a.componentType);
        model.bufferViews.push_back(view);
        a.bufferView = int(model.bufferViews.size()) - 1;
        a.byteOffset = 0;
    }
    return {};
}

Result<void> decodePrimitive(tinygltf::Model& model, const DracoPrimitive& d, Filled& filled,
                             const Diagnostics& diag) {
    auto targets = accessorsToFill(d, filled, diag);
    if (!targets) return std::move(targets).error();
    if (targets->empty()) return {}; // another primitive decoded the same stream into them
    std::uint64_t bytes = 0;
    for (const Target& t : *targets) {
        auto n = accessorBytes(model, t.accessor, t.id < 0, t.object, diag);
        if (!n) return std::move(n).error();
        bytes += *n;
    }
    LANTERN_TRY(diag.charge(bytes, 1, d.object, "decoding the Draco stream"));
    LANTERN_TRY(checkBufferView(model, d.bufferView, diag));
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(d.bufferView)];
    const unsigned char* data = model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset;
    auto header = readDracoHeader(data, view.byteLength, d.object, diag);
    if (!header) return std::move(header).error();
    LANTERN_TRY(checkHeaderCounts(model, d, *header, diag));
    auto mesh = decodeStream(data, view.byteLength, d.object, diag);
    if (!mesh) return std::move(mesh).error();
    LANTERN_TRY(checkDecodedCounts(model, d, **mesh, diag));
    LANTERN_TRY(fill(model, **mesh, *targets, diag));
    for (const Target& t : *targets)
        filled[t.accessor] = {d.bufferView, t.id};
    return {};
}

/// Whether a primitive whose Draco data cannot be decoded may be read from its accessors' own
/// data: the extension is only used (not in extensionsRequired) and every accessor the
/// primitive names has a bufferView (the uncompressed fallback the extension asks for then).
bool mayFallBack(const tinygltf::Model& model, const tinygltf::Primitive& prim) {
    const auto& required = model.extensionsRequired;
    if (std::find(required.begin(), required.end(), "KHR_draco_mesh_compression") !=
        required.end())
        return false;
    auto hasData = [&](int accessor) {
        return accessor >= 0 && std::size_t(accessor) < model.accessors.size() &&
               model.accessors[std::size_t(accessor)].bufferView >= 0;
    };
    for (const auto& [name, accessor] : prim.attributes)
        if (!hasData(accessor)) return false;
    return prim.indices < 0 || hasData(prim.indices);
}

} // namespace

void restoreDracoIndices(tinygltf::Model& model, const RawFacts& raw) {
    for (const auto& [where, indices] : raw.dracoIndices) {
        const auto [m, p] = where;
        // One tinygltf primitive per JSON primitive (inspectJson refuses any it would drop).
        if (std::size_t(m) < model.meshes.size() &&
            std::size_t(p) < model.meshes[std::size_t(m)].primitives.size())
            model.meshes[std::size_t(m)].primitives[std::size_t(p)].indices = indices;
    }
}

Result<void> decodeDraco(tinygltf::Model& model, const Diagnostics& diag) {
    Filled filled;
    for (std::size_t m = 0; m < model.meshes.size(); ++m)
        for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            const tinygltf::Primitive& prim = model.meshes[m].primitives[p];
            const tinygltf::Value* ext = extension(prim.extensions, "KHR_draco_mesh_compression");
            if (!ext) continue;
            auto d = readExtension(model, prim, *ext, at("meshes", m) + "." + at("primitives", p),
                                   diag);
            auto decoded = d ? decodePrimitive(model, *d, filled, diag)
                             : Result<void>(std::move(d).error());
            if (decoded) continue;
            // Nothing of the model is changed by a primitive that fails (fill() comes last).
            if (!mayFallBack(model, prim)) return decoded;
            diag.warn(decoded.error().object,
                      decoded.error().message +
                          "; KHR_draco_mesh_compression is not required, so the primitive's "
                          "uncompressed accessors are read instead");
        }
    return {};
}

} // namespace lantern::gltf
