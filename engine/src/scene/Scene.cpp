// The scene model: names, node transforms, validation with object paths, pose evaluation and
// bounds.
#include <lantern/Scene.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace lantern {
namespace {

std::string at(const char* array, std::size_t i) {
    return std::string(array) + "[" + std::to_string(i) + "]";
}

bool finite(double v) { return std::isfinite(v); }
bool finite(const glm::dvec3& v) { return finite(v.x) && finite(v.y) && finite(v.z); }
bool finite(const glm::dvec4& v) { return finite(glm::dvec3(v)) && finite(v.w); }
bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Error invalid(const std::string& object, const std::string& message) {
    return makeError(ErrorCode::InvalidInput, message, object);
}

Result<void> validateSide(const MaterialSide& s, const std::string& object) {
    if (!finite(s.ambient)) return invalid(object + ".ambient", "non-finite colour");
    if (!finite(s.diffuse)) return invalid(object + ".diffuse", "non-finite colour");
    if (!finite(s.specular)) return invalid(object + ".specular", "non-finite colour");
    if (!finite(s.emission)) return invalid(object + ".emission", "non-finite colour");
    if (!finite(s.shininess))
        return invalid(object + ".shininess", "shininess must be a finite number");
    if (s.shininess < 0.0)
        return invalid(object + ".shininess",
                       "shininess must be >= 0, got " + std::to_string(s.shininess));
    return {};
}

Result<void> validatePrimitive(const Primitive& prim, const std::string& obj,
                               std::size_t materialCount) {
    const std::size_t n = prim.positions.size();
    if (prim.normals.size() != n)
        return invalid(obj, "has " + std::to_string(prim.normals.size()) + " normals for " +
                                std::to_string(n) + " positions");
    if (!prim.colors.empty() && prim.colors.size() != n)
        return invalid(obj, "has " + std::to_string(prim.colors.size()) + " colours for " +
                                std::to_string(n) + " positions");
    if (!prim.texcoords.empty() && prim.texcoords.size() != n)
        return invalid(obj, "has " + std::to_string(prim.texcoords.size()) +
                                " texture coordinates for " + std::to_string(n) + " positions");
    if (prim.indices.empty() && n % 3 != 0)
        return invalid(obj, "non-indexed triangle list with " + std::to_string(n) +
                                " vertices (not a multiple of 3)");
    if (prim.indices.size() % 3 != 0)
        return invalid(obj + ".indices", "index count " + std::to_string(prim.indices.size()) +
                                             " is not a multiple of 3");
    for (std::size_t i = 0; i < prim.indices.size(); ++i)
        if (prim.indices[i] >= n)
            return invalid(obj + "." + at("indices", i),
                           "index " + std::to_string(prim.indices[i]) +
                               " is out of range (vertex count " + std::to_string(n) + ")");
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(prim.positions[i]))
            return invalid(obj + "." + at("positions", i), "non-finite position");
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(prim.normals[i]))
            return invalid(obj + "." + at("normals", i), "non-finite normal");
    for (std::size_t i = 0; i < prim.colors.size(); ++i)
        if (!finite(glm::vec3(prim.colors[i])) || !std::isfinite(prim.colors[i].w))
            return invalid(obj + "." + at("colors", i), "non-finite colour");
    for (std::size_t i = 0; i < prim.texcoords.size(); ++i)
        if (!std::isfinite(prim.texcoords[i].x) || !std::isfinite(prim.texcoords[i].y))
            return invalid(obj + "." + at("texcoords", i), "non-finite texture coordinate");
    if (prim.material < -1 || prim.material >= int(materialCount))
        return invalid(obj + ".material",
                       "material " + std::to_string(prim.material) + " does not exist");
    return {};
}

Result<void> validateMeshes(const Scene& scene) {
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (std::size_t p = 0; p < scene.meshes[m].primitives.size(); ++p)
            LANTERN_TRY(validatePrimitive(scene.meshes[m].primitives[p],
                                          at("meshes", m) + "." + at("primitives", p),
                                          scene.materials.size()));
    return {};
}

Result<void> validateMaterials(const Scene& scene) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& mat = scene.materials[i];
        const std::string obj = at("materials", i);
        LANTERN_TRY(validateSide(mat.front, obj));
        if (mat.back) LANTERN_TRY(validateSide(*mat.back, obj + ".back"));
        if (!finite(mat.alphaCutoff) || mat.alphaCutoff < 0.0)
            return invalid(obj + ".alphaCutoff", "alpha cutoff must be a finite number >= 0");
        if (mat.baseColorTexture < -1 || mat.baseColorTexture >= int(scene.textures.size()))
            return invalid(obj + ".baseColorTexture",
                           "texture " + std::to_string(mat.baseColorTexture) + " does not exist");
    }
    return {};
}

Result<void> validateTextures(const Scene& scene) {
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        if (t.width <= 0 || t.height <= 0 ||
            t.rgba8.size() != std::size_t(t.width) * std::size_t(t.height) * 4)
            return invalid(at("textures", i), "texture size and pixel data do not match");
    }
    return {};
}

