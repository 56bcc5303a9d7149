// glTF meshes -> Lantern primitives: attributes read through the checked accessor readers,
// triangle strips and fans converted to lists (glTF's vertex order, so windings are kept),
// point and line modes skipped with a warning, and missing normals computed as angle-weighted
// averages of the faces sharing each vertex.
#include "io/GltfInternal.h"

namespace lantern::gltf {
namespace {

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS:
        return "POINTS";
    case TINYGLTF_MODE_LINE:
        return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
        return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
        return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES:
        return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
        return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
        return "TRIANGLE_FAN";
    default:
        return "?";
    }
}

/// The triangle list of a primitive given its vertex sequence (its indices, or 0..n-1).
/// Strip triangle i is (i, i+1+i%2, i+2-i%2) and fan triangle i is (i+1, i+2, 0), as glTF 2.0
/// specifies, which keeps every triangle's winding. A trailing partial triangle of a list is
/// dropped, as OpenGL's glDrawArrays/glDrawElements do.
std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& sequence) {
    const std::size_t n = sequence.size();
    std::vector<std::uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        out.assign(sequence.begin(), sequence.begin() + std::ptrdiff_t(n - n % 3));
    } else if (n >= 3) {
        out.reserve((n - 2) * 3);
        for (std::size_t i = 0; i + 2 < n; ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                out.push_back(sequence[i]);
                out.push_back(sequence[i + 1 + i % 2]);
                out.push_back(sequence[i + 2 - i % 2]);
            } else {
                out.push_back(sequence[i + 1]);
                out.push_back(sequence[i + 2]);
                out.push_back(sequence[0]);
            }
        }
    }
    return out;
}

template <typename Vec>
std::vector<Vec> toVectors(const std::vector<float>& flat, std::size_t components) {
    std::vector<Vec> out(flat.size() / components);
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t c = 0; c < components && c < std::size_t(Vec::length()); ++c)
            out[i][int(c)] = flat[i * components + c];
    return out;
}

/// Which TEXCOORD set the primitive's base-colour texture reads (0 without one).
int texcoordSet(const tinygltf::Model& model, int material) {
    if (material < 0) return 0;
    const tinygltf::TextureInfo& info =
        model.materials[std::size_t(material)].pbrMetallicRoughness.baseColorTexture;
    return info.index >= 0 ? info.texCoord : 0;
}

// The accessor of the primitive's attribute `name`, or -1.
int attributeAccessor(const tinygltf::Primitive& prim, const std::string& name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

// POSITION (accessor `positionAccessor`), and NORMAL, COLOR_0 and the TEXCOORD set of the
// material's base colour texture when the primitive has them.
Result<void> readAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                            int positionAccessor, const std::string& obj, const Diagnostics& diag,
                            Primitive& out) {
    auto attribute = [&](const std::string& name) { return attributeAccessor(prim, name); };
    auto positions = readFloats(model, positionAccessor, obj + ".attributes.POSITION", diag);
    if (!positions) return std::move(positions).error();
    out.positions = toVectors<glm::vec3>(*positions, 3);

    if (const int a = attribute("NORMAL"); a >= 0) {
        auto normals = readFloats(model, a, obj + ".attributes.NORMAL", diag);
        if (!normals) return std::move(normals).error();
        out.normals = toVectors<glm::vec3>(*normals, 3);
    }
    if (const int a = attribute("COLOR_0"); a >= 0) {
        auto colors = readFloats(model, a, obj + ".attributes.COLOR_0", diag);
        if (!colors) return std::move(colors).error();
        const std::size_t n = std::size_t(componentCount(model.accessors[std::size_t(a)].type));
        out.colors = toVectors<glm::vec4>(*colors, n);
        if (n == 3)
            for (glm::vec4& c : out.colors)
                c.w = 1.0f;
    }
    const int set = texcoordSet(model, prim.material);
    const std::string texcoordName = "TEXCOORD_" + std::to_string(set);
    if (const int a = attribute(texcoordName); a >= 0) {
        auto uv = readFloats(model, a, obj + ".attributes." + texcoordName, diag);
        if (!uv) return std::move(uv).error();
        out.texcoords = toVectors<glm::vec2>(*uv, 2);
    } else if (prim.material >= 0 && model.materials[std::size_t(prim.material)]
                                             .pbrMetallicRoughness.baseColorTexture.index >= 0) {
        diag.warn(obj + ".attributes", "no " + texcoordName +
                                           " for the material's base colour texture; the "
                                           "texture is not applied");
    }
    return {};
}

