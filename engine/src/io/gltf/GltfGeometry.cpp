// glTF meshes -> Lantern primitives: attributes read through the checked accessor readers,
// strips, fans and loops converted to lists (glTF's vertex order, so windings are kept), and
// missing normals of triangles computed as angle-weighted averages of the faces sharing each
// vertex (lines and points without normals are drawn unlit).
#include "io/gltf/GltfInternal.h"

#include <cmath>

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

/// The element list of a primitive given its vertex sequence (its indices, or 0..n-1), as
/// glTF 2.0 specifies each mode. Strip triangle i is (i, i+1+i%2, i+2-i%2) and fan triangle i
/// is (i+1, i+2, 0), which keeps every triangle's winding; strip line i is (i, i+1) and a loop
/// adds (n-1, 0), so the last vertex of each line is GL's provoking vertex. A trailing partial
/// triangle or line of a list is dropped, as OpenGL's glDrawArrays/glDrawElements do.
std::vector<std::uint32_t> elementList(int mode, const std::vector<std::uint32_t>& sequence) {
    const std::size_t n = sequence.size();
    std::vector<std::uint32_t> out;
    switch (mode) {
    case TINYGLTF_MODE_POINTS:
        return sequence;
    case TINYGLTF_MODE_LINE:
        out.assign(sequence.begin(), sequence.begin() + std::ptrdiff_t(n - n % 2));
        return out;
    case TINYGLTF_MODE_LINE_STRIP:
    case TINYGLTF_MODE_LINE_LOOP:
        if (n < 2) return out;
        out.reserve(2 * n);
        for (std::size_t i = 0; i + 1 < n; ++i) out.insert(out.end(), {sequence[i], sequence[i + 1]});
        if (mode == TINYGLTF_MODE_LINE_LOOP && n > 2) out.insert(out.end(), {sequence[n - 1], sequence[0]});
        return out;
    case TINYGLTF_MODE_TRIANGLES:
        out.assign(sequence.begin(), sequence.begin() + std::ptrdiff_t(n - n % 3));
        return out;
    default:
        break;
    }
    if (n >= 3) {
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

Topology topologyOf(int mode) {
    if (mode == TINYGLTF_MODE_POINTS) return Topology::Points;
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
        mode == TINYGLTF_MODE_LINE_STRIP)
        return Topology::Lines;
    return Topology::Triangles;
}

// The floats read for `object` as vectors of `components` each. The vectors are charged to the
// load's budget before they are made; the floats are freed after and their bytes returned.
template <typename Vec>
Result<std::vector<Vec>> toVectors(std::vector<float>& flat, std::size_t components,
                                   const std::string& object, const Diagnostics& diag) {
    const std::size_t count = flat.size() / components;
    LANTERN_TRY(diag.charge(count, sizeof(Vec), object, "converting the data to vectors"));
    std::vector<Vec> out(count);
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t c = 0; c < components && c < std::size_t(Vec::length()); ++c)
            out[i][int(c)] = flat[i * components + c];
    const std::uint64_t freed = flat.size() * sizeof(float);
    std::vector<float>().swap(flat);
    diag.release(freed);
    return out;
}

/// Which TEXCOORD set the primitive's material's textures read (0 without any).
int texcoordSet(const tinygltf::Model& model, int material) {
    return material < 0 ? 0 : materialTexcoordSet(model.materials[std::size_t(material)]);
}

/// Whether the primitive's material has any texture.
bool hasTextures(const tinygltf::Model& model, int material) {
    if (material < 0) return false;
    const tinygltf::Material& m = model.materials[std::size_t(material)];
    return m.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
           m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 ||
           m.normalTexture.index >= 0 || m.occlusionTexture.index >= 0 ||
           m.emissiveTexture.index >= 0;
}

} // namespace