Result<void> validateLight(const Light& l, const std::string& obj) {
    if (!finite(l.ambient) || !finite(l.diffuse) || !finite(l.specular))
        return invalid(obj, "non-finite light colour");
    if (!finite(l.attenuation))
        return invalid(obj + ".attenuation", "non-finite attenuation coefficient");
    if (l.attenuation.x < 0 || l.attenuation.y < 0 || l.attenuation.z < 0)
        return invalid(obj + ".attenuation", "attenuation coefficients must be >= 0");
    if (l.attenuation.x == 0 && l.attenuation.y == 0 && l.attenuation.z == 0)
        return invalid(obj + ".attenuation",
                       "attenuation coefficients are all zero (infinite light)");
    if (!finite(l.spotExponent) || l.spotExponent < 0)
        return invalid(obj + ".spotExponent", "spot exponent must be a finite number >= 0");
    if (!finite(l.spotCutoffDeg) ||
        !((l.spotCutoffDeg >= 0 && l.spotCutoffDeg <= 90) || l.spotCutoffDeg == 180))
        return invalid(obj + ".spotCutoffDeg",
                       "spot cutoff " + std::to_string(l.spotCutoffDeg) +
                           " is outside [0, 90] and not 180 (GL's no-cone value): a cone "
                           "wider than a half-space is not a spot light");
    if (std::isnan(l.range) || !(l.range > 0)) return invalid(obj + ".range", "range must be > 0");
    if (!finite(l.innerConeAngle) || !finite(l.outerConeAngle) || l.innerConeAngle < 0 ||
        !(l.innerConeAngle < l.outerConeAngle) || l.outerConeAngle > 1.5707963267948966)
        return invalid(obj, "spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    return {};
}

Result<void> validateLights(const Scene& scene) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        LANTERN_TRY(validateLight(scene.lights[i], at("lights", i)));
    return {};
}

Result<void> validateCameras(const Scene& scene) {
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        const std::string obj = at("cameras", i);
        LANTERN_TRY(checkProjection(scene.cameras[i].projection, obj));
        if (scene.cameras[i].lookAt)
            LANTERN_TRY(checkLookAt(*scene.cameras[i].lookAt, obj + ".lookAt"));
    }
    return {};
}

// One node's references and transform; its children are checked by validateNodes.
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

// With one parent per node, a cycle is a chain of parents that never reaches a root.
Result<void> checkNoCycles(const std::vector<int>& parent) {
    for (std::size_t i = 0; i < parent.size(); ++i) {
        int p = parent[i];
        std::size_t steps = 0;
        while (p != -1 && steps <= parent.size()) {
            p = parent[p];
            ++steps;
        }
        if (p != -1) return invalid(at("nodes", i), "node hierarchy contains a cycle");
    }
    return {};
}

// Nodes: references in range, finite transforms, a forest (one parent, no cycles). Returns each
// node's parent (-1 for none).
Result<std::vector<int>> validateNodes(const Scene& scene) {
    const std::vector<Node>& nodes = scene.nodes;
    std::vector<int> parent(nodes.size(), -1);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const Node& nd = nodes[i];
        const std::string obj = at("nodes", i);
        LANTERN_TRY(validateNode(scene, nd, obj));
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
    if (scene.nodes[ch.node].matrix)
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

Result<void> Scene::validate() const {
    LANTERN_TRY(validateMeshes(*this));
    LANTERN_TRY(validateMaterials(*this));
    LANTERN_TRY(validateTextures(*this));
    LANTERN_TRY(validateLights(*this));
    LANTERN_TRY(validateCameras(*this));
    Result<std::vector<int>> parent = validateNodes(*this);
    if (!parent) return std::move(parent).error();
    LANTERN_TRY(validateAnimations(*this));
    return validateRoots(*this, *parent);
}

Pose evaluatePose(const Scene& scene, int root, double time) {
    Pose pose;
    pose.root = root < 0 ? scene.defaultRoot : root;
    pose.time = time;
    const std::size_t n = scene.nodes.size();
    pose.worldFromNode.assign(n, glm::dmat4(1.0));
    pose.visible.assign(n, false);

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
            const glm::dvec4 v = sampleAnimation(anim.samplers[ch.sampler], ch.path, time);
            switch (ch.path) {
            case AnimationPath::Translation: t[ch.node] = glm::dvec3(v); break;
            case AnimationPath::Scale: s[ch.node] = glm::dvec3(v); break;
            case AnimationPath::Rotation: r[ch.node] = glm::dquat(v.w, v.x, v.y, v.z); break;
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
    if (pose.root < 0 || pose.root >= int(scene.roots.size())) return pose;
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
    return pose;
}

Bounds computeBounds(const Scene& scene, const Pose& pose) {
    Bounds b;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        if (!pose.visible[i] || scene.nodes[i].mesh < 0) continue;
        const glm::dmat4& m = pose.worldFromNode[i];
        for (const Primitive& prim : scene.meshes[scene.nodes[i].mesh].primitives) {
            if (prim.positions.empty()) continue;
            Bounds local;
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
            s.vertices += p.positions.size();
        }
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
            if (p.triangleCount() > 0) return std::nullopt;
    }
    return "no node of " + name + " draws a mesh with anything in it";
}

} // namespace lantern
