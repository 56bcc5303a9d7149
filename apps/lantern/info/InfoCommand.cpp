// `lantern info SCENE`: what a scene holds (nodes, meshes, triangles, materials, lights,
// cameras, animations, bounds) and the renderer features it needs. No GPU needed.
#include "common/CliSupport.h"
#include "common/Commands.h"

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

    std::size_t phong = 0, pbr = 0, unlit = 0, blend = 0, mask = 0, twoSidedMaterials = 0,
                textured = 0;
    for (const Material& m : scene.materials) {
        (m.unlit ? unlit : m.ambientFollowsDiffuse ? pbr : phong)++;
        if (m.alphaMode == AlphaMode::Blend) ++blend;
        if (m.alphaMode == AlphaMode::Mask) ++mask;
        if (m.back) ++twoSidedMaterials;
        if (m.baseColorTexture >= 0) ++textured;
    }
    std::size_t directional = 0, point = 0, spot = 0, glLights = 0;
    for (const Light& l : scene.lights) {
        (l.type == LightType::Directional ? directional
         : l.type == LightType::Point     ? point
                                          : spot)++;
        if (l.falloff == LightFalloff::Gl) ++glLights;
    }
    std::size_t perspective = 0, infinite = 0, frustum = 0, ortho = 0, lookAts = 0;
    for (const Camera& c : scene.cameras) {
        const ProjectionKind k = c.projection.kind;
        (k == ProjectionKind::Perspective ? perspective
         : k == ProjectionKind::Frustum   ? frustum
                                          : ortho)++;
        if (k != ProjectionKind::Orthographic && std::isinf(c.projection.zfar)) ++infinite;
        if (c.lookAt) ++lookAts;
    }
    double start = kInfinity, end = -kInfinity;
    std::size_t channels = 0;
    for (const Animation& an : scene.animations) {
        channels += an.channels.size();
        if (!an.samplers.empty()) {
            start = std::min(start, an.startTime());
            end = std::max(end, an.endTime());
        }
    }

    std::cout << "scene: " << a.scene << "\n";
    std::cout << "scenes: " << s.roots << " (default " << scene.defaultRoot << ")\n";
    for (std::size_t r = 0; r < scene.roots.size(); ++r) {
        const SceneRoot& sr = scene.roots[r];
        std::cout << "  " << r << (sr.name.empty() ? "" : " \"" + sr.name + "\"") << ": "
                  << sr.nodes.size() << " root nodes" << (sr.lighting ? ", LANTERN_lighting" : "")
                  << (int(r) == root ? "  <- shown" : "") << "\n";
    }
    std::cout << "nodes: " << s.nodes << "\n"
              << "meshes: " << s.meshes << " (" << s.primitives << " primitives, " << s.triangles
              << " triangles, " << s.vertices << " vertices)\n"
              << "materials: "
              << breakdown(s.materials, {{"phong", phong},
                                         {"pbr", pbr},
                                         {"unlit", unlit},
                                         {"blend", blend},
                                         {"mask", mask},
                                         {"two-sided", twoSidedMaterials},
                                         {"textured", textured}})
              << "\n"
              << "textures: " << s.textures << "\n"
              << "lights: "
              << breakdown(s.lights, {{"directional", directional},
                                      {"point", point},
                                      {"spot", spot},
                                      {"GL falloff", glLights}})
              << "\n"
              << "cameras: "
              << breakdown(s.cameras, {{"perspective", perspective},
                                       {"infinite far", infinite},
                                       {"frustum", frustum},
                                       {"orthographic", ortho},
                                       {"lookAt", lookAts}})
              << "\n"
              << "animations: " << s.animations;
    if (s.animations > 0)
        std::cout << " (" << channels << " channels, " << start << " s to " << end << " s)";
    std::cout << "\n";
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

} // namespace

Runner addInfoCommand(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd =
        app.add_subcommand("info", "Print what a scene holds and the features it needs");
    cmd->add_option("scene", args->scene, "glTF/GLB file, or builtin:NAME")->required();
    cmd->add_option("--scene", args->sceneIndex, "glTF scene index (default: the file's default)");
    cmd->add_option("--time", args->time, "Animation time in seconds for bounds and features")
        ->capture_default_str();
    cmd->add_option("--max-size", args->maxSize, "Largest file, buffer or image accepted, in bytes")
        ->capture_default_str();
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
