// glTF accessors: layout checks (component types, alignment, strides, bounds within the buffer
// view, sparse parts) and bounds-checked reading with glTF's normalisation rules. Every read
// re-derives and re-checks the layout, so no path reads outside a buffer.
#include "io/gltf/GltfInternal.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace lantern::gltf {
namespace {


int matrixRows(int type) {
    switch (type) {
    case TINYGLTF_TYPE_MAT2:
        return 2;
    case TINYGLTF_TYPE_MAT3:
        return 3;
    case TINYGLTF_TYPE_MAT4:
        return 4;
    default:
        return 0;
    }
}

/// Where an accessor's elements lie, after every check.
struct Layout {
    const unsigned char* data = nullptr; ///< first element; null: all zeros (no bufferView)
    std::size_t count = 0, stride = 0, elementBytes = 0;
    int componentType = 0, components = 0, componentBytes = 0, rows = 0;
    bool normalized = false;

    /// Byte offset of component c inside an element (matrix columns are 4-byte aligned).
    std::size_t componentOffset(int c) const {
        if (rows == 0) return std::size_t(c) * std::size_t(componentBytes);
        const std::size_t column = (std::size_t(rows) * componentBytes + 3) & ~std::size_t(3);
        return std::size_t(c / rows) * column + std::size_t(c % rows) * componentBytes;
    }
};

/// True when `count` items of `itemBytes`, spaced `stride` apart, fit into `available` bytes
/// from `offset` (no overflow for any input).
bool fits(std::size_t offset, std::size_t count, std::size_t stride, std::size_t itemBytes,
          std::size_t available) {
    if (count == 0) return offset <= available;
    if (offset > available || itemBytes > available - offset) return false;
    return count - 1 <= (available - offset - itemBytes) / (stride == 0 ? 1 : stride);
}

/// Checks buffer view `v` itself (buffer in range, inside the buffer).
Result<const tinygltf::BufferView*> bufferView(const tinygltf::Model& model, int v,
                                               const std::string& object, const Diagnostics& diag) {
    if (v < 0 || std::size_t(v) >= model.bufferViews.size())
        return diag.error(object, "bufferView " + std::to_string(v) +
                                      " does not exist (the file has " +
                                      std::to_string(model.bufferViews.size()) + ")");
    const tinygltf::BufferView& bv = model.bufferViews[std::size_t(v)];
    const std::string name = at("bufferViews", std::size_t(v));
    if (bv.buffer < 0 || std::size_t(bv.buffer) >= model.buffers.size())
        return diag.error(name + ".buffer",
                          "buffer " + std::to_string(bv.buffer) + " does not exist");
    const std::size_t size = model.buffers[std::size_t(bv.buffer)].data.size();
    if (bv.byteLength == 0) return diag.error(name + ".byteLength", "must be >= 1");
    if (!fits(bv.byteOffset, 1, 0, bv.byteLength, size))
        return diag.error(name, "byteOffset " + std::to_string(bv.byteOffset) + " + byteLength " +
                                    std::to_string(bv.byteLength) + " exceeds the " +
                                    std::to_string(size) + " bytes of " +
                                    at("buffers", std::size_t(bv.buffer)));
    if (bv.byteStride != 0) {
        if (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4 != 0)
            return diag.error(name + ".byteStride", std::to_string(bv.byteStride) +
                                                        " is not a multiple of 4 in [4, 252]");
        if (bv.byteStride > bv.byteLength)
            return diag.error(name + ".byteStride", std::to_string(bv.byteStride) +
                                                        " is larger than the byteLength " +
                                                        std::to_string(bv.byteLength));
        if (bv.target == TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER)
            return diag.error(name + ".byteStride",
                              "index data (target ELEMENT_ARRAY_BUFFER) must be tightly packed");
    }
    return &bv;
}

Result<Layout> locate(const tinygltf::Model& model, int index, const Diagnostics& diag) {
    const std::string name = at("accessors", std::size_t(index));
    if (index < 0 || std::size_t(index) >= model.accessors.size())
        return diag.error(name, "accessor does not exist (the file has " +
                                    std::to_string(model.accessors.size()) + ")");
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    Layout l;
    l.componentType = a.componentType;
    l.componentBytes = componentSize(a.componentType);
    l.components = componentCount(a.type);
    l.rows = matrixRows(a.type);
    l.count = a.count;
    l.normalized = a.normalized;
    if (l.componentBytes == 0)
        return diag.error(name + ".componentType",
                          std::to_string(a.componentType) + " is not a glTF component type");
    if (l.components == 0) return diag.error(name + ".type", "is not a glTF accessor type");
    if (a.normalized && (a.componentType == kFloat || a.componentType == kUnsignedInt))
        return diag.error(name + ".normalized",
                          "only BYTE, UNSIGNED_BYTE, SHORT and UNSIGNED_SHORT may be normalized, "
                          "not " +
                              componentTypeName(a.componentType));
    if (a.count == 0) return diag.error(name + ".count", "must be >= 1");
    l.elementBytes = elementSize(a.type, a.componentType);
    l.stride = l.elementBytes;
    if (a.bufferView < 0) {
        if (a.byteOffset != 0)
            return diag.error(name + ".byteOffset", "is given without a bufferView");
        return l;
    }
    auto bv = bufferView(model, a.bufferView, name + ".bufferView", diag);
    if (!bv) return std::move(bv).error();
    const tinygltf::BufferView& view = **bv;
    const std::string viewName = at("bufferViews", std::size_t(a.bufferView));
    if (view.byteStride != 0) {
        if (view.byteStride < l.elementBytes)
            return diag.error(name, "byteStride " + std::to_string(view.byteStride) + " of " +
                                        viewName + " is smaller than the element size " +
                                        std::to_string(l.elementBytes));
        if (view.byteStride % std::size_t(l.componentBytes) != 0)
            return diag.error(name, "byteStride " + std::to_string(view.byteStride) + " of " +
                                        viewName + " is not a multiple of the component size " +
                                        std::to_string(l.componentBytes));
        l.stride = view.byteStride;
    }
    if (a.byteOffset % std::size_t(l.componentBytes) != 0 ||
        (view.byteOffset + a.byteOffset) % std::size_t(l.componentBytes) != 0)
        return diag.error(name + ".byteOffset",
                          "data is not aligned to its " + std::to_string(l.componentBytes) +
                              "-byte components (byteOffset " + std::to_string(a.byteOffset) +
                              ", bufferView byteOffset " + std::to_string(view.byteOffset) + ")");
    if (!fits(a.byteOffset, a.count, l.stride, l.elementBytes, view.byteLength))
        return diag.error(
            name, std::to_string(a.count) + " elements of " + std::to_string(l.elementBytes) +
                      " bytes (stride " + std::to_string(l.stride) + ") from byteOffset " +
                      std::to_string(a.byteOffset) + " run past the end of " + viewName +
                      " (byteLength " + std::to_string(view.byteLength) + ")");
    l.data = model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
    return l;
}

/// The sparse parts' layout: indices and values, after every check.
struct SparseLayout {
    const unsigned char* indices = nullptr;
    const unsigned char* values = nullptr;
    std::size_t count = 0;
    int indexType = 0, indexBytes = 0;
};

Result<SparseLayout> locateSparse(const tinygltf::Model& model, int index, const Layout& l,
                                  const Diagnostics& diag) {
    const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
    const std::string name = at("accessors", std::size_t(index)) + ".sparse";
    SparseLayout s;
    if (a.sparse.count < 1 || std::size_t(a.sparse.count) > a.count)
        return diag.error(name + ".count", std::to_string(a.sparse.count) + " is outside [1, " +
                                               std::to_string(a.count) + "]");
    s.count = std::size_t(a.sparse.count);
    s.indexType = a.sparse.indices.componentType;
    if (s.indexType != kUnsignedByte && s.indexType != kUnsignedShort &&
        s.indexType != kUnsignedInt)
        return diag.error(name + ".indices.componentType",
                          "must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, not " +
                              componentTypeName(s.indexType));
    s.indexBytes = componentSize(s.indexType);
    struct Part {
        int view, offset;
        std::size_t itemBytes;
        const char* what;
        const unsigned char** out;
    };
    for (const Part& p : {Part{a.sparse.indices.bufferView, a.sparse.indices.byteOffset,
                               std::size_t(s.indexBytes), "indices", &s.indices},
                          Part{a.sparse.values.bufferView, a.sparse.values.byteOffset,
                               l.elementBytes, "values", &s.values}}) {
        const std::string part = name + "." + p.what;
        auto bv = bufferView(model, p.view, part + ".bufferView", diag);
        if (!bv) return std::move(bv).error();
        if (p.offset < 0) return diag.error(part + ".byteOffset", "must be >= 0");
        if (!fits(std::size_t(p.offset), s.count, p.itemBytes, p.itemBytes, (*bv)->byteLength))
            return diag.error(part, std::to_string(s.count) + " " + p.what + " of " +
                                        std::to_string(p.itemBytes) + " bytes from byteOffset " +
                                        std::to_string(p.offset) + " run past the end of " +
                                        at("bufferViews", std::size_t(p.view)));
        *p.out = model.buffers[std::size_t((*bv)->buffer)].data.data() + (*bv)->byteOffset +
                 std::size_t(p.offset);
    }
    return s;
}

double decode(const unsigned char* p, int type, bool normalized) {
    switch (type) {
    case kFloat: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
    }
    case kUnsignedByte:
        return normalized ? p[0] / 255.0 : p[0];
    case kByte: {
        const auto v = std::int8_t(p[0]);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedShort: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case kShort: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedInt: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default:
        return 0.0;
    }
}

std::uint32_t decodeIndex(const unsigned char* p, int type) {
    return std::uint32_t(decode(p, type, false));
}

template <typename T>
Result<std::vector<T>> readNumbers(const tinygltf::Model& model, int index,
                                   const std::string& object, const Diagnostics& diag) {
    auto located = locate(model, index, diag);
    if (!located) return std::move(located).error();
    const Layout& l = *located;
    const std::string name = at("accessors", std::size_t(index));
    const std::size_t nc = std::size_t(l.components);
    LANTERN_TRY(diag.charge(std::uint64_t(l.count) * nc, sizeof(T), object,
                            "reading " + name));
    std::vector<T> out(l.count * nc, T(0));
    auto readElement = [&](const unsigned char* element, std::size_t k) -> Result<void> {
        for (std::size_t c = 0; c < nc; ++c) {
            const double v =
                decode(element + l.componentOffset(int(c)), l.componentType, l.normalized);
            if (!std::isfinite(v))
                return diag.error(name, "element " + std::to_string(k) + " component " +
                                            std::to_string(c) + " is not a finite number (" +
                                            (std::isnan(v) ? "NaN" : "infinite") +
                                            (object == name ? ")" : "; read as " + object + ")"));
            out[k * nc + c] = T(v);
        }
        return {};
    };
    if (l.data)
        for (std::size_t k = 0; k < l.count; ++k)
            LANTERN_TRY(readElement(l.data + k * l.stride, k));
    if (model.accessors[std::size_t(index)].sparse.isSparse) {
        auto sparse = locateSparse(model, index, l, diag);
        if (!sparse) return std::move(sparse).error();
        const SparseLayout& s = *sparse;
        std::uint64_t previous = 0;
        for (std::size_t i = 0; i < s.count; ++i) {
            const std::uint32_t target =
                decodeIndex(s.indices + i * std::size_t(s.indexBytes), s.indexType);
            if (target >= l.count)
                return diag.error(name + ".sparse.indices", "index " + std::to_string(target) +
                                                                " (entry " + std::to_string(i) +
                                                                ") is out of range (count " +
                                                                std::to_string(l.count) + ")");
            if (i > 0 && target <= previous)
                return diag.error(name + ".sparse.indices",
                                  "indices are not strictly increasing at entry " +
                                      std::to_string(i));
            previous = target;
            LANTERN_TRY(readElement(s.values + i * l.elementBytes, target));
        }
    }
    return out;
}

} // namespace