bool needsTangents(const tinygltf::Model& model, const tinygltf::Primitive& prim) {
    auto normalMapped = [&](int material) {
        return material >= 0 && std::size_t(material) < model.materials.size() &&
               model.materials[std::size_t(material)].normalTexture.index >= 0;
    };
    if (normalMapped(prim.material)) return true;
    const tinygltf::Value* variants = extension(prim.extensions, "KHR_materials_variants");
    if (!variants || !variants->Has("mappings") || !variants->Get("mappings").IsArray()) return false;
    const tinygltf::Value& mappings = variants->Get("mappings");
    for (std::size_t i = 0; i < mappings.ArrayLen(); ++i) {
        const tinygltf::Value& m = mappings.Get(int(i));
        if (m.Has("material") && m.Get("material").IsInt() &&
            normalMapped(m.Get("material").GetNumberAsInt()))
            return true;
    }
    return false;
}

namespace {

// The accessor of the primitive's attribute `name`, or -1.
int attributeAccessor(const tinygltf::Primitive& prim, const std::string& name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

// POSITION (accessor `positionAccessor`), and NORMAL, COLOR_0, the material's TEXCOORD set
// and its second (materialSecondTexcoordSet), and TANGENT for a normal-mapped material, when
// the primitive has them.
Result<void> readAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                            int positionAccessor, const std::string& obj, const Diagnostics& diag,
                            Primitive& out) {
    auto attribute = [&](const std::string& name) { return attributeAccessor(prim, name); };
    auto positions = readFloats(model, positionAccessor, obj + ".attributes.POSITION", diag);
    if (!positions) return std::move(positions).error();
    LANTERN_TAKE(out.positions,
                 toVectors<glm::vec3>(*positions, 3, obj + ".attributes.POSITION", diag));

    if (const int a = attribute("NORMAL"); a >= 0) {
        auto normals = readFloats(model, a, obj + ".attributes.NORMAL", diag);
        if (!normals) return std::move(normals).error();
        LANTERN_TAKE(out.normals,
                     toVectors<glm::vec3>(*normals, 3, obj + ".attributes.NORMAL", diag));
    }
    if (const int a = attribute("TANGENT"); a >= 0 && needsTangents(model, prim)) {
        auto tangents = readFloats(model, a, obj + ".attributes.TANGENT", diag);
        if (!tangents) return std::move(tangents).error();
        LANTERN_TAKE(out.tangents,
                     toVectors<glm::vec4>(*tangents, 4, obj + ".attributes.TANGENT", diag));
    }
    if (const int a = attribute("COLOR_0"); a >= 0) {
        auto colors = readFloats(model, a, obj + ".attributes.COLOR_0", diag);
        if (!colors) return std::move(colors).error();
        const std::size_t n = std::size_t(componentCount(model.accessors[std::size_t(a)].type));
        LANTERN_TAKE(out.colors,
                     toVectors<glm::vec4>(*colors, n, obj + ".attributes.COLOR_0", diag));
        if (n == 3)
            for (glm::vec4& c : out.colors)
                c.w = 1.0f;
    }
    const int set = texcoordSet(model, prim.material);
    const std::string texcoordName = "TEXCOORD_" + std::to_string(set);
    if (const int a = attribute(texcoordName); a >= 0) {
        auto uv = readFloats(model, a, obj + ".attributes." + texcoordName, diag);
        if (!uv) return std::move(uv).error();
        LANTERN_TAKE(out.texcoords,
                     toVectors<glm::vec2>(*uv, 2, obj + ".attributes." + texcoordName, diag));
    } else if (hasTextures(model, prim.material)) {
        diag.warn(obj + ".attributes", "no " + texcoordName +
                                           " for the material's textures; they are not applied");
    }
    const int second = prim.material < 0 ? -1
                       : materialSecondTexcoordSet(model.materials[std::size_t(prim.material)]);
    if (second >= 0) {
        const std::string name = "TEXCOORD_" + std::to_string(second);
        if (const int a = attribute(name); a >= 0) {
            auto uv = readFloats(model, a, obj + ".attributes." + name, diag);
            if (!uv) return std::move(uv).error();
            LANTERN_TAKE(out.texcoords1, toVectors<glm::vec2>(*uv, 2, obj + ".attributes." + name, diag));
        } else {
            diag.warn(obj + ".attributes", "no " + name +
                                               " for the material's maps that read it; they read (0, 0)");
        }
    }
    return {};
}

// JOINTS_0/1 and WEIGHTS_0/1 (up to 8 influences; further sets are ignored with a warning).
Result<void> readSkinAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                const std::string& obj, const Diagnostics& diag, Primitive& out) {
    for (int set = 0; set < 2; ++set) {
        const std::string jname = "JOINTS_" + std::to_string(set);
        const std::string wname = "WEIGHTS_" + std::to_string(set);
        const int ja = attributeAccessor(prim, jname), wa = attributeAccessor(prim, wname);
        if (ja < 0 && wa < 0) break;
        if (ja < 0 || wa < 0)
            return diag.error(obj + ".attributes." + (ja < 0 ? wname : jname),
                              "has no matching " + (ja < 0 ? jname : wname) +
                                  " (skin influences come in JOINTS_n / WEIGHTS_n pairs)");
        auto joints = readDoubles(model, ja, obj + ".attributes." + jname, diag);
        if (!joints) return std::move(joints).error();
        auto weights = readFloats(model, wa, obj + ".attributes." + wname, diag);
        if (!weights) return std::move(weights).error();
        std::vector<glm::uvec4>& j = set == 0 ? out.joints0 : out.joints1;
        std::vector<glm::vec4>& w = set == 0 ? out.weights0 : out.weights1;
        LANTERN_TRY(diag.charge(joints->size() / 4, sizeof(glm::uvec4), obj + "." + jname,
                                "converting the data to vectors"));
        j.resize(joints->size() / 4);
        for (std::size_t i = 0; i < j.size(); ++i)
            for (int k = 0; k < 4; ++k) j[i][k] = std::uint32_t((*joints)[i * 4 + std::size_t(k)]);
        LANTERN_TAKE(w, toVectors<glm::vec4>(*weights, 4, obj + "." + wname, diag));
        for (std::size_t i = 0; i < w.size(); ++i)
            for (int k = 0; k < 4; ++k)
                if (w[i][k] < 0.0f)
                    return diag.error(obj + ".attributes." + wname,
                                      "weight " + std::to_string(w[i][k]) + " of vertex " +
                                          std::to_string(i) + " is negative");
    }
    for (const auto& [name, accessor] : prim.attributes)
        if ((name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0) &&
            name != "JOINTS_0" && name != "JOINTS_1" && name != "WEIGHTS_0" && name != "WEIGHTS_1")
            diag.warn(obj + ".attributes." + name,
                      "only 8 influences per vertex are used (JOINTS_0/1, WEIGHTS_0/1); ignored");
    return {};
}

