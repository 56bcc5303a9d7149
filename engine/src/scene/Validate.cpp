// Scene::validate: every object of a scene checked before it is drawn, each refusal naming the
// object by its path (meshes[2].primitives[0].material) and what is wrong with it.
#include "scene/ValidateSupport.h"

#include <lantern/Scene.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace lantern {
namespace {

using namespace validation;

// Skin attributes (counts, set 1 only with set 0, weights finite and >= 0) and morph targets
// (counts, finite displacements).
Result<void> validateDeformation(const Primitive& prim, const std::string& obj) {
    const std::size_t n = prim.positions.size();
    const struct {
        const char* name;
        std::size_t size;
    } streams[] = {{"joints0", prim.joints0.size()},
                   {"weights0", prim.weights0.size()},
                   {"joints1", prim.joints1.size()},
                   {"weights1", prim.weights1.size()}};
    for (const auto& st : streams)
        if (st.size != 0 && st.size != n)
            return invalid(obj + "." + st.name, "has " + std::to_string(st.size) + " entries for " +
                                                     std::to_string(n) + " positions");
    if (prim.joints0.size() != prim.weights0.size() || prim.joints1.size() != prim.weights1.size())
        return invalid(obj, "joints and weights come in pairs (JOINTS_n with WEIGHTS_n)");
    if (!prim.joints1.empty() && prim.joints0.empty())
        return invalid(obj + ".joints1", "a second set of joints without a first");
    for (const auto* set : {&prim.weights0, &prim.weights1})
        for (std::size_t i = 0; i < set->size(); ++i) {
            const glm::vec4& w = (*set)[i];
            for (int k = 0; k < 4; ++k)
                if (!std::isfinite(w[k]) || w[k] < 0.0f)
                    return invalid(obj + "." + at(set == &prim.weights0 ? "weights0" : "weights1", i),
                                   "skin weight " + std::to_string(w[k]) +
                                       " is negative or not finite");
        }
    for (std::size_t t = 0; t < prim.targets.size(); ++t) {
        const MorphTarget& target = prim.targets[t];
        const std::string tobj = obj + "." + at("targets", t);
        if (!target.positions.empty() && target.positions.size() != n)
            return invalid(tobj + ".positions", "has " + std::to_string(target.positions.size()) +
                                                    " displacements for " + std::to_string(n) +
                                                    " positions");
        if (!target.normals.empty() && target.normals.size() != n)
            return invalid(tobj + ".normals", "has " + std::to_string(target.normals.size()) +
                                                  " displacements for " + std::to_string(n) +
                                                  " normals");
        for (std::size_t i = 0; i < target.positions.size(); ++i)
            if (!finite(target.positions[i]))
                return invalid(tobj + "." + at("positions", i), "non-finite displacement");
        for (std::size_t i = 0; i < target.normals.size(); ++i)
            if (!finite(target.normals[i]))
                return invalid(tobj + "." + at("normals", i), "non-finite displacement");
    }
    return {};
}

Result<void> validatePrimitive(const Primitive& prim, const std::string& obj,
                               std::size_t materialCount) {
    const std::size_t n = prim.positions.size();
    if (prim.normals.size() != n && !prim.unlitForWantOfNormals())
        return invalid(obj, "has " + std::to_string(prim.normals.size()) + " normals for " +
                                std::to_string(n) + " positions");
    if (!prim.colors.empty() && prim.colors.size() != n)
        return invalid(obj, "has " + std::to_string(prim.colors.size()) + " colours for " +
                                std::to_string(n) + " positions");
    if (!prim.texcoords.empty() && prim.texcoords.size() != n)
        return invalid(obj, "has " + std::to_string(prim.texcoords.size()) +
                                " texture coordinates for " + std::to_string(n) + " positions");
    if (!prim.texcoords1.empty() && prim.texcoords1.size() != n)
        return invalid(obj, "has " + std::to_string(prim.texcoords1.size()) +
                                " second texture coordinates for " + std::to_string(n) +
                                " positions");
    if (!prim.tangents.empty() && prim.tangents.size() != n)
        return invalid(obj, "has " + std::to_string(prim.tangents.size()) + " tangents for " +
                                std::to_string(n) + " positions");
    const std::size_t k = prim.verticesPerElement();
    const char* list = k == 3 ? "triangle" : k == 2 ? "line" : "point";
    if (prim.indices.empty() && n % k != 0)
        return invalid(obj, "non-indexed " + std::string(list) + " list with " +
                                std::to_string(n) + " vertices (not a multiple of " +
                                std::to_string(k) + ")");
    if (prim.indices.size() % k != 0)
        return invalid(obj + ".indices", "index count " + std::to_string(prim.indices.size()) +
                                             " is not a multiple of " + std::to_string(k) +
                                             " (a " + list + " list)");
    for (std::size_t i = 0; i < prim.indices.size(); ++i)
        if (prim.indices[i] >= n)
            return invalid(obj + "." + at("indices", i),
                           "index " + std::to_string(prim.indices[i]) +
                               " is out of range (vertex count " + std::to_string(n) + ")");
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(prim.positions[i]))
            return invalid(obj + "." + at("positions", i), "non-finite position");
    for (std::size_t i = 0; i < prim.normals.size(); ++i)
        if (!finite(prim.normals[i]))
            return invalid(obj + "." + at("normals", i), "non-finite normal");
    for (std::size_t i = 0; i < prim.colors.size(); ++i)
        if (!finite(glm::vec3(prim.colors[i])) || !std::isfinite(prim.colors[i].w))
            return invalid(obj + "." + at("colors", i), "non-finite colour");
    for (std::size_t i = 0; i < prim.texcoords.size(); ++i)
        if (!std::isfinite(prim.texcoords[i].x) || !std::isfinite(prim.texcoords[i].y))
            return invalid(obj + "." + at("texcoords", i), "non-finite texture coordinate");
    for (std::size_t i = 0; i < prim.texcoords1.size(); ++i)
        if (!std::isfinite(prim.texcoords1[i].x) || !std::isfinite(prim.texcoords1[i].y))
            return invalid(obj + "." + at("texcoords1", i), "non-finite texture coordinate");
    for (std::size_t i = 0; i < prim.tangents.size(); ++i)
        if (!finite(glm::vec3(prim.tangents[i])) || !std::isfinite(prim.tangents[i].w))
            return invalid(obj + "." + at("tangents", i), "non-finite tangent");
    if (prim.material < -1 || prim.material >= int(materialCount))
        return invalid(obj + ".material",
                       "material " + std::to_string(prim.material) + " does not exist");
    return validateDeformation(prim, obj);
}