int componentSize(int componentType) {
    switch (componentType) {
    case kByte:
    case kUnsignedByte:
        return 1;
    case kShort:
    case kUnsignedShort:
        return 2;
    case kUnsignedInt:
    case kFloat:
        return 4;
    default:
        return 0; // INT (5124) and DOUBLE (5130) are not glTF 2.0 accessor types
    }
}

int componentCount(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return 1;
    case TINYGLTF_TYPE_VEC2:
        return 2;
    case TINYGLTF_TYPE_VEC3:
        return 3;
    case TINYGLTF_TYPE_VEC4:
        return 4;
    case TINYGLTF_TYPE_MAT2:
        return 4;
    case TINYGLTF_TYPE_MAT3:
        return 9;
    case TINYGLTF_TYPE_MAT4:
        return 16;
    default:
        return 0;
    }
}

std::size_t elementSize(int type, int componentType) {
    const int cs = componentSize(componentType), n = componentCount(type);
    if (cs == 0 || n == 0) return 0;
    const int rows = matrixRows(type);
    if (rows == 0) return std::size_t(cs * n);
    // Each matrix column starts on a 4-byte boundary (glTF 2.0, "Data Alignment").
    return std::size_t(rows) * ((std::size_t(rows) * std::size_t(cs) + 3) & ~std::size_t(3));
}

