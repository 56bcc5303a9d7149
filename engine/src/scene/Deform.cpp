// Skinning and morph targets on the CPU, in double precision: the one implementation that
// bounds, framing and the reference use. shaders/deform.comp is its GPU twin, operation for
// operation (morph, then skin; cofactor normals with the mirroring sign; guarded normalise).
#include <lantern/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern {
namespace {

// A normal scaled by its largest component, then normalised: no overflow for huge vectors,
// and the zero vector stays zero (lavapipe's normalize(0) is NaN; numerics.md 3.1).
glm::dvec3 guardedNormalize(const glm::dvec3& n) {
    const double big = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    if (!(big > 0.0) || !std::isfinite(big)) return glm::dvec3(0.0);
    const glm::dvec3 m = n / big;
    return m / std::sqrt(glm::dot(m, m));
}

// The weighted sum of a vertex's joint matrices; identity when every weight is 0.
glm::dmat4 skinMatrix(const std::vector<glm::dmat4>& joints, const Primitive& prim,
                      std::size_t v) {
    glm::dmat4 s(0.0);
    double sum = 0.0;
    auto add = [&](const glm::uvec4& j, const glm::vec4& w) {
        for (int k = 0; k < 4; ++k)
            if (w[k] != 0.0f) {
                s += double(w[k]) * joints[j[k]];
                sum += double(w[k]);
            }
    };
    add(prim.joints0[v], prim.weights0[v]);
    if (!prim.joints1.empty()) add(prim.joints1[v], prim.weights1[v]);
    return sum == 0.0 ? glm::dmat4(1.0) : s;
}

} // namespace

bool isSkinned(const Scene& scene, int node, const Primitive& prim) {
    return node >= 0 && std::size_t(node) < scene.nodes.size() &&
           scene.nodes[std::size_t(node)].skin >= 0 && !prim.joints0.empty();
}

bool isDeformed(const Scene& scene, int node, const Primitive& prim) {
    return !prim.targets.empty() || isSkinned(scene, node, prim);
}

glm::dmat4 worldFromDrawn(const Scene& scene, const Pose& pose, int node, const Primitive& prim) {
    return isSkinned(scene, node, prim) ? glm::dmat4(1.0) : pose.worldFromNode[std::size_t(node)];
}

DeformedPrimitive deformPrimitive(const Scene& scene, const Pose& pose, int node,
                                  const Primitive& prim) {
    const std::size_t n = prim.positions.size();
    DeformedPrimitive out;
    out.positions.resize(n);
    out.normals.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        out.positions[v] = glm::dvec3(prim.positions[v]);
        out.normals[v] = prim.normals.empty() ? glm::dvec3(0.0) : glm::dvec3(prim.normals[v]);
    }
    const std::vector<double>* weights =
        std::size_t(node) < pose.morphWeights.size() ? &pose.morphWeights[std::size_t(node)]
                                                     : nullptr;
    if (weights)
        for (std::size_t t = 0; t < prim.targets.size() && t < weights->size(); ++t) {
            const double w = (*weights)[t];
            if (w == 0.0) continue;
            const MorphTarget& target = prim.targets[t];
            for (std::size_t v = 0; v < target.positions.size(); ++v)
                out.positions[v] += w * glm::dvec3(target.positions[v]);
            for (std::size_t v = 0; v < target.normals.size(); ++v)
                out.normals[v] += w * glm::dvec3(target.normals[v]);
        }
    if (isSkinned(scene, node, prim)) {
        const std::vector<glm::dmat4>& joints =
            pose.jointMatrices[std::size_t(scene.nodes[std::size_t(node)].skin)];
        for (std::size_t v = 0; v < n; ++v) {
            const glm::dmat4 s = skinMatrix(joints, prim, v);
            out.positions[v] = glm::dvec3(s * glm::dvec4(out.positions[v], 1.0));
            const glm::dmat3 m(s);
            glm::dmat3 cof(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
            if (glm::dot(m[0], cof[0]) < 0.0) cof = -cof;  // mirroring: keep normals outward
            out.normals[v] = cof * out.normals[v];
        }
    }
    for (glm::dvec3& nrm : out.normals) nrm = guardedNormalize(nrm);
    return out;
}

} // namespace lantern
