// `lantern info SCENE`: what a scene holds (nodes, meshes, triangles, materials, lights,
// cameras, animations, bounds) and the renderer features it needs; no GPU needed.
// `lantern info --devices`: the Vulkan devices, the one Lantern would choose and why, where
// pipelines are cached, and whether `lantern view` has a display.
#include "common/FidelityReport.h"
#include "common/CliSupport.h"
#include "common/Commands.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

namespace lantern::cli {
namespace {

struct InfoArgs {
    std::string scene;
    bool devices = false;
    std::string deviceName;
    int sceneIndex = -1;
    double time = 0.0;
    SceneFileOptions file;  ///< --max-size, --variant, --allow-folder, --up
    bool json = false;      ///< --json
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

// "185.8 MiB (24.6 B per triangle)": what the scene's arrays hold in host memory.
std::string hostMemory(const SceneSummary& s) {
    char text[96];
    std::snprintf(text, sizeof text, "%.1f MiB", double(s.hostBytes) / 1048576.0);
    std::string out = text;
    if (s.triangles > 0) {
        std::snprintf(text, sizeof text, " (%.1f B per triangle)",
                      double(s.hostBytes) / double(s.triangles));
        out += text;
    }
    return out;
}

void printCounts(const SceneSummary& s, const Kinds& k) {
    std::cout << "nodes: " << s.nodes << "\n"
              << "meshes: " << s.meshes << " (" << s.primitives << " primitives, " << s.triangles
              << " triangles, "
              << (s.lines ? std::to_string(s.lines) + " lines, " : std::string())
              << (s.points ? std::to_string(s.points) + " points, " : std::string()) << s.vertices
              << " vertices)\n"
              << "host memory: " << hostMemory(s) << "\n"
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

// What the file uses and how each is drawn (the fidelity report, `--json` has the objects).
void printFileFeatures(const Scene& scene) {
    if (scene.features.empty()) return;
    std::cout << "file features (docs/scene-format-support.md):\n";
    for (const FeatureUse& f : scene.features)
        std::cout << "  " << f.key << ": " << toString(f.fidelity)
                  << (f.rule.empty() ? "" : " (" + f.rule + ")") << ", " << f.count
                  << (f.count == 1 ? " use" : " uses") << "\n";
}

// The whole of `info` as one JSON document: the fidelity report, the counts, the renderer's
// features and pipeline variants.
int printJson(const InfoArgs& a, const Scene& scene, int root) {
    nlohmann::ordered_json j = sceneReport(a.scene, scene, std::nullopt);
    const SceneSummary s = summarize(scene);
    j["counts"] = {{"nodes", s.nodes},           {"meshes", s.meshes},
                   {"primitives", s.primitives}, {"triangles", s.triangles},
                   {"lines", s.lines},           {"points", s.points},
                   {"vertices", s.vertices},     {"materials", s.materials},
                   {"textures", s.textures},     {"lights", s.lights},
                   {"cameras", s.cameras},       {"animations", s.animations},
                   {"host_bytes", s.hostBytes}};
    RenderOptions options;
    options.root = root;
    auto features = explainScene(scene, options, a.time);
    if (!features) return report(features.error());
    j["renderFeatures"] = features->features;
    j["pipelineVariants"] = features->variants;
    std::cout << j.dump(2) << "\n";
    return kOk;
}

// KHR_materials_variants: the names, and the one drawn (--variant).
void printVariants(const Scene& scene) {
    if (scene.variants.empty()) return;
    std::cout << "material variants: " << scene.variants.size() << "\n";
    for (std::size_t i = 0; i < scene.variants.size(); ++i)
        std::cout << "  " << i << " \"" << scene.variants[i] << "\""
                  << (int(i) == scene.activeVariant ? "  <- drawn (--variant)" : "") << "\n";
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

std::string joined(const std::vector<int>& values) {
    std::string out;
    for (int v : values)
        out += (out.empty() ? "" : ", ") + std::to_string(v);
    return out;
}

// Whether `lantern view` can open a window here: a display named in the environment that GLFW
// can connect to.
std::string displayStatus() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!x11 || !*x11) && (!wayland || !*wayland))
        return "none (DISPLAY and WAYLAND_DISPLAY are unset; `lantern view` needs one, e.g. "
               "xvfb-run)";
    const std::string named = x11 && *x11 ? std::string("DISPLAY=") + x11
                                          : std::string("WAYLAND_DISPLAY=") + wayland;
    if (!glfwInit()) return named + ", but GLFW cannot connect to it";
    const bool vulkan = glfwVulkanSupported() == GLFW_TRUE;
    glfwTerminate();
    return named + (vulkan ? ", GLFW connects and offers Vulkan surfaces"
                           : ", GLFW connects but offers no Vulkan surface");
}

// Where the chosen device's compiled pipelines are kept between runs, and how big that is.
std::string pipelineCacheStatus(const DeviceListing& d) {
    if (d.pipelineCacheFile.empty())
        return "in memory only (" + d.pipelineCacheOff +
               "; pipelines are compiled again by each run)";
    if (d.pipelineCacheBytes < 0) return d.pipelineCacheFile + " (not written yet)";
    return d.pipelineCacheFile + " (" + std::to_string(d.pipelineCacheBytes) + " bytes)";
}

int runDevices(const InfoArgs& a) {
    const BuildInfo build = buildInfo();
    std::cout << "Vulkan loader: " << build.vulkanLoader << "\n";
    auto list = listDevices(a.deviceName);
    if (!list) return report(list.error());
    std::cout << "devices: " << list->devices.size() << "\n";
    const DeviceListing* chosen = nullptr;
    for (std::size_t i = 0; i < list->devices.size(); ++i) {
        const DeviceListing& d = list->devices[i];
        std::cout << (d.chosen ? "  * " : "    ") << "[" << i << "] " << d.name << "\n"
                  << "      type " << d.type << ", Vulkan " << d.apiVersion
                  << (d.driver.empty() ? "" : ", driver " + d.driver) << "\n"
                  << "      " << (d.usable ? "usable" : "not usable: " + d.whyNot)
                  << "; --msaa " << joined(d.msaaSampleCounts) << "; windows (VK_KHR_swapchain) "
                  << (d.presentation ? "yes" : "no") << "\n";
        if (d.chosen) chosen = &d;
    }
    std::cout << "chosen: " << (chosen ? chosen->name + ": " : "") << list->choice << "\n"
              << "pipeline cache: " << (chosen ? pipelineCacheStatus(*chosen) : "no device")
              << "\n"
              << "display for `lantern view`: " << displayStatus() << "\n";
    return chosen ? kOk : kFailed;
}

int run(const InfoArgs& a) {
    if (a.devices && a.scene.empty()) return runDevices(a);
    if (a.scene.empty())
        return report(makeError(ErrorCode::Usage, "give a SCENE, or --devices", "scene"));
    if (a.devices)
        if (int code = runDevices(a); code != kOk) return code;
    const LoadOptions load = a.file.load(stderrSink(false));
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
    if (a.json) return printJson(a, scene, root);
    const SceneSummary s = summarize(scene);
    const Kinds kinds = countKinds(scene);
    printRoots(a, scene, s, root);
    printCounts(s, kinds);
    printVariants(scene);
    printFileFeatures(scene);
    return printBoundsAndFeatures(a, scene, root);
}

} // namespace

Runner addInfoCommand(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand(
        "info", "Print what a scene holds and the features it needs, or the Vulkan devices");
    cmd->add_option("scene", args->scene, "Scene file (glTF, GLB, OBJ, PLY, STL, OFF), or builtin:NAME");
    cmd->add_flag("--devices", args->devices,
                  "List the Vulkan devices, the one Lantern would choose and why, the sample "
                  "counts each supports, the pipeline cache and whether a display is available");
    cmd->add_option("--device", args->deviceName,
                    "With --devices: choose as --device NAME would in render and view");
    cmd->add_option("--scene", args->sceneIndex, "glTF scene index (default: the file's default)");
    cmd->add_option("--time", args->time, "Animation time in seconds for bounds and features")
        ->capture_default_str();
    args->file.add(*cmd);
    cmd->add_flag("--json", args->json,
                  "Print everything as JSON, with the fidelity report: every feature the file "
                  "uses, supported, approximated (the rule) or skipped, and its objects");
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