std::string componentTypeName(int componentType) {
    switch (componentType) {
    case kByte:
        return "BYTE";
    case kUnsignedByte:
        return "UNSIGNED_BYTE";
    case kShort:
        return "SHORT";
    case kUnsignedShort:
        return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT:
        return "INT";
    case kUnsignedInt:
        return "UNSIGNED_INT";
    case kFloat:
        return "FLOAT";
    default:
        return "componentType " + std::to_string(componentType);
    }
}

std::string typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    case TINYGLTF_TYPE_MAT2:
        return "MAT2";
    case TINYGLTF_TYPE_MAT3:
        return "MAT3";
    case TINYGLTF_TYPE_MAT4:
        return "MAT4";
    default:
        return "type " + std::to_string(type);
    }
}

Result<void> checkAccessor(const tinygltf::Model& model, int index, const LoadOptions& options,
                           const Diagnostics& diag) {
    auto located = locate(model, index, diag);
    if (!located) return std::move(located).error();
    const Layout& l = *located;
    if (!l.data) {
        // No buffer view: the elements are zeros the loader allocates, so `count` is bounded
        // here rather than by a buffer.
        if (l.count > options.maxBytes / l.elementBytes)
            return diag.error(at("accessors", std::size_t(index)),
                              std::to_string(l.count) + " elements of " +
                                  std::to_string(l.elementBytes) +
                                  " bytes without a bufferView exceed --max-size (" +
                                  std::to_string(options.maxBytes) + " bytes)");
    }
    if (model.accessors[std::size_t(index)].sparse.isSparse) {
        auto sparse = locateSparse(model, index, l, diag);
        if (!sparse) return std::move(sparse).error();
    }
    return {};
}

