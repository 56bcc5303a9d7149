// glTF (after validation) -> Lantern's scene model, the whole model: nodes, scenes
// (LANTERN_lighting) and animations here, materials in GltfMaterials.cpp, lights and cameras in
// GltfLightsCameras.cpp, meshes in GltfGeometry.cpp; and the checked reading of extensions
// (ExtensionReader). Every value is checked where it is read; messages carry the glTF object path.
#include "io/gltf/GltfInternal.h"

#include <lantern/Image.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <tuple>

namespace lantern::gltf {

glm::dvec3 vec3(const std::vector<double>& v) {
    return {v[0], v[1], v[2]};
}
glm::dvec4 vec4(const std::vector<double>& v) {
    return {v[0], v[1], v[2], v.size() > 3 ? v[3] : 1.0};
}

bool allFinite(const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

Error inFile(Error e, const Diagnostics& diag) {
    e.file = diag.file();
    return e;
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name) {
    auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

int extensionSource(const tinygltf::Texture& texture, const char* name) {
    const tinygltf::Value* ext = extension(texture.extensions, name);
    if (!ext || !ext->IsObject() || !ext->Has("source")) return -1;
    const tinygltf::Value& source = ext->Get("source");
    // The JSON pass (GltfSchema) made it an integer in 0..2^31-1, read as int or real.
    return source.IsInt() ? source.Get<int>() : source.IsNumber() ? int(source.GetNumberAsDouble()) : -1;
}

namespace {

// --- Nodes and scenes ----------------------------------------------------------------------

// The node's semantic id, from its extras {"semantic_id": N} (docs/aovs.md): an integer in
// 0 .. 2^32 - 2 (2^32 - 1 is kNoId, the background of the other id planes).
Result<std::optional<std::uint32_t>> readSemantic(const tinygltf::Value& extras,
                                                  const std::string& obj, const Diagnostics& diag) {
    if (!extras.IsObject() || !extras.Has("semantic_id")) return std::optional<std::uint32_t>{};
    const tinygltf::Value& v = extras.Get("semantic_id");
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d < double(kNoId) && d == std::floor(d)))
        return diag.error(obj + ".extras.semantic_id",
                          "must be an integer from 0 to 4294967294");
    return std::optional<std::uint32_t>(std::uint32_t(d));
}

Result<Node> convertNode(const tinygltf::Node& src, std::size_t index, const Diagnostics& diag) {
    const std::string obj = at("nodes", index);
    Node n;
    auto semantic = readSemantic(src.extras, obj, diag);
    if (!semantic) return std::move(semantic).error();
    n.semantic = *semantic;
    n.name = src.name;
    n.mesh = src.mesh;
    n.camera = src.camera;
    n.children = src.children;
    if (auto it = src.extensions.find("KHR_lights_punctual"); it != src.extensions.end())
        n.light = it->second.Get("light").GetNumberAsInt();
    n.skin = src.skin;
    if (!allFinite(src.weights)) return diag.error(obj + ".weights", "contains a non-finite number");
    n.weights = src.weights;
    for (auto [name, values] :
         {std::pair{"matrix", &src.matrix}, std::pair{"translation", &src.translation},
          std::pair{"rotation", &src.rotation}, std::pair{"scale", &src.scale}})
        if (!allFinite(*values))
            return diag.error(obj + "." + name, "contains a non-finite number");
    if (!src.matrix.empty()) {
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                m[c][r] = src.matrix[std::size_t(c * 4 + r)];
        if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
            return diag.error(obj + ".matrix", "last row must be 0, 0, 0, 1 (a projective "
                                               "matrix is not a node transform)");
        n.matrix = m;
        return n;
    }
    if (!src.translation.empty()) n.translation = vec3(src.translation);
    if (!src.scale.empty()) n.scale = vec3(src.scale);
    if (!src.rotation.empty()) {
        const glm::dquat q(src.rotation[3], src.rotation[0], src.rotation[1], src.rotation[2]);
        const double len = glm::length(q);
        if (!(len > 0.0)) return diag.error(obj + ".rotation", "quaternion has zero length");
        if (std::abs(len - 1.0) > 1e-3)
            diag.warn(obj + ".rotation",
                      "quaternion length " + std::to_string(len) + " is not 1; normalised");
        n.rotation = q / len;
    }
    return n;
}

Result<std::optional<LightingModel>> convertLighting(const tinygltf::Scene& src, std::size_t index,
                                                     const Diagnostics& diag) {
    const tinygltf::Value* e = extension(src.extensions, "LANTERN_lighting");
    if (!e) return std::optional<LightingModel>{};
    ExtensionReader r(*e, at("scenes", index) + ".extensions.LANTERN_lighting", diag);
    r.warnUnknown({"globalAmbient", "localViewer", "twoSided", "shading", "specular"});
    LightingModel model;
    model.globalAmbient = r.vec3("globalAmbient", model.globalAmbient);
    model.localViewer = r.boolean("localViewer", model.localViewer);
    if (r.has("twoSided")) model.twoSided = r.boolean("twoSided", false);
    const std::string shading = r.string("shading", "phong");
    const std::string specular = r.string("specular", "blinn");
    LANTERN_TRY(r.status());
    const auto mode = parseShadingMode(shading);
    if (!mode)
        return diag.error(r.object() + ".shading",
                          "\"" + shading + "\" is not flat, gouraud or phong");
    model.shading = *mode;
    const auto spec = parseSpecularModel(specular);
    if (!spec)
        return diag.error(r.object() + ".specular", "\"" + specular + "\" is not blinn or phong");
    model.specular = *spec;
    return std::optional<LightingModel>(model);
}

// --- Skins ------------------------------------------------------------------------------------

Result<Skin> convertSkin(const tinygltf::Model& model, std::size_t index, const Diagnostics& diag) {
    const tinygltf::Skin& src = model.skins[index];
    const std::string obj = at("skins", index);
    Skin skin;
    skin.name = src.name;
    skin.joints = src.joints;
    skin.skeleton = src.skeleton;
    skin.inverseBind.assign(src.joints.size(), glm::dmat4(1.0));
    if (src.inverseBindMatrices >= 0) {
        auto m = readDoubles(model, src.inverseBindMatrices, obj + ".inverseBindMatrices", diag);
        if (!m) return std::move(m).error();
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    skin.inverseBind[j][c][r] = (*m)[j * 16 + std::size_t(c * 4 + r)];
    }
    // The skeleton root is a hint (glTF): it must be an ancestor of (or be) every joint.
    if (skin.skeleton >= 0) {
        std::vector<int> parent(model.nodes.size(), -1);
        for (std::size_t i = 0; i < model.nodes.size(); ++i)
            for (int c : model.nodes[i].children)
                if (c >= 0 && std::size_t(c) < parent.size()) parent[std::size_t(c)] = int(i);
        for (int joint : skin.joints) {
            int n = joint;
            for (std::size_t steps = 0; n != -1 && n != skin.skeleton && steps <= parent.size();
                 ++steps)
                n = parent[std::size_t(n)];
            if (n != skin.skeleton) {
                diag.warn(obj + ".skeleton", "node " + std::to_string(skin.skeleton) +
                                                 " is not an ancestor of joint node " +
                                                 std::to_string(joint) +
                                                 "; the hint is ignored (joints are placed by "
                                                 "their own nodes)");
                skin.skeleton = -1;
                break;
            }
        }
    }
    return skin;
}

// Warns where a mesh with skin attributes is drawn by a node without a skin (drawn unskinned),
// and clears morph weights that name targets no primitive kept.
void checkSkinUse(Scene& scene, const Diagnostics& diag) {
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        Node& n = scene.nodes[i];
        if (n.mesh < 0) continue;
        const Mesh& mesh = scene.meshes[std::size_t(n.mesh)];
        if (mesh.primitives.empty()) n.weights.clear();
        if (n.skin >= 0) continue;
        for (const Primitive& p : mesh.primitives)
            if (!p.joints0.empty()) {
                diag.warn(at("nodes", i), "draws mesh " + std::to_string(n.mesh) +
                                              ", which has skin weights, without a skin; "
                                              "drawn in its bind pose");
                break;
            }
    }
}

// --- Animations -----------------------------------------------------------------------------

Result<AnimationSampler> convertSampler(const tinygltf::Model& model,
                                        const tinygltf::AnimationSampler& src, AnimationPath path,
                                        std::size_t weightCount, const std::string& obj,
                                        const Diagnostics& diag) {
    AnimationSampler s;
    s.interpolation = src.interpolation == "STEP"          ? Interpolation::Step
                      : src.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                           : Interpolation::Linear;
    auto times = readDoubles(model, src.input, obj + ".input", diag);
    if (!times) return std::move(times).error();
    for (std::size_t k = 0; k < times->size(); ++k) {
        const double t = (*times)[k];
        if (t < 0.0)
            return diag.error(obj + ".input", "key time " + std::to_string(k) + " (" +
                                                  std::to_string(t) + ") is negative");
        if (k > 0 && !(t > (*times)[k - 1]))
            return diag.error(obj + ".input", "key times are not strictly increasing at key " +
                                                  std::to_string(k) + " (" + std::to_string(t) +
                                                  " after " + std::to_string((*times)[k - 1]) +
                                                  ")");
    }
    s.times = std::move(*times);
    auto values = readDoubles(model, src.output, obj + ".output", diag);
    if (!values) return std::move(values).error();
    if (path == AnimationPath::Weights) {
        const std::size_t per = s.interpolation == Interpolation::CubicSpline ? 3 : 1;
        const std::size_t keys = s.times.size() * per;
        if (keys == 0 || values->size() % keys != 0 || values->size() / keys != weightCount)
            return diag.error(obj + ".output",
                              "has " + std::to_string(values->size()) + " values for " +
                                  std::to_string(s.times.size()) + " keys of " +
                                  std::to_string(weightCount) +
                                  " morph weights (expected " +
                                  std::to_string(keys * weightCount) + ")");
        s.weights = std::move(*values);
        s.weightCount = weightCount;
        return s;
    }
    const std::size_t n = path == AnimationPath::Rotation ? 4 : 3;
    s.values.resize(values->size() / n);
    for (std::size_t i = 0; i < s.values.size(); ++i)
        s.values[i] = glm::dvec4((*values)[i * n], (*values)[i * n + 1], (*values)[i * n + 2],
                                 n == 4 ? (*values)[i * n + 3] : 0.0);
    return s;
}

Result<Animation> convertAnimation(const tinygltf::Model& model, const Scene& scene,
                                   std::size_t index, const Diagnostics& diag) {
    const tinygltf::Animation& src = model.animations[index];
    const std::string obj = at("animations", index);
    Animation a;
    a.name = src.name;
    // Samplers are converted for the channels Lantern plays, once per (sampler, path): a
    // sampler's output is read as vec3 or quaternion depending on the path it drives.
    std::map<std::tuple<int, AnimationPath, std::size_t>, int> converted;
    for (std::size_t c = 0; c < src.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = src.channels[c];
        const std::string cobj = obj + "." + at("channels", c);
        if (ch.target_node < 0) continue; // glTF: a channel without a node is ignored
        if (ch.target_path == "pointer") continue; // KHR_animation_pointer: warned, not played
        AnimationPath path;
        if (ch.target_path == "translation")
            path = AnimationPath::Translation;
        else if (ch.target_path == "rotation")
            path = AnimationPath::Rotation;
        else if (ch.target_path == "scale")
            path = AnimationPath::Scale;
        else
            path = AnimationPath::Weights;
        // Morph weights: one per morph target of the node's mesh (as converted).
        std::size_t weightCount = 0;
        if (path == AnimationPath::Weights) {
            const int mesh = scene.nodes[std::size_t(ch.target_node)].mesh;
            weightCount = mesh >= 0 && !scene.meshes[std::size_t(mesh)].primitives.empty()
                              ? scene.meshes[std::size_t(mesh)].primitives[0].targets.size()
                              : 0;
            if (weightCount == 0) {
                diag.warn(cobj, "animates the morph weights of node " +
                                    std::to_string(ch.target_node) +
                                    ", which draws no morph targets; channel skipped");
                continue;
            }
        } else if (!model.nodes[std::size_t(ch.target_node)].matrix.empty())
            return diag.error(cobj + ".target.node",
                              "node " + std::to_string(ch.target_node) +
                                  " has a matrix; only translation/rotation/scale nodes can be "
                                  "animated");
        const auto key = std::tuple{ch.sampler, path, weightCount};
        auto found = converted.find(key);
        if (found == converted.end()) {
            auto s = convertSampler(model, src.samplers[std::size_t(ch.sampler)], path,
                                    weightCount,
                                    obj + "." + at("samplers", std::size_t(ch.sampler)), diag);
            if (!s) return std::move(s).error();
            a.samplers.push_back(std::move(*s));
            found = converted.emplace(key, int(a.samplers.size()) - 1).first;
        }
        a.channels.push_back({ch.target_node, path, found->second});
    }
    return a;
}

} // namespace

