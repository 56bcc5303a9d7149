// lantern::glfw::Window: GLFW window + Vulkan surface + WindowTarget, and waiting instead of
// spinning while the window is minimised.
#include <lantern/glfw/GlfwWindow.h>

#define GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <mutex>

namespace lantern::glfw {
namespace {

std::mutex g_mutex;
std::string g_lastError;
int g_windows = 0;

extern "C" void onGlfwError(int code, const char* description) {
    std::lock_guard lock(g_mutex);
    g_lastError = "GLFW error " + std::to_string(code) + ": " + (description ? description : "?");
}

std::string lastError() {
    std::lock_guard lock(g_mutex);
    return g_lastError.empty() ? "no details" : g_lastError;
}

Result<void> initGlfw() {
    glfwSetErrorCallback(onGlfwError);
    if (glfwInit() != GLFW_TRUE) {
        const char* display = std::getenv("DISPLAY");
        const char* wayland = std::getenv("WAYLAND_DISPLAY");
        return makeError(ErrorCode::NoDevice,
                         "cannot open a window: no display could be opened (DISPLAY=" +
                             std::string(display ? display : "(unset)") +
                             (wayland ? std::string(", WAYLAND_DISPLAY=") + wayland : std::string()) +
                             "; " + lastError() + ")");
    }
    if (glfwVulkanSupported() != GLFW_TRUE)
        return makeError(ErrorCode::NoDevice,
                         "GLFW found no Vulkan loader able to create window surfaces (" +
                             lastError() + ")");
    return {};
}

} // namespace

Result<RendererDesc> forPresentation(RendererDesc desc) {
    LANTERN_TRY(initGlfw());
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names)
        return makeError(ErrorCode::NoDevice,
                         "the Vulkan driver cannot make surfaces for this display (" + lastError() + ")");
    for (std::uint32_t i = 0; i < count; ++i) {
        bool present = false;
        for (const std::string& e : desc.instanceExtensions) present |= e == names[i];
        if (!present) desc.instanceExtensions.emplace_back(names[i]);
    }
    desc.presentation = true;
    return desc;
}

struct Window::Impl {
    GLFWwindow* window = nullptr;
    std::optional<WindowTarget> target;

    ~Impl() {
        target.reset();  // the swapchain and the (owned) surface go before the window
        if (window) glfwDestroyWindow(window);
        std::lock_guard lock(g_mutex);
        if (--g_windows == 0) glfwTerminate();
    }

    void syncSize() {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window, &w, &h);
        target->resize(w, h);
    }
};

Window::Window(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Window::Window(Window&&) noexcept = default;
Window& Window::operator=(Window&&) noexcept = default;
Window::~Window() = default;

Result<Window> Window::create(Renderer& renderer, const WindowDesc& desc) {
    LANTERN_TRY(initGlfw());
    if (desc.width < 1 || desc.height < 1)
        return makeError(ErrorCode::InvalidInput, "the window size must be at least 1 x 1",
                         "WindowDesc.width/height");
    auto impl = std::make_unique<Impl>();
    {
        std::lock_guard lock(g_mutex);
        ++g_windows;  // from here on ~Impl balances it
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, desc.resizable ? GLFW_TRUE : GLFW_FALSE);
    impl->window = glfwCreateWindow(desc.width, desc.height, desc.title.c_str(), nullptr, nullptr);
    if (!impl->window)
        return makeError(ErrorCode::NoDevice, "cannot create a window (" + lastError() + ")");
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    const VkResult r = glfwCreateWindowSurface(WindowTarget::windowInstance(renderer),
                                               impl->window, nullptr, &surface);
    if (r != VK_SUCCESS)
        return makeError(ErrorCode::NoDevice, "cannot create a Vulkan surface for the window (" +
                                                  lastError() + ")");
    WindowTargetDesc td;
    td.surface = surface;
    td.ownsSurface = true;
    glfwGetFramebufferSize(impl->window, &td.width, &td.height);
    td.presentMode = desc.presentMode;
    td.overlay = desc.overlay;
    auto target = WindowTarget::create(renderer, td);  // owns the surface, even on failure
    if (!target) return std::move(target).error();
    impl->target.emplace(std::move(*target));
    return Window(std::move(impl));
}

GLFWwindow* Window::handle() const { return m_impl->window; }
WindowTarget& Window::target() { return *m_impl->target; }
bool Window::shouldClose() const { return glfwWindowShouldClose(m_impl->window) == GLFW_TRUE; }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(m_impl->window, title.c_str()); }

bool Window::drawable() const {
    GLFWwindow* w = m_impl->window;
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(w, &fw, &fh);
    // GLFW_VISIBLE reports whether the window is mapped (a window manager unmaps an iconified
    // window; so does `xdotool windowunmap`).
    return fw > 0 && fh > 0 && !glfwGetWindowAttrib(w, GLFW_ICONIFIED) &&
           glfwGetWindowAttrib(w, GLFW_VISIBLE);
}

bool Window::pollEvents(double idleTimeoutSeconds) {
    glfwPollEvents();
    m_impl->syncSize();
    while (!shouldClose() && !drawable()) {
        if (idleTimeoutSeconds >= 0.0)
            glfwWaitEventsTimeout(idleTimeoutSeconds);
        else
            glfwWaitEvents();
        m_impl->syncSize();
        if (idleTimeoutSeconds >= 0.0) break;
    }
    return !shouldClose() && drawable();
}

} // namespace lantern::glfw