Result<void> checkBufferView(const tinygltf::Model& model, int index, const Diagnostics& diag) {
    auto bv = bufferView(model, index, at("bufferViews", std::size_t(index)), diag);
    if (!bv) return std::move(bv).error();
    return {};
}

Result<std::vector<float>> readFloats(const tinygltf::Model& model, int index,
                                      const std::string& object, const Diagnostics& diag) {
    return readNumbers<float>(model, index, object, diag);
}

Result<std::vector<double>> readDoubles(const tinygltf::Model& model, int index,
                                        const std::string& object, const Diagnostics& diag) {
    return readNumbers<double>(model, index, object, diag);
}

Result<std::vector<std::uint32_t>> readIndices(const tinygltf::Model& model, int index,
                                               std::size_t vertexCount, const std::string& object,
                                               const Diagnostics& diag) {
    auto located = locate(model, index, diag);
    if (!located) return std::move(located).error();
    const Layout& l = *located;
    if (l.components != 1 || l.normalized ||
        (l.componentType != kUnsignedByte && l.componentType != kUnsignedShort &&
         l.componentType != kUnsignedInt))
        return diag.error(object, "index accessor " + at("accessors", std::size_t(index)) +
                                      " must hold non-normalized UNSIGNED_BYTE, UNSIGNED_SHORT "
                                      "or UNSIGNED_INT scalars");
    // Sparse index accessors are legal: read them through the generic path.
    LANTERN_TRY(diag.charge(l.count, sizeof(std::uint32_t), object,
                            "reading " + at("accessors", std::size_t(index))));
    std::vector<std::uint32_t> out;
    if (model.accessors[std::size_t(index)].sparse.isSparse) {
        auto values = readNumbers<double>(model, index, object, diag);
        if (!values) return std::move(values).error();
        out.reserve(values->size());
        for (double v : *values)
            out.push_back(std::uint32_t(v));
    } else {
        out.resize(l.count, 0);
        if (l.data)
            for (std::size_t k = 0; k < l.count; ++k)
                out[k] = decodeIndex(l.data + k * l.stride, l.componentType);
    }
    // glTF forbids the primitive-restart value (all bits set) in index data.
    const std::uint32_t restart = l.componentType == kUnsignedByte    ? 0xFFu
                                  : l.componentType == kUnsignedShort ? 0xFFFFu
                                                                      : 0xFFFFFFFFu;
    for (std::size_t k = 0; k < out.size(); ++k) {
        if (out[k] == restart)
            return diag.error(object,
                              "index " + std::to_string(out[k]) + " (at position " +
                                  std::to_string(k) + ") is the primitive-restart value of " +
                                  componentTypeName(l.componentType) + ", which glTF forbids");
        if (out[k] >= vertexCount)
            return diag.error(object, "index " + std::to_string(out[k]) +
                                          " is out of range (vertex count " +
                                          std::to_string(vertexCount) + "; at position " +
                                          std::to_string(k) + ")");
    }
    return out;
}

} // namespace lantern::gltf