Result<void> validateWeights(const std::vector<double>& weights, std::size_t targets,
                             const std::string& obj) {
    if (!weights.empty() && weights.size() != targets)
        return invalid(obj, std::to_string(weights.size()) + " morph weights for " +
                                std::to_string(targets) + " morph targets");
    for (double w : weights)
        if (!finite(w)) return invalid(obj, "non-finite morph weight");
    return {};
}

Result<void> validateMeshes(const Scene& scene) {
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const std::string obj = at("meshes", m) + "." + at("primitives", p);
            LANTERN_TRY(validatePrimitive(mesh.primitives[p], obj, scene.materials.size()));
            if (mesh.primitives[p].targets.size() != mesh.primitives[0].targets.size())
                return invalid(obj + ".targets",
                               "has " + std::to_string(mesh.primitives[p].targets.size()) +
                                   " morph targets; primitive 0 has " +
                                   std::to_string(mesh.primitives[0].targets.size()) +
                                   " (glTF: every primitive of a mesh has the same number)");
        }
        LANTERN_TRY(validateWeights(mesh.weights, mesh.morphTargetCount(), at("meshes", m) + ".weights"));
    }
    return {};
}

// Skins: joints exist and are distinct, one finite inverse bind matrix each, the skeleton
// exists.
Result<void> validateSkins(const Scene& scene) {
    for (std::size_t i = 0; i < scene.skins.size(); ++i) {
        const Skin& skin = scene.skins[i];
        const std::string obj = at("skins", i);
        if (skin.joints.empty()) return invalid(obj + ".joints", "a skin needs at least one joint");
        std::vector<bool> seen(scene.nodes.size(), false);
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            const int node = skin.joints[j];
            if (node < 0 || node >= int(scene.nodes.size()))
                return invalid(obj + "." + at("joints", j),
                               "node " + std::to_string(node) + " does not exist");
            if (seen[std::size_t(node)])
                return invalid(obj + "." + at("joints", j),
                               "node " + std::to_string(node) + " is listed twice");
            seen[std::size_t(node)] = true;
        }
        if (skin.inverseBind.size() != skin.joints.size())
            return invalid(obj + ".inverseBindMatrices",
                           std::to_string(skin.inverseBind.size()) + " matrices for " +
                               std::to_string(skin.joints.size()) + " joints");
        for (std::size_t j = 0; j < skin.inverseBind.size(); ++j)
            for (int c = 0; c < 4; ++c)
                if (!finite(skin.inverseBind[j][c]))
                    return invalid(obj + ".inverseBindMatrices",
                                   "matrix " + std::to_string(j) + " is not finite");
        if (skin.skeleton < -1 || skin.skeleton >= int(scene.nodes.size()))
            return invalid(obj + ".skeleton",
                           "node " + std::to_string(skin.skeleton) + " does not exist");
    }
    return {};
}

