// A GLFW host that owns its window: it creates the window and its Vulkan surface itself and
// hands the surface to a Lantern WindowTarget, which presents the scene's frames (the
// animation playing in a loop). Escape or closing the window quits.
// Usage: lantern-glfw-example [--scene builtin:NAME|FILE.gltf] [--frames N] [--size WxH]
#include <lantern/Lantern.h>
#include <lantern/Window.h>
#include <lantern/glfw/GlfwWindow.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>

namespace {

struct Args {
    std::string scene = "builtin:spheres-animated";
    long frames = 0;  ///< frames to present before quitting; 0: until the window is closed
    int width = 640, height = 480;
};

std::optional<Args> parseArgs(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const bool hasValue = i + 1 < argc;
        if (!std::strcmp(argv[i], "--scene") && hasValue) {
            a.scene = argv[++i];
        } else if (!std::strcmp(argv[i], "--frames") && hasValue) {
            char* end = nullptr;
            a.frames = std::strtol(argv[++i], &end, 10);
            if (*end || a.frames < 0) return std::nullopt;
        } else if (!std::strcmp(argv[i], "--size") && hasValue) {
            if (std::sscanf(argv[++i], "%dx%d", &a.width, &a.height) != 2 || a.width < 1 ||
                a.height < 1)
                return std::nullopt;
        } else {
            return std::nullopt;
        }
    }
    return a;
}

int fail(const lantern::Error& e) {
    std::fprintf(stderr, "glfw example: %s\n", e.describe().c_str());
    return lantern::exitCodeFor(e.code);
}

// Everything that lives on the window, destroyed in the right order: Lantern's swapchain
// (and the surface it owns) before the renderer, the renderer before the window, GLFW last.
struct Host {
    std::optional<lantern::Renderer> renderer;
    std::optional<lantern::WindowTarget> target;
    GLFWwindow* window = nullptr;
    ~Host() {
        if (target) (void)target->waitIdle();
        target.reset();
        renderer.reset();
        if (window) glfwDestroyWindow(window);
        glfwTerminate();
    }
};

} // namespace

int main(int argc, char** argv) {
    const auto args = parseArgs(argc, argv);
    if (!args) {
        std::fprintf(stderr, "usage: %s [--scene builtin:NAME|FILE.gltf] [--frames N] [--size WxH]\n",
                     argv[0]);
        return 2;
    }
    Host host;

    // The scene first: a bad file is refused before a window opens.
    auto loaded = lantern::loadScene(args->scene);
    if (!loaded) return fail(loaded.error());
    auto scene = std::make_shared<const lantern::Scene>(std::move(*loaded));

    // forPresentation initialises GLFW and asks for the instance extensions its surfaces need.
    lantern::RendererDesc base;
    base.log = [](lantern::LogLevel level, std::string_view message) {
        if (level >= lantern::LogLevel::Warning)
            std::fprintf(stderr, "lantern: %.*s\n", int(message.size()), message.data());
    };
    auto desc = lantern::glfw::forPresentation(base);
    if (!desc) return fail(desc.error());
    auto renderer = lantern::Renderer::create(*desc);
    if (!renderer) return fail(renderer.error());
    host.renderer.emplace(std::move(*renderer));

    // The host's own window and surface (no OpenGL context: Vulkan presents).
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    host.window = glfwCreateWindow(args->width, args->height, "Lantern GLFW example", nullptr,
                                   nullptr);
    if (!host.window) {
        std::fprintf(stderr, "glfw example: glfwCreateWindow failed\n");
        return 3;
    }
    glfwSetKeyCallback(host.window, [](GLFWwindow* w, int key, int, int action, int) {
        if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS) glfwSetWindowShouldClose(w, GLFW_TRUE);
    });
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(lantern::WindowTarget::windowInstance(*host.renderer), host.window,
                                nullptr, &surface) != VK_SUCCESS) {
        std::fprintf(stderr, "glfw example: glfwCreateWindowSurface failed\n");
        return 3;
    }
    lantern::WindowTargetDesc td;
    td.surface = surface;
    td.ownsSurface = true;  // the target destroys it after its swapchain
    glfwGetFramebufferSize(host.window, &td.width, &td.height);
    auto target = lantern::WindowTarget::create(*host.renderer, td);
    if (!target) return fail(target.error());
    host.target.emplace(std::move(*target));

    auto prepared = host.renderer->prepare(scene);
    if (!prepared) return fail(prepared.error());
    std::printf("device: %s; window %dx%d, present mode %s\n",
                host.renderer->device().name.c_str(), host.target->width(), host.target->height(),
                lantern::toString(host.target->presentMode()));

    lantern::RenderOptions options;  // width and height follow the swapchain
    const lantern::TimeRange range = lantern::animationRange(*scene);
    const auto start = std::chrono::steady_clock::now();
    long presented = 0;
    while (!glfwWindowShouldClose(host.window) && (args->frames == 0 || presented < args->frames)) {
        glfwPollEvents();
        int w = 0, h = 0;
        glfwGetFramebufferSize(host.window, &w, &h);
        host.target->resize(w, h);
        if (w == 0 || h == 0) {  // minimised: wait for the window to come back
            glfwWaitEventsTimeout(0.25);
            continue;
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto frame = host.target->render(*prepared, options, lantern::loopTime(seconds, range));
        if (!frame) return fail(frame.error());
        if (frame->status == lantern::FrameStatus::Presented) ++presented;
    }
    std::printf("presented %ld frames\n", presented);
    return 0;
}
