// The scene model: names, node transforms, animation time ranges, pose evaluation and bounds
// (validation is in Validate.cpp).
#include <lantern/Scene.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace lantern {

const char* toString(ShadingMode mode) noexcept {
    switch (mode) {
    case ShadingMode::Flat: return "flat";
    case ShadingMode::Gouraud: return "gouraud";
    case ShadingMode::Phong: return "phong";
    }
    return "?";
}

const char* toString(SpecularModel model) noexcept {
    return model == SpecularModel::Blinn ? "blinn" : "phong";
}

std::optional<ShadingMode> parseShadingMode(std::string_view t) noexcept {
    if (t == "flat") return ShadingMode::Flat;
    if (t == "gouraud") return ShadingMode::Gouraud;
    if (t == "phong") return ShadingMode::Phong;
    return std::nullopt;
}

std::optional<SpecularModel> parseSpecularModel(std::string_view t) noexcept {
    if (t == "blinn") return SpecularModel::Blinn;
    if (t == "phong") return SpecularModel::Phong;
    return std::nullopt;
}

glm::dmat4 Node::localTransform() const {
    if (matrix) return *matrix;
    glm::dmat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::dvec4(translation, 1.0);
    return m;
}

double Animation::startTime() const {
    double t = kInfinity;
    for (const auto& s : samplers)
        if (!s.times.empty()) t = std::min(t, s.times.front());
    return std::isinf(t) ? 0.0 : t;
}

double Animation::endTime() const {
    double t = -kInfinity;
    for (const auto& s : samplers)
        if (!s.times.empty()) t = std::max(t, s.times.back());
    return std::isinf(t) ? 0.0 : t;
}

TimeRange animationRange(const Scene& scene, int animation) {
    TimeRange range;
    bool any = false;
    for (std::size_t i = 0; i < scene.animations.size(); ++i) {
        if (animation >= 0 && std::size_t(animation) != i) continue;
        const Animation& a = scene.animations[i];
        range.start = any ? std::min(range.start, a.startTime()) : a.startTime();
        range.end = any ? std::max(range.end, a.endTime()) : a.endTime();
        any = true;
    }
    return range;
}

double loopTime(double time, const TimeRange& range) {
    const double length = range.duration();
    if (!(length > 0.0) || !std::isfinite(time)) return range.start;
    const double wrapped = std::fmod(time - range.start, length);
    return range.start + (wrapped < 0.0 ? wrapped + length : wrapped);
}

void Bounds::extend(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
}

double Bounds::radius() const { return empty() ? 0.0 : glm::length(max - min) * 0.5; }

namespace {

// The morph weights every node with morph targets is drawn with: the animated ones (set by the
// caller), else the node's, else the mesh's, else zeros.
void defaultMorphWeights(const Scene& scene, Pose& pose) {
    pose.morphWeights.assign(scene.nodes.size(), {});
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& nd = scene.nodes[i];
        if (nd.mesh < 0) continue;
        const Mesh& mesh = scene.meshes[std::size_t(nd.mesh)];
        const std::size_t n = mesh.morphTargetCount();
        if (n == 0) continue;
        pose.morphWeights[i] = !nd.weights.empty()     ? nd.weights
                               : !mesh.weights.empty() ? mesh.weights
                                                       : std::vector<double>(n, 0.0);
    }
}

// World transforms of joints outside the root's hierarchy (a skin may use nodes that no scene
// lists): composed along their parents, each node once.
void placeUnvisitedJoints(const Scene& scene, Pose& pose,
                          const std::function<glm::dmat4(std::size_t)>& local) {
    std::vector<int> parent(scene.nodes.size(), -1);
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        for (int c : scene.nodes[i].children) parent[std::size_t(c)] = int(i);
    std::vector<bool> done = pose.visible;
    std::vector<int> chain;
    for (const Skin& skin : scene.skins)
        for (int joint : skin.joints) {
            chain.clear();
            for (int n = joint; n >= 0 && !done[std::size_t(n)]; n = parent[std::size_t(n)])
                chain.push_back(n);
            // Outermost first: its parent is placed already or it is a root.
            for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
                const int p = parent[std::size_t(*it)];
                const glm::dmat4 parentWorld = p >= 0 ? pose.worldFromNode[std::size_t(p)]
                                                      : glm::dmat4(1.0);
                pose.worldFromNode[std::size_t(*it)] = parentWorld * local(std::size_t(*it));
                done[std::size_t(*it)] = true;
            }
        }
}

} // namespace

