// `lantern render SCENE`: headless rendering to EXR/PNG (spec/cli.md).
#include "CliSupport.h"
#include "Commands.h"

#include <iostream>
#include <memory>

namespace lantern::cli {
namespace {

struct RenderArgs {
    std::string scene;
    std::vector<std::string> outputs;
    int width = 1280, height = 720;
    int sceneIndex = -1;
    double time = 0.0;
    std::string aov;
    bool half = false;
    bool explain = false;
    std::string compression = "zip";
    std::uint64_t maxSize = std::uint64_t(1) << 30;
    CameraOptions camera;
    ShadingOptions shading;
    DeviceOptions device;
};

int run(const RenderArgs& a) {
    RenderOptions options;
    options.width = a.width;
    options.height = a.height;
    options.root = a.sceneIndex;
    if (auto r = a.shading.apply(options); !r) return report(r.error());
    if (auto r = a.camera.apply(options); !r) return report(r.error());
    if (!a.aov.empty()) {
        std::stringstream ss(a.aov);
        std::string item;
        while (std::getline(ss, item, ',')) {
            if (item == "depth") options.aovs.depth = true;
            else if (item == "normal") options.aovs.normal = true;
            else
                return report(makeError(ErrorCode::InvalidInput,
                                        "unknown AOV \"" + item + "\" (depth, normal)", "--aov"));
        }
    }
    ExrOptions exr;
    exr.half = a.half;
    const auto compression = parseExrCompression(a.compression);
    if (!compression)
        return report(makeError(ErrorCode::InvalidInput, "unknown compression \"" + a.compression + "\"",
                                "--compression"));
    exr.compression = *compression;
    std::vector<std::string> outputs = a.outputs;
    if (outputs.empty()) outputs.push_back("out/render.exr");
    for (const std::string& out : outputs) {
        const std::string ext = std::filesystem::path(out).extension().string();
        if (ext != ".exr" && ext != ".png")
            return report(makeError(ErrorCode::InvalidInput,
                                    "unknown image type \"" + ext + "\" (use .exr or .png)", "--output", out));
    }

    LoadOptions load;
    load.maxBytes = a.maxSize;
    load.log = stderrSink(a.device.verbose);
    auto scene = loadScene(a.scene, load);
    if (!scene) return report(scene.error());
    auto shared = std::make_shared<const Scene>(std::move(*scene));

    auto renderer = Renderer::create(a.device.desc());
    if (!renderer) return report(renderer.error());
    if (a.device.verbose)
        std::cerr << "lantern: device: " << renderer->device().name << " (" << renderer->device().driver
                  << ")\n";
    if (a.explain) {
        auto report_ = renderer->explain(*shared, options, a.time);
        if (!report_) return report(report_.error());
        std::cout << "features:\n";
        for (const auto& f : report_->features) std::cout << "  " << f << "\n";
        std::cout << "pipeline variants:\n";
        for (const auto& v : report_->variants) std::cout << "  " << v << "\n";
    }
    auto prepared = renderer->prepare(shared);
    if (!prepared) return report(prepared.error());
    auto image = renderer->render(*prepared, options, a.time);
    if (!image) return report(image.error());
    for (const std::string& out : outputs) {
        std::uint64_t clamped = 0;
        exr.clampedCount = &clamped;
        if (auto w = writeImage(out, *image, exr); !w) return report(w.error());
        if (clamped > 0)
            std::cerr << "lantern: warning: " << out << ": " << clamped
                      << " values exceeded the half range and were clamped to 65504\n";
        std::cout << out << "\n";
    }
    return kOk;
}

} // namespace

Runner addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene headless to EXR/PNG");
    cmd->add_option("scene", args->scene, "glTF/GLB file, or builtin:NAME")->required();
    cmd->add_option("-o,--output", args->outputs,
                    "Output file(s): .exr or .png; repeat to write several (default out/render.exr)");
    cmd->add_option("--width", args->width, "Image width in pixels")->capture_default_str();
    cmd->add_option("--height", args->height, "Image height in pixels")->capture_default_str();
    cmd->add_option("--scene", args->sceneIndex, "glTF scene index (default: the file's default)");
    cmd->add_option("--time", args->time, "Animation time in seconds")->capture_default_str();
    cmd->add_option("--aov", args->aov, "Extra EXR channels: depth,normal");
    cmd->add_flag("--half", args->half, "Write 16-bit half channels instead of 32-bit float");
    cmd->add_option("--compression", args->compression,
                    "EXR compression: none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab")
        ->capture_default_str();
    cmd->add_flag("--explain", args->explain, "Print the features the scene uses and the pipeline variants");
    cmd->add_option("--max-size", args->maxSize, "Largest file, buffer or image accepted, in bytes")
        ->capture_default_str();
    args->camera.add(*cmd);
    args->shading.add(*cmd);
    args->device.add(*cmd);
    return [args, cmd]() { return cmd->parsed() ? run(*args) : -1; };
}

} // namespace lantern::cli
