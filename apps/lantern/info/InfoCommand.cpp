// `lantern info SCENE`: what a scene holds (nodes, meshes, triangles, materials, lights,
// cameras, animations, bounds) and the renderer features it needs. No GPU needed.
#include "common/CliSupport.h"
#include "common/Commands.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

namespace lantern::cli {
namespace {

struct InfoArgs {
    std::string scene;
    int sceneIndex = -1;
    double time = 0.0;
    std::uint64_t maxSize = std::uint64_t(1) << 30;
};

/// "3 (a 2, b 1)": a total and its non-zero parts in a fixed order.
std::string breakdown(std::size_t total,
                      const std::vector<std::pair<const char*, std::size_t>>& parts) {
    std::ostringstream s;
    s << total;
    std::string inner;
    for (const auto& [name, n] : parts)
        if (n > 0)
            inner += (inner.empty() ? "" : ", ") + std::string(name) + " " + std::to_string(n);
    if (!inner.empty()) s << " (" << inner << ")";
    return s.str();
}

std::string vec(const glm::dvec3& v) {
    std::ostringstream s;
    s << "[" << v.x << ", " << v.y << ", " << v.z << "]";
    return s.str();
}

// What the scene's materials, lights, cameras and animations are, counted by kind.
struct Kinds {
    std::size_t phong = 0, pbr = 0, unlit = 0, blend = 0, mask = 0, twoSidedMaterials = 0,
                textured = 0;
    std::size_t directional = 0, point = 0, spot = 0, glLights = 0;
    std::size_t perspective = 0, infinite = 0, frustum = 0, ortho = 0, lookAts = 0;
    double start = kInfinity, end = -kInfinity; ///< the animations' time range
    std::size_t channels = 0;
};

Kinds countKinds(const Scene& scene) {
    Kinds k;
    for (const Material& m : scene.materials) {
        (m.unlit ? k.unlit : m.ambientFollowsDiffuse ? k.pbr : k.phong)++;
        if (m.alphaMode == AlphaMode::Blend) ++k.blend;
        if (m.alphaMode == AlphaMode::Mask) ++k.mask;
        if (m.back) ++k.twoSidedMaterials;
        if (m.baseColorTexture >= 0) ++k.textured;
    }
    for (const Light& l : scene.lights) {
        (l.type == LightType::Directional ? k.directional
         : l.type == LightType::Point     ? k.point
                                          : k.spot)++;
        if (l.falloff == LightFalloff::Gl) ++k.glLights;
    }
    for (const Camera& c : scene.cameras) {
        const ProjectionKind p = c.projection.kind;
        (p == ProjectionKind::Perspective ? k.perspective
         : p == ProjectionKind::Frustum   ? k.frustum
                                          : k.ortho)++;
        if (p != ProjectionKind::Orthographic && std::isinf(c.projection.zfar)) ++k.infinite;
        if (c.lookAt) ++k.lookAts;
    }
    for (const Animation& an : scene.animations) {
        k.channels += an.channels.size();
        if (!an.samplers.empty()) {
            k.start = std::min(k.start, an.startTime());
            k.end = std::max(k.end, an.endTime());
        }
    }
    return k;
}

// The scene's roots (glTF scenes), the one shown marked.
void printRoots(const InfoArgs& a, const Scene& scene, const SceneSummary& s, int root) {
    std::cout << "scene: " << a.scene << "\n";
    std::cout << "scenes: " << s.roots << " (default " << scene.defaultRoot << ")\n";
    for (std::size_t r = 0; r < scene.roots.size(); ++r) {
        const SceneRoot& sr = scene.roots[r];
        std::cout << "  " << r << (sr.name.empty() ? "" : " \"" + sr.name + "\"") << ": "
                  << sr.nodes.size() << " root nodes" << (sr.lighting ? ", LANTERN_lighting" : "")
                  << (int(r) == root ? "  <- shown" : "") << "\n";
    }
}

void printCounts(const SceneSummary& s, const Kinds& k) {
    std::cout << "nodes: " << s.nodes << "\n"
              << "meshes: " << s.meshes << " (" << s.primitives << " primitives, " << s.triangles
              << " triangles, " << s.vertices << " vertices)\n"
              << "materials: "
              << breakdown(s.materials, {{"phong", k.phong},
                                         {"pbr", k.pbr},
                                         {"unlit", k.unlit},
                                         {"blend", k.blend},
                                         {"mask", k.mask},
                                         {"two-sided", k.twoSidedMaterials},
                                         {"textured", k.textured}})
              << "\n"
              << "textures: " << s.textures << "\n"
              << "lights: "
              << breakdown(s.lights, {{"directional", k.directional},
                                      {"point", k.point},
                                      {"spot", k.spot},
                                      {"GL falloff", k.glLights}})
              << "\n"
              << "cameras: "
              << breakdown(s.cameras, {{"perspective", k.perspective},
                                       {"infinite far", k.infinite},
                                       {"frustum", k.frustum},
                                       {"orthographic", k.ortho},
                                       {"lookAt", k.lookAts}})
              << "\n"
              << "animations: " << s.animations;
    if (s.animations > 0)
        std::cout << " (" << k.channels << " channels, " << k.start << " s to " << k.end << " s)";
    std::cout << "\n";
}

// The bounds at --time, the renderer features the scene needs and their pipeline variants.
int printBoundsAndFeatures(const InfoArgs& a, const Scene& scene, int root) {
    const Bounds b = computeBounds(scene, evaluatePose(scene, root, a.time));
    if (!b.empty())
        std::cout << "bounds: " << vec(b.min) << " - " << vec(b.max) << " (scene " << root
                  << ", t = " << a.time << " s)\n";
    else
        std::cout << "bounds: empty (nothing drawn)\n";
    RenderOptions options;
    options.root = a.sceneIndex;
    auto features = explainScene(scene, options, a.time);
    if (!features) return report(features.error());
    std::cout << "features:\n";
    for (const std::string& f : features->features)
        std::cout << "  " << f << "\n";
    std::cout << "pipeline variants:\n";
    for (const std::string& v : features->variants)
        std::cout << "  " << v << "\n";
    return kOk;
}

int run(const InfoArgs& a) {
    LoadOptions load;
    load.maxBytes = a.maxSize;
    load.log = stderrSink(false);
    auto loaded = loadScene(a.scene, load);
    if (!loaded) return report(loaded.error());
    const Scene& scene = *loaded;
    if (a.sceneIndex < -1 || a.sceneIndex >= int(scene.roots.size()))
        return report(makeError(ErrorCode::InvalidInput,
                                "scene " + std::to_string(a.sceneIndex) +
                                    " does not exist (the file has " +
                                    std::to_string(scene.roots.size()) + " scenes)",
                                "--scene"));
    if (!std::isfinite(a.time))
        return report(makeError(ErrorCode::InvalidInput, "time must be a finite number", "--time"));
    const int root = a.sceneIndex < 0 ? scene.defaultRoot : a.sceneIndex;
    const SceneSummary s = summarize(scene);
    const Kinds kinds = countKinds(scene);
    printRoots(a, scene, s, root);
    printCounts(s, kinds);
    return printBoundsAndFeatures(a, scene, root);
}

} // namespace

Runner addInfoCommand(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd =
        app.add_subcommand("info", "Print what a scene holds and the features it needs");
    cmd->add_option("scene", args->scene, "glTF/GLB file, or builtin:NAME")->required();
    cmd->add_option("--scene", args->sceneIndex, "glTF scene index (default: the file's default)");
    cmd->add_option("--time", args->time, "Animation time in seconds for bounds and features")
        ->capture_default_str();
    addMaxSizeOption(*cmd, args->maxSize);
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