// --- ExtensionReader ------------------------------------------------------------------------

void ExtensionReader::fail(const std::string& key, const std::string& message) const {
    if (!*m_error) *m_error = m_diag.error(path(key), message);
}

Result<void> ExtensionReader::status() const {
    if (*m_error) return **m_error;
    return {};
}

double ExtensionReader::number(const std::string& key, double fallback) const {
    if (!m_value.Has(key)) return fallback;
    const tinygltf::Value& v = m_value.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) {
        fail(key, "must be a finite number");
        return fallback;
    }
    return v.GetNumberAsDouble();
}

std::optional<std::vector<double>> ExtensionReader::numbers(const std::string& key, std::size_t n,
                                                            std::size_t alsoN) const {
    if (!m_value.Has(key)) return std::nullopt;
    const tinygltf::Value& v = m_value.Get(key);
    const std::size_t len = v.IsArray() ? v.ArrayLen() : 0;
    if (!v.IsArray() || !(len == n || (alsoN != 0 && len == alsoN))) {
        fail(key, "must be an array of " + std::to_string(n) +
                      (alsoN ? " (or " + std::to_string(alsoN) + ")" : std::string()) + " numbers");
        return std::nullopt;
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < len; ++i) {
        const tinygltf::Value& e = v.Get(int(i));
        if (!e.IsNumber() || !std::isfinite(e.GetNumberAsDouble())) {
            fail(key, "element " + std::to_string(i) + " is not a finite number");
            return std::nullopt;
        }
        out.push_back(e.GetNumberAsDouble());
    }
    return out;
}

