// `lantern info SCENE`: what a scene holds (no GPU needed).
#include "CliSupport.h"
#include "Commands.h"

#include <iostream>

namespace lantern::cli {
namespace {

struct InfoArgs {
    std::string scene;
    std::uint64_t maxSize = std::uint64_t(1) << 30;
};

int run(const InfoArgs& a) {
    LoadOptions load;
    load.maxBytes = a.maxSize;
    load.log = stderrSink(false);
    auto scene = loadScene(a.scene, load);
    if (!scene) return report(scene.error());
    const SceneSummary s = summarize(*scene);
    std::cout << "scene: " << a.scene << "\n"
              << "scenes: " << s.roots << " (default " << scene->defaultRoot << ")\n"
              << "nodes: " << s.nodes << "\n"
              << "meshes: " << s.meshes << " (" << s.primitives << " primitives, " << s.triangles
              << " triangles, " << s.vertices << " vertices)\n"
              << "materials: " << s.materials << "\n"
              << "textures: " << s.textures << "\n"
              << "lights: " << s.lights << "\n"
              << "cameras: " << s.cameras << "\n"
              << "animations: " << s.animations << "\n";
    if (!s.bounds.empty())
        std::cout << "bounds: [" << s.bounds.min.x << ", " << s.bounds.min.y << ", " << s.bounds.min.z
                  << "] - [" << s.bounds.max.x << ", " << s.bounds.max.y << ", " << s.bounds.max.z << "]\n";
    else
        std::cout << "bounds: empty\n";
    return kOk;
}

} // namespace

Runner addInfoCommand(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand("info", "Print what a scene holds");
    cmd->add_option("scene", args->scene, "glTF/GLB file, or builtin:NAME")->required();
    cmd->add_option("--max-size", args->maxSize, "Largest file, buffer or image accepted, in bytes");
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