// The primitive's vertex sequence: its indices, or 0..vertexCount-1 without them.
Result<std::vector<std::uint32_t>> vertexSequence(const tinygltf::Model& model,
                                                  const tinygltf::Primitive& prim,
                                                  std::size_t vertexCount, const std::string& obj,
                                                  const Diagnostics& diag) {
    std::vector<std::uint32_t> sequence;
    if (prim.indices >= 0) {
        auto indices = readIndices(model, prim.indices, vertexCount, obj + ".indices", diag);
        if (!indices) return std::move(indices).error();
        sequence = std::move(*indices);
    } else {
        sequence.resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i)
            sequence[i] = std::uint32_t(i);
    }
    return sequence;
}

// One primitive as a triangle list; nothing (after a warning) when it is skipped: points and
// lines, no POSITION, or not one whole triangle.
Result<std::optional<Primitive>> convertPrimitive(const tinygltf::Model& model,
                                                  const tinygltf::Primitive& prim,
                                                  const std::string& obj, const Diagnostics& diag) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        diag.warn(obj + ".mode", std::string("mode ") + modeName(prim.mode) +
                                     " is not drawn (only triangles); primitive skipped");
        return std::optional<Primitive>();
    }
    const int positionAccessor = attributeAccessor(prim, "POSITION");
    if (positionAccessor < 0) {
        diag.warn(obj + ".attributes", "no POSITION; primitive skipped");
        return std::optional<Primitive>();
    }
    if (!prim.targets.empty())
        diag.warn(obj + ".targets", "morph targets are not supported; ignored");
    for (const char* unused : {"JOINTS_0", "WEIGHTS_0"})
        if (attributeAccessor(prim, unused) >= 0) {
            diag.warn(obj + ".attributes", "skinning is not supported; the mesh is drawn "
                                           "in its bind pose");
            break;
        }

    Primitive out;
    out.material = prim.material;
    LANTERN_TRY(readAttributes(model, prim, positionAccessor, obj, diag, out));
    auto sequence = vertexSequence(model, prim, out.positions.size(), obj, diag);
    if (!sequence) return std::move(sequence).error();
    const std::size_t given = sequence->size();
    out.indices = triangleList(prim.mode, *sequence);
    if (prim.mode == TINYGLTF_MODE_TRIANGLES && given % 3 != 0)
        diag.warn(obj, std::to_string(given) +
                           " vertices for TRIANGLES is not a multiple "
                           "of 3; the last " +
                           std::to_string(given % 3) + " are ignored");
    if (out.indices.empty()) {
        diag.warn(obj, std::string(modeName(prim.mode)) + " with " + std::to_string(given) +
                           " vertices has no triangle; primitive skipped");
        return std::optional<Primitive>();
    }
    // A plain non-indexed list needs no index buffer: draw the vertices in threes.
    if (prim.indices < 0 && prim.mode == TINYGLTF_MODE_TRIANGLES && given % 3 == 0)
        out.indices.clear();
    if (out.normals.empty()) out.normals = computeSmoothNormals(out.positions, out.indices);
    return std::optional<Primitive>(std::move(out));
}

} // namespace

Result<Mesh> convertMesh(const tinygltf::Model& model, std::size_t meshIndex,
                         const Diagnostics& diag) {
    const tinygltf::Mesh& src = model.meshes[meshIndex];
    Mesh mesh;
    mesh.name = src.name;
    if (src.primitives.empty()) diag.warn(at("meshes", meshIndex), "mesh has no primitives");
    if (!src.weights.empty())
        diag.warn(at("meshes", meshIndex) + ".weights",
                  "morph targets are not supported; the base mesh is drawn");
    for (std::size_t p = 0; p < src.primitives.size(); ++p) {
        const std::string obj = at("meshes", meshIndex) + "." + at("primitives", p);
        auto prim = convertPrimitive(model, src.primitives[p], obj, diag);
        if (!prim) return std::move(prim).error();
        if (*prim) mesh.primitives.push_back(std::move(**prim));
    }
    return mesh;
}

} // namespace lantern::gltf