glm::dvec2 ExtensionReader::vec2(const std::string& key, const glm::dvec2& fallback) const {
    const auto v = numbers(key, 2, 0);
    return v ? glm::dvec2((*v)[0], (*v)[1]) : fallback;
}

glm::dvec3 ExtensionReader::vec3(const std::string& key, const glm::dvec3& fallback) const {
    const auto v = numbers(key, 3, 0);
    return v ? glm::dvec3((*v)[0], (*v)[1], (*v)[2]) : fallback;
}

glm::dvec4 ExtensionReader::rgba(const std::string& key, const glm::dvec4& fallback) const {
    const auto v = numbers(key, 4, 3);
    return v ? glm::dvec4((*v)[0], (*v)[1], (*v)[2], v->size() > 3 ? (*v)[3] : 1.0) : fallback;
}

bool ExtensionReader::boolean(const std::string& key, bool fallback) const {
    if (!m_value.Has(key)) return fallback;
    const tinygltf::Value& v = m_value.Get(key);
    if (!v.IsBool()) {
        fail(key, "must be true or false");
        return fallback;
    }
    return v.Get<bool>();
}

std::string ExtensionReader::string(const std::string& key, const std::string& fallback) const {
    if (!m_value.Has(key)) return fallback;
    const tinygltf::Value& v = m_value.Get(key);
    if (!v.IsString()) {
        fail(key, "must be a string");
        return fallback;
    }
    return v.Get<std::string>();
}