// The largest joint index each primitive's vertices use (-1: not skinned), once per primitive.
std::vector<std::vector<long long>> largestJoints(const Scene& scene) {
    std::vector<std::vector<long long>> out(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& p : scene.meshes[m].primitives) {
            long long big = -1;
            for (const auto* set : {&p.joints0, &p.joints1})
                for (const glm::uvec4& j : *set)
                    for (int k = 0; k < 4; ++k) big = std::max(big, (long long)j[k]);
            out[m].push_back(big);
        }
    return out;
}

// A node's skin and morph weights against its mesh.
Result<void> validateNodeDeformation(const Scene& scene, const Node& nd, const std::string& obj,
                                     const std::vector<std::vector<long long>>& largest) {
    if (nd.skin < -1 || nd.skin >= int(scene.skins.size()))
        return invalid(obj + ".skin", "skin " + std::to_string(nd.skin) + " does not exist");
    if (nd.mesh < 0) {
        if (!nd.weights.empty())
            return invalid(obj + ".weights", "morph weights on a node without a mesh");
        return {};
    }
    const Mesh& mesh = scene.meshes[std::size_t(nd.mesh)];
    LANTERN_TRY(validateWeights(nd.weights, mesh.morphTargetCount(), obj + ".weights"));
    if (nd.skin < 0) return {};
    const std::size_t joints = scene.skins[std::size_t(nd.skin)].joints.size();
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
        if (largest[std::size_t(nd.mesh)][p] >= (long long)joints)
            return invalid(at("meshes", std::size_t(nd.mesh)) + "." + at("primitives", p) +
                               ".joints",
                           "joint " + std::to_string(largest[std::size_t(nd.mesh)][p]) +
                               " is out of range: skin " + std::to_string(nd.skin) + " (used by " +
                               obj + ") has " + std::to_string(joints) + " joints");
    return {};
}

Result<void> validateNode(const Scene& scene, const Node& nd, const std::string& obj) {
    if (nd.mesh < -1 || nd.mesh >= int(scene.meshes.size()))
        return invalid(obj + ".mesh", "mesh " + std::to_string(nd.mesh) + " does not exist");
    if (nd.camera < -1 || nd.camera >= int(scene.cameras.size()))
        return invalid(obj + ".camera", "camera " + std::to_string(nd.camera) + " does not exist");
    if (nd.light < -1 || nd.light >= int(scene.lights.size()))
        return invalid(obj + ".light", "light " + std::to_string(nd.light) + " does not exist");
    if (!finite(nd.translation) || !finite(nd.scale) ||
        !finite(glm::dvec4(nd.rotation.x, nd.rotation.y, nd.rotation.z, nd.rotation.w)))
        return invalid(obj, "non-finite transform");
    if (nd.matrix)
        for (int c = 0; c < 4; ++c)
            if (!finite((*nd.matrix)[c])) return invalid(obj + ".matrix", "non-finite matrix");
    return {};
}

