// `lantern view SCENE`: the interactive viewer (docs/cli.md, docs/viewer.md): its options, the
// checks made before a window opens, the renderer and the window (a GLFW window on a Vulkan
// swapchain, lantern::glfw::Window); the Viewer runs the rest. Public API only.
#include "common/CliSupport.h"
#include "common/Commands.h"
#include "view/ViewArgs.h"
#include "view/Viewer.h"

#include <iostream>
#include <lantern/Window.h>
#include <lantern/glfw/GlfwWindow.h>
#include <memory>

namespace lantern::cli {
namespace {

int runView(const ViewArgs& a) {
    if (!a.camera.viewports.empty())
        return report(makeError(ErrorCode::Usage,
                                "the viewer sizes its views with the window: use --layout quad",
                                "--viewport"));
    if (a.afterFrames < 0)
        return report(makeError(ErrorCode::Usage, "--after-frames must be >= 0", "--after-frames"));
    if (!a.screenshots.empty() && a.afterFrames == 0)
        return report(
            makeError(ErrorCode::Usage, "--screenshot needs --after-frames N", "--screenshot"));
    if (auto r = checkImagePaths(a.screenshots, "--screenshot"); !r) return report(r.error());
    const auto mode = parsePresentMode(a.presentMode);
    if (!mode)
        return report(
            makeError(ErrorCode::InvalidInput,
                      "unknown present mode \"" + a.presentMode + "\" (fifo, mailbox, immediate)",
                      "--present-mode"));
    if (a.watch && a.scene.rfind("builtin:", 0) == 0)
        std::cerr << "lantern: warning: --watch has no file to watch for " << a.scene << "\n";

    const LoadOptions load = a.file.load(stderrSink(a.device.verbose));
    auto scene = loadScene(a.scene, load);
    if (!scene) return report(scene.error());
    if (a.sceneIndex < -1 || a.sceneIndex >= int(scene->roots.size()))
        return report(makeError(ErrorCode::InvalidInput,
                                "scene " + std::to_string(a.sceneIndex) +
                                    " does not exist (the file has " +
                                    std::to_string(scene->roots.size()) + " scenes)",
                                "--scene"));
    {
        // The camera options must hold, and name a camera that exists, before a window opens.
        RenderOptions check;
        if (auto r = a.camera.apply(check); !r) return report(r.error());
        // Intrinsics fix the image size in pixels, and a window is resized at will; the
        // viewer's camera control and its command line speak gluLookAt.
        if (check.camera.intrinsics || check.camera.viewFromWorld)
            return report(makeError(ErrorCode::Usage,
                                    "computer-vision cameras (intrinsics, poses, camera files) "
                                    "are for lantern render; the viewer takes scene cameras and "
                                    "--look-at",
                                    !a.camera.cameraFiles.empty() ? "--camera"
                                    : check.camera.intrinsics     ? "--intrinsics"
                                                                  : "--world-to-camera"));
        if (auto p = resolveCameraPlacement(*scene, check.camera, 1.0, a.sceneIndex, a.time); !p)
            return report(p.error());
    }

    RendererDesc base = a.device.desc();
    base.framesInFlight = a.framesInFlight;
    auto desc = glfw::forPresentation(base);
    if (!desc) return report(desc.error());
    auto renderer = Renderer::create(*desc);
    if (!renderer) return report(renderer.error());
    if (a.device.verbose)
        std::cerr << "lantern: device: " << renderer->device().name << " ("
                  << renderer->device().driver << ")\n";
    if (auto r = a.shading.checkDevice(renderer->device()); !r) return report(r.error());
    if (auto r = makeParentFolders(a.screenshots, 0, "--screenshot"); !r) return report(r.error());
    glfw::WindowDesc wd;
    wd.width = a.width;
    wd.height = a.height;
    wd.title = "lantern view: " + a.scene;
    wd.presentMode = *mode;
    wd.overlay = true;
    auto window = glfw::Window::create(*renderer, wd);
    if (!window) return report(window.error());
    if (a.device.verbose)
        std::cerr << "lantern: window: " << window->target().width() << "x"
                  << window->target().height() << ", present mode "
                  << toString(window->target().presentMode()) << ", "
                  << window->target().imageCount() << " swapchain images, "
                  << window->target().framesInFlight() << " frames in flight\n";
    Viewer viewer(a, *renderer, *window);
    return viewer.run(std::make_shared<Scene>(std::move(*scene)));
}

} // namespace

Runner addViewCommand(CLI::App& app) {
    auto args = std::make_shared<ViewArgs>();
    CLI::App* cmd = app.add_subcommand(
        "view", "Open a window and play the scene: orbit/pan/zoom/fly, shading keys, a side panel "
                "editing lights and materials (F1 lists the keys)");
    cmd->add_option("scene", args->scene, "Scene file (glTF, GLB, OBJ, PLY, STL, OFF), or builtin:NAME")->required();
    const auto [width, height] = addSizeOptions(*cmd, args->width, args->height);
    width->check(CLI::Range(1, 16384));
    height->check(CLI::Range(1, 16384));
    cmd->add_option("--scene", args->sceneIndex, "glTF scene index (default: the file's default)");
    cmd->add_option("--time", args->time, "Animation time to start at, in seconds")
        ->capture_default_str();
    cmd->add_flag("--paused", args->paused, "Start with the animation paused");
    cmd->add_option("--fps", args->fps, "Frame rate the arrow keys step by")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->add_option("--present-mode", args->presentMode,
                    "fifo (vsync, the default), mailbox or immediate (falls back to what the "
                    "display offers)")
        ->capture_default_str();
    cmd->add_option("--frames-in-flight", args->framesInFlight,
                    "Frames the CPU may be ahead of the GPU (1-4; 2: double buffering)")
        ->capture_default_str()
        ->check(CLI::Range(1, 4));
    cmd->add_flag("--watch", args->watch,
                  "Reload the file when it changes on disk, keeping the camera");
    cmd->add_option(
        "--screenshot", args->screenshots,
        "With --after-frames: write the picture to PATH (.exr or .png; repeatable) and exit");
    cmd->add_option("--after-frames", args->afterFrames,
                    "Exit after N frames (writing the --screenshot files of frame N)");
    cmd->add_option("--screenshot-dir", args->screenshotDir,
                    "Folder for F12 screenshots (lantern-view-NNNN.exr and .png)")
        ->capture_default_str();
    cmd->add_option("--background", args->background, help::kBackground);
    cmd->add_flag("--no-panel", args->noPanel, "Start with the side panel hidden (F2 shows it)");
    cmd->add_flag("--show-help", args->showHelp, "Start with the key help shown (F1)");
    cmd->add_flag("--headlight", args->headlight, "Start with the lights following the camera (H)");
    cmd->add_flag("--wireframe", args->wireframe, "Start with the wireframe overlay on (Z)");
    cmd->add_flag("--normals", args->normals, "Start with the normals displayed (N)");
    cmd->add_flag("--stats", args->stats, "Print frame-time statistics when the viewer exits");
    args->file.add(*cmd);
    args->camera.add(*cmd);
    args->shading.add(*cmd);
    args->device.add(*cmd);
    return [args, cmd]() {
        if (!cmd->parsed()) return -1;
        return runView(*args);
    };
}

} // namespace lantern::cli