Pose evaluatePose(const Scene& scene, int root, double time) {
    Pose pose;
    pose.root = root < 0 ? scene.defaultRoot : root;
    pose.time = time;
    const std::size_t n = scene.nodes.size();
    pose.worldFromNode.assign(n, glm::dmat4(1.0));
    pose.visible.assign(n, false);
    defaultMorphWeights(scene, pose);

    // Animated TRS per node, starting from the rest pose.
    std::vector<glm::dvec3> t(n), s(n);
    std::vector<glm::dquat> r(n);
    for (std::size_t i = 0; i < n; ++i) {
        t[i] = scene.nodes[i].translation;
        r[i] = scene.nodes[i].rotation;
        s[i] = scene.nodes[i].scale;
    }
    for (const Animation& anim : scene.animations) {
        for (const AnimationChannel& ch : anim.channels) {
            const AnimationSampler& sampler = anim.samplers[ch.sampler];
            if (ch.path == AnimationPath::Weights) {
                pose.morphWeights[std::size_t(ch.node)] = sampleWeights(sampler, time);
                continue;
            }
            const glm::dvec4 v = sampleAnimation(sampler, ch.path, time);
            switch (ch.path) {
            case AnimationPath::Translation: t[ch.node] = glm::dvec3(v); break;
            case AnimationPath::Scale: s[ch.node] = glm::dvec3(v); break;
            case AnimationPath::Rotation: r[ch.node] = glm::dquat(v.w, v.x, v.y, v.z); break;
            case AnimationPath::Weights: break;
            }
        }
    }
    auto local = [&](std::size_t i) {
        const Node& nd = scene.nodes[i];
        if (nd.matrix) return *nd.matrix;
        Node tmp;
        tmp.translation = t[i];
        tmp.rotation = r[i];
        tmp.scale = s[i];
        return tmp.localTransform();
    };
    if (pose.root >= 0 && pose.root < int(scene.roots.size())) {
        // Iterative depth-first walk (validated: a forest, so it terminates).
        std::vector<std::pair<int, glm::dmat4>> stack;
        for (int rn : scene.roots[pose.root].nodes) stack.emplace_back(rn, glm::dmat4(1.0));
        while (!stack.empty()) {
            auto [node, parentWorld] = stack.back();
            stack.pop_back();
            const glm::dmat4 world = parentWorld * local(std::size_t(node));
            pose.worldFromNode[node] = world;
            pose.visible[node] = true;
            for (int ch : scene.nodes[node].children) stack.emplace_back(ch, world);
        }
    }
    if (!scene.skins.empty()) {
        placeUnvisitedJoints(scene, pose, local);
        pose.jointMatrices.resize(scene.skins.size());
        for (std::size_t k = 0; k < scene.skins.size(); ++k) {
            const Skin& skin = scene.skins[k];
            pose.jointMatrices[k].resize(skin.joints.size());
            for (std::size_t j = 0; j < skin.joints.size(); ++j)
                pose.jointMatrices[k][j] =
                    pose.worldFromNode[std::size_t(skin.joints[j])] * skin.inverseBind[j];
        }
    }
    return pose;
}

Bounds computeBounds(const Scene& scene, const Pose& pose) {
    Bounds b;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        if (!pose.visible[i] || scene.nodes[i].mesh < 0) continue;
        for (const Primitive& prim : scene.meshes[scene.nodes[i].mesh].primitives) {
            if (prim.positions.empty()) continue;
            const glm::dmat4 m = worldFromDrawn(scene, pose, int(i), prim);
            Bounds local;
            if (isDeformed(scene, int(i), prim))
                for (const glm::dvec3& p : deformPrimitive(scene, pose, int(i), prim).positions)
                    local.extend(p);
            else
                for (const glm::vec3& p : prim.positions) local.extend(glm::dvec3(p));
            for (int c = 0; c < 8; ++c) {
                const glm::dvec3 corner((c & 1) ? local.max.x : local.min.x,
                                        (c & 2) ? local.max.y : local.min.y,
                                        (c & 4) ? local.max.z : local.min.z);
                b.extend(glm::dvec3(m * glm::dvec4(corner, 1.0)));
            }
        }
    }
    return b;
}