// With one parent per node, a cycle is a chain of parents that never reaches a root. Linear
// time: each node's chain is walked once, marking every node on it; a walk stops at a node
// already known to reach a root, and meets its own marks only on a cycle.
Result<void> checkNoCycles(const std::vector<int>& parent) {
    enum : unsigned char { Unknown, OnPath, ReachesRoot };
    std::vector<unsigned char> state(parent.size(), Unknown);
    std::vector<int> path;
    for (std::size_t i = 0; i < parent.size(); ++i) {
        path.clear();
        int n = int(i);
        while (n != -1 && state[std::size_t(n)] == Unknown) {
            state[std::size_t(n)] = OnPath;
            path.push_back(n);
            n = parent[std::size_t(n)];
        }
        if (n != -1 && state[std::size_t(n)] == OnPath)
            return invalid(at("nodes", std::size_t(n)), "node hierarchy contains a cycle");
        for (int k : path) state[std::size_t(k)] = ReachesRoot;
    }
    return {};
}

// Nodes: references in range, finite transforms, a forest (one parent, no cycles). Returns each
// node's parent (-1 for none).
Result<std::vector<int>> validateNodes(const Scene& scene) {
    const std::vector<Node>& nodes = scene.nodes;
    std::vector<int> parent(nodes.size(), -1);
    const std::vector<std::vector<long long>> largest = largestJoints(scene);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const Node& nd = nodes[i];
        const std::string obj = at("nodes", i);
        LANTERN_TRY(validateNode(scene, nd, obj));
        LANTERN_TRY(validateNodeDeformation(scene, nd, obj, largest));
        for (std::size_t c = 0; c < nd.children.size(); ++c) {
            const int ch = nd.children[c];
            if (ch < 0 || ch >= int(nodes.size()))
                return invalid(obj + "." + at("children", c),
                               "node " + std::to_string(ch) + " does not exist");
            if (ch == int(i))
                return invalid(obj + "." + at("children", c), "node is its own child (a cycle)");
            if (parent[ch] != -1)
                return invalid(obj + "." + at("children", c), "node " + std::to_string(ch) +
                                                                  " already has parent node " +
                                                                  std::to_string(parent[ch]));
            parent[ch] = int(i);
        }
    }
    LANTERN_TRY(checkNoCycles(parent));
    return parent;
}

Result<void> validateSampler(const AnimationSampler& smp, const std::string& sobj) {
    if (smp.times.empty()) return invalid(sobj + ".input", "sampler has no keyframes");
    for (std::size_t k = 0; k < smp.times.size(); ++k) {
        if (!finite(smp.times[k]) || smp.times[k] < 0)
            return invalid(sobj + ".input",
                           "key time " + std::to_string(k) + " is negative or not finite");
        if (k > 0 && !(smp.times[k] > smp.times[k - 1]))
            return invalid(sobj + ".input",
                           "key times are not strictly increasing at key " + std::to_string(k));
    }
    const std::size_t per = smp.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (smp.weightCount > 0 || !smp.weights.empty()) {
        if (smp.weights.size() != smp.times.size() * per * smp.weightCount)
            return invalid(sobj + ".output",
                           "has " + std::to_string(smp.weights.size()) + " morph weights for " +
                               std::to_string(smp.times.size()) + " keys of " +
                               std::to_string(smp.weightCount) + " targets");
        for (double w : smp.weights)
            if (!finite(w)) return invalid(sobj + ".output", "non-finite keyframe value");
        if (smp.interpolation == Interpolation::CubicSpline && smp.times.size() < 2)
            return invalid(sobj, "CUBICSPLINE needs at least two keys");
        return {};
    }
    if (smp.values.size() != smp.times.size() * per)
        return invalid(sobj + ".output", "has " + std::to_string(smp.values.size()) +
                                             " values for " + std::to_string(smp.times.size()) +
                                             " keys (expected " +
                                             std::to_string(smp.times.size() * per) + ")");
    if (smp.interpolation == Interpolation::CubicSpline && smp.times.size() < 2)
        return invalid(sobj, "CUBICSPLINE needs at least two keys");
    for (const auto& v : smp.values)
        if (!finite(v)) return invalid(sobj + ".output", "non-finite keyframe value");
    return {};
}