// Morph targets: POSITION and NORMAL displacements (others, such as TANGENT, are ignored).
Result<void> readTargets(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                         const std::string& obj, const Diagnostics& diag, Primitive& out) {
    for (std::size_t t = 0; t < prim.targets.size(); ++t) {
        MorphTarget target;
        for (const auto& [name, accessor] : prim.targets[t]) {
            const std::string tobj = obj + "." + at("targets", t) + "." + name;
            if (name != "POSITION" && name != "NORMAL") {
                diag.warn(tobj, "morph-target attribute not used (only POSITION and NORMAL)");
                continue;
            }
            auto values = readFloats(model, accessor, tobj, diag);
            if (!values) return std::move(values).error();
            LANTERN_TAKE(name == "POSITION" ? target.positions : target.normals,
                         toVectors<glm::vec3>(*values, 3, tobj, diag));
        }
        out.targets.push_back(std::move(target));
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

// One primitive as a list of triangles, lines or points; nothing (after a warning) when it is
// skipped: no POSITION, or not one whole element.
Result<std::optional<Primitive>> convertPrimitive(const tinygltf::Model& model,
                                                  const tinygltf::Primitive& prim,
                                                  const std::string& obj, const Diagnostics& diag) {
    const int positionAccessor = attributeAccessor(prim, "POSITION");
    if (positionAccessor < 0) {
        diag.warn(obj + ".attributes", "no POSITION; primitive skipped");
        return std::optional<Primitive>();
    }
    Primitive out;
    out.topology = topologyOf(prim.mode);
    out.material = prim.material;
    out.materialWithoutVariant = prim.material;
    auto names = variantNames(model, diag);
    if (!names) return std::move(names).error();
    auto variants = primitiveVariants(model, prim, names->size(), obj, diag);
    if (!variants) return std::move(variants).error();
    out.variantMaterials = std::move(*variants);
    LANTERN_TRY(readAttributes(model, prim, positionAccessor, obj, diag, out));
    LANTERN_TRY(readSkinAttributes(model, prim, obj, diag, out));
    LANTERN_TRY(readTargets(model, prim, obj, diag, out));
    auto sequence = vertexSequence(model, prim, out.positions.size(), obj, diag);
    if (!sequence) return std::move(sequence).error();
    const std::size_t given = sequence->size();
    out.indices = elementList(prim.mode, *sequence);
    const std::size_t k = out.verticesPerElement();
    const bool list = prim.mode == TINYGLTF_MODE_TRIANGLES || prim.mode == TINYGLTF_MODE_LINE;
    if (list && given % k != 0)
        diag.warn(obj, std::to_string(given) + " vertices for " + modeName(prim.mode) +
                           " is not a multiple of " + std::to_string(k) + "; the last " +
                           std::to_string(given % k) + " are ignored");
    if (out.indices.empty()) {
        diag.warn(obj, std::string(modeName(prim.mode)) + " with " + std::to_string(given) +
                           " vertices draws nothing; primitive skipped");
        return std::optional<Primitive>();
    }
    // A plain non-indexed list needs no index buffer: draw the vertices in order.
    if (prim.indices < 0 && (list || prim.mode == TINYGLTF_MODE_POINTS) && given % k == 0)
        out.indices.clear();
    // Triangles without normals get smooth ones; lines and points without are drawn unlit.
    if (out.normals.empty() && out.topology == Topology::Triangles) {
        // The normals and, while they are summed, one double vector per vertex.
        const std::uint64_t sums = out.positions.size() * sizeof(glm::dvec3);
        LANTERN_TRY(diag.charge(out.positions.size(), sizeof(glm::vec3) + sizeof(glm::dvec3), obj,
                                "computing smooth normals"));
        out.normals = computeSmoothNormals(out.positions, out.indices);
        diag.release(sums);
    }
    return std::optional<Primitive>(std::move(out));
}

} // namespace

Result<Mesh> convertMesh(const tinygltf::Model& model, std::size_t meshIndex,
                         const Diagnostics& diag) {
    const tinygltf::Mesh& src = model.meshes[meshIndex];
    Mesh mesh;
    mesh.name = src.name;
    if (src.primitives.empty()) diag.warn(at("meshes", meshIndex), "mesh has no primitives");
    for (double w : src.weights)
        if (!std::isfinite(w))
            return diag.error(at("meshes", meshIndex) + ".weights", "non-finite morph weight");
    const std::size_t targets = src.primitives.empty() ? 0 : src.primitives[0].targets.size();
    if (!src.weights.empty() && src.weights.size() != targets)
        return diag.error(at("meshes", meshIndex) + ".weights",
                          std::to_string(src.weights.size()) + " weights for " +
                              std::to_string(targets) + " morph targets");
    mesh.weights = src.weights;
    for (std::size_t p = 0; p < src.primitives.size(); ++p) {
        const std::string obj = at("meshes", meshIndex) + "." + at("primitives", p);
        auto prim = convertPrimitive(model, src.primitives[p], obj, diag);
        if (!prim) return std::move(prim).error();
        if (*prim) mesh.primitives.push_back(std::move(**prim));
    }
    if (mesh.primitives.empty()) mesh.weights.clear();  // every primitive skipped (warned)
    return mesh;
}

} // namespace lantern::gltf