namespace {

template <class T>
std::size_t bytesOf(const std::vector<T>& v) {
    return v.capacity() * sizeof(T);
}

// What summarize() calls hostBytes: the large arrays a scene holds.
std::size_t hostBytes(const Scene& scene) {
    std::size_t n = 0;
    for (const Mesh& m : scene.meshes)
        for (const Primitive& p : m.primitives) {
            n += bytesOf(p.positions) + bytesOf(p.normals) + bytesOf(p.colors) +
                 bytesOf(p.texcoords) + bytesOf(p.texcoords1) + bytesOf(p.tangents) +
                 bytesOf(p.joints0) + bytesOf(p.joints1) + bytesOf(p.weights0) +
                 bytesOf(p.weights1) + bytesOf(p.indices);
            for (const MorphTarget& t : p.targets) n += bytesOf(t.positions) + bytesOf(t.normals);
        }
    for (const Texture& t : scene.textures) n += bytesOf(t.rgba8);
    for (const Animation& a : scene.animations)
        for (const AnimationSampler& s : a.samplers)
            n += bytesOf(s.times) + bytesOf(s.values) + bytesOf(s.weights);
    return n;
}

} // namespace

SceneSummary summarize(const Scene& scene) {
    SceneSummary s;
    s.nodes = scene.nodes.size();
    s.meshes = scene.meshes.size();
    s.materials = scene.materials.size();
    s.textures = scene.textures.size();
    s.lights = scene.lights.size();
    s.cameras = scene.cameras.size();
    s.animations = scene.animations.size();
    s.roots = scene.roots.size();
    for (const Mesh& m : scene.meshes)
        for (const Primitive& p : m.primitives) {
            ++s.primitives;
            s.triangles += p.triangleCount();
            if (p.topology == Topology::Lines) s.lines += p.elementCount();
            if (p.topology == Topology::Points) s.points += p.elementCount();
            s.vertices += p.positions.size();
        }
    s.hostBytes = hostBytes(scene);
    if (!scene.roots.empty()) s.bounds = computeBounds(scene, evaluatePose(scene, -1, 0.0));
    return s;
}

std::optional<std::string> nothingToDraw(const Scene& scene, int root) {
    const int r = root < 0 ? scene.defaultRoot : root;
    if (scene.roots.empty())
        return std::string(scene.nodes.empty() ? "the file defines no scene and no node"
                                               : "the scene has no root nodes");
    if (r < 0 || r >= int(scene.roots.size())) return "scene " + std::to_string(r) + " does not exist";
    std::string name = "scene " + std::to_string(r);
    if (!scene.roots[std::size_t(r)].name.empty())
        name += " \"" + scene.roots[std::size_t(r)].name + "\"";
    if (scene.roots[std::size_t(r)].nodes.empty()) return name + " has no nodes";
    const Pose pose = evaluatePose(scene, r, 0.0);
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const int mesh = scene.nodes[i].mesh;
        if (!pose.visible[i] || mesh < 0) continue;
        for (const Primitive& p : scene.meshes[std::size_t(mesh)].primitives)
            if (p.elementCount() > 0) return std::nullopt;
    }
    return "no node of " + name + " draws a mesh with anything in it";
}

Result<void> selectMaterialVariant(Scene& scene, std::string_view name) {
    int variant = -1;
    if (!name.empty()) {
        for (std::size_t i = 0; i < scene.variants.size(); ++i)
            if (scene.variants[i] == name) variant = int(i);
        if (variant < 0) {
            std::string known;
            for (const std::string& v : scene.variants) known += (known.empty() ? "\"" : ", \"") + v + "\"";
            return makeError(ErrorCode::InvalidInput,
                             "no material variant \"" + std::string(name) + "\" (" +
                                 (known.empty() ? std::string("the scene has none")
                                                : "the scene's variants: " + known) +
                                 ")",
                             "--variant", scene.sourcePath);
        }
    }
    for (Mesh& mesh : scene.meshes)
        for (Primitive& p : mesh.primitives) {
            if (p.variantMaterials.empty()) continue;
            p.material = p.materialWithoutVariant;
            for (const Primitive::VariantMaterial& m : p.variantMaterials)
                if (m.variant == variant) p.material = m.material;
        }
    scene.activeVariant = variant;
    return {};
}

} // namespace lantern