Result<void> validateChannel(const Scene& scene, const Animation& an, const AnimationChannel& ch,
                             const std::string& cobj) {
    if (ch.sampler < 0 || ch.sampler >= int(an.samplers.size()))
        return invalid(cobj + ".sampler",
                       "sampler " + std::to_string(ch.sampler) + " does not exist");
    if (ch.node < 0 || ch.node >= int(scene.nodes.size()))
        return invalid(cobj + ".target.node",
                       "node " + std::to_string(ch.node) + " does not exist");
    const Node& nd = scene.nodes[std::size_t(ch.node)];
    const AnimationSampler& smp = an.samplers[std::size_t(ch.sampler)];
    if (ch.path == AnimationPath::Weights) {
        const std::size_t targets =
            nd.mesh >= 0 ? scene.meshes[std::size_t(nd.mesh)].morphTargetCount() : 0;
        if (targets == 0 || smp.weightCount != targets)
            return invalid(cobj, "animates " + std::to_string(smp.weightCount) +
                                     " morph weights of node " + std::to_string(ch.node) +
                                     ", whose mesh has " + std::to_string(targets) +
                                     " morph targets");
        return {};
    }
    if (smp.weightCount > 0)
        return invalid(cobj, "a morph-weight sampler drives a transform");
    if (nd.matrix)
        return invalid(cobj + ".target.node",
                       "node " + std::to_string(ch.node) + " has a matrix and cannot be animated");
    return {};
}

Result<void> validateAnimations(const Scene& scene) {
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        const Animation& an = scene.animations[a];
        const std::string obj = at("animations", a);
        for (std::size_t s = 0; s < an.samplers.size(); ++s)
            LANTERN_TRY(validateSampler(an.samplers[s], obj + "." + at("samplers", s)));
        for (std::size_t c = 0; c < an.channels.size(); ++c)
            LANTERN_TRY(validateChannel(scene, an, an.channels[c], obj + "." + at("channels", c)));
    }
    return {};
}

// The scenes (roots): at least one, the default one existing, each listing root nodes only.
Result<void> validateRoots(const Scene& scene, const std::vector<int>& parent) {
    const std::vector<SceneRoot>& roots = scene.roots;
    // No root at all is a valid scene that draws nothing (nothingToDraw() says so).
    if (roots.empty() && scene.defaultRoot == 0) return {};
    if (scene.defaultRoot < 0 || scene.defaultRoot >= int(roots.size()))
        return invalid("scene",
                       "default scene " + std::to_string(scene.defaultRoot) + " does not exist");
    for (std::size_t r = 0; r < roots.size(); ++r) {
        for (std::size_t k = 0; k < roots[r].nodes.size(); ++k) {
            const int n = roots[r].nodes[k];
            const std::string obj = at("scenes", r) + "." + at("nodes", k);
            if (n < 0 || n >= int(scene.nodes.size()))
                return invalid(obj, "node " + std::to_string(n) + " does not exist");
            if (parent[n] != -1)
                return invalid(obj, "node " + std::to_string(n) + " is a child of node " +
                                        std::to_string(parent[n]) + ", not a root");
        }
        if (roots[r].lighting && !finite(roots[r].lighting->globalAmbient))
            return invalid(at("scenes", r) + ".extensions.LANTERN_lighting.globalAmbient",
                           "non-finite colour");
    }
    return {};
}

} // namespace

Result<void> Scene::validate() const {
    LANTERN_TRY(validateMeshes(*this));
    LANTERN_TRY(validation::validateAppearance(*this));
    LANTERN_TRY(validateSkins(*this));
    Result<std::vector<int>> parent = validateNodes(*this);
    if (!parent) return std::move(parent).error();
    LANTERN_TRY(validateAnimations(*this));
    return validateRoots(*this, *parent);
}

} // namespace lantern