std::optional<ExtensionReader> ExtensionReader::child(const std::string& key) const {
    if (!m_value.Has(key) || !m_value.Get(key).IsObject()) return std::nullopt;
    ExtensionReader c(m_value.Get(key), path(key), m_diag);
    c.m_error = m_error;
    return c;
}

void ExtensionReader::warnUnknown(std::initializer_list<const char*> known) const {
    for (const std::string& k : m_value.Keys())
        if (std::none_of(known.begin(), known.end(), [&](const char* n) { return k == n; }))
            m_diag.warn(path(k), "unknown member ignored");
}

// --- The whole model --------------------------------------------------------------------------

Result<Scene> convertModel(const tinygltf::Model& model, const RawFacts& raw,
                           const ImageStore& images, const LoadOptions& options,
                           const Diagnostics& diag) {
    Scene scene;
    scene.sourcePath = diag.file();

    LANTERN_TRY(convertMaterials(model, raw, images, options, diag, scene));
    auto variants = variantNames(model, diag);
    if (!variants) return std::move(variants).error();
    scene.variants = std::move(*variants);
    // Exactly as many as the model has (loadBytes charged these sizes to the budget).
    scene.meshes.reserve(model.meshes.size());
    scene.lights.reserve(model.lights.size());
    scene.cameras.reserve(model.cameras.size());
    scene.nodes.reserve(model.nodes.size());
    scene.skins.reserve(model.skins.size());
    for (std::size_t i = 0; i < model.meshes.size(); ++i) {
        auto m = convertMesh(model, i, diag);
        if (!m) return std::move(m).error();
        scene.meshes.push_back(std::move(*m));
    }
    for (std::size_t i = 0; i < model.lights.size(); ++i) {
        auto l = convertLight(model.lights[i], i, diag);
        if (!l) return inFile(std::move(l).error(), diag);
        scene.lights.push_back(std::move(*l));
    }
    for (std::size_t i = 0; i < model.cameras.size(); ++i) {
        const bool hasZfar = i < raw.perspectiveHasZfar.size() && raw.perspectiveHasZfar[i];
        auto c = convertCamera(model.cameras[i], i, hasZfar, diag);
        if (!c) return inFile(std::move(c).error(), diag);
        scene.cameras.push_back(std::move(*c));
    }
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        auto n = convertNode(model.nodes[i], i, diag);
        if (!n) return std::move(n).error();
        scene.nodes.push_back(std::move(*n));
    }
    for (std::size_t i = 0; i < model.skins.size(); ++i) {
        auto skin = convertSkin(model, i, diag);
        if (!skin) return std::move(skin).error();
        scene.skins.push_back(std::move(*skin));
    }
    checkSkinUse(scene, diag);
    LANTERN_TRY(expandInstances(model, diag, scene));
    for (std::size_t i = 0; i < model.scenes.size(); ++i) {
        SceneRoot root;
        root.name = model.scenes[i].name;
        root.nodes = model.scenes[i].nodes;
        auto lighting = convertLighting(model.scenes[i], i, diag);
        if (!lighting) return inFile(std::move(lighting).error(), diag);
        root.lighting = *lighting;
        scene.roots.push_back(std::move(root));
    }
    if (scene.roots.empty() && !scene.nodes.empty()) {
        // glTF lets a file have nodes but no scene; draw every node that has no parent.
        std::vector<bool> isChild(scene.nodes.size(), false);
        for (const Node& n : scene.nodes)
            for (int c : n.children)
                isChild[std::size_t(c)] = true;
        SceneRoot root;
        root.name = "all root nodes";
        for (std::size_t i = 0; i < scene.nodes.size(); ++i)
            if (!isChild[i]) root.nodes.push_back(int(i));
        diag.warn("scenes", "the file defines no scene; drawing all " +
                                std::to_string(root.nodes.size()) + " root nodes");
        scene.roots.push_back(std::move(root));
    }
    scene.defaultRoot = model.defaultScene >= 0 ? model.defaultScene : 0;
    for (std::size_t i = 0; i < model.animations.size(); ++i) {
        auto a = convertAnimation(model, scene, i, diag);
        if (!a) return std::move(a).error();
        scene.animations.push_back(std::move(*a));
    }
    return scene;
}

} // namespace lantern::gltf
