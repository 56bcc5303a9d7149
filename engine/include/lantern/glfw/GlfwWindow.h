// GlfwWindow.h: a GLFW window presenting a Lantern Renderer's frames, for hosts that want a
// window in a few lines (CMake target Lantern::glfw, its own library):
//
//   auto desc = lantern::glfw::forPresentation(lantern::RendererDesc{});
//   auto renderer = lantern::Renderer::create(*desc);
//   auto window = lantern::glfw::Window::create(*renderer, {.title = "demo"});
//   auto scene = renderer->prepare(...);
//   while (!window->shouldClose())
//       if (window->pollEvents()) (void)window->target().render(*scene, options, time);
//
// GLFW is initialised on first use and terminated when the last Window is destroyed. Use it
// from the main thread only (GLFW's rule).
#pragma once

#include <lantern/Window.h>

#include <string>

struct GLFWwindow;

namespace lantern::glfw {

struct WindowDesc {
    int width = 1280, height = 720;  ///< the window's size in screen coordinates
    std::string title = "Lantern";
    PresentMode presentMode = PresentMode::Fifo;
    bool overlay = false;  ///< prepare WindowTarget's overlay render pass (for ImGui)
    bool resizable = true;
};

/// `desc` with presentation on and the instance extensions GLFW's surfaces need. Initialises
/// GLFW: fails with NoDevice when no display can be opened (the message names $DISPLAY) or
/// GLFW finds no Vulkan loader.
Result<RendererDesc> forPresentation(RendererDesc desc);

/// A GLFW window (no client API), its surface and the WindowTarget presenting to it.
/// Move-only; must be destroyed before the Renderer it was created with.
class Window {
public:
    static Result<Window> create(Renderer& renderer, const WindowDesc& desc);

    Window(Window&&) noexcept;
    Window& operator=(Window&&) noexcept;
    ~Window();

    GLFWwindow* handle() const;
    WindowTarget& target();
    bool shouldClose() const;
    void setTitle(const std::string& title);

    /// Processes pending window events and tells the target the framebuffer's size. While the
    /// window cannot be drawn (a 0 x 0 framebuffer, iconified, or unmapped), waits for events
    /// instead of returning at once, so a minimised window costs no CPU: until it can be drawn
    /// again or closed, or, when `idleTimeoutSeconds` >= 0, for at most that long. Returns
    /// whether the window can be drawn now.
    bool pollEvents(double idleTimeoutSeconds = -1.0);

    /// Whether the window can be drawn now (as pollEvents() decides).
    bool drawable() const;

private:
    struct Impl;
    explicit Window(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

} // namespace lantern::glfw
