// lantern::WindowTarget and lantern::glfw::Window in a real X server (Xvfb) on the test
// machine's Vulkan device: every present mode and several frames-in-flight counts present the
// same picture a headless render gives (and the X server shows it, sRGB-encoded); a minimised
// window, a resize the target was not told about and the overlay hook behave as documented;
// the validation layer stays silent throughout.
#include "TestSupport.h"
#include "XServer.h"

#include <lantern/Lantern.h>
#include <lantern/Window.h>
#include <lantern/glfw/GlfwWindow.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace lantern::test {
namespace {

using namespace std::chrono_literals;

class WindowTargetTest : public ::testing::Test {
protected:
    void SetUp() override {
        LANTERN_SKIP_IF_MISSING(XServer::missing());
        LANTERN_SKIP_IF_MISSING(missingVulkanDevice());
        m_dir = testOutputDir();
        std::string error;
        m_server = XServer::start(m_dir, error);
        // Xvfb is there but this machine gives it no display (no /tmp/.X11-unix, say).
        if (!m_server) GTEST_SKIP() << "no X display could be started here: " << error;
    }

    // A presentation renderer with validation on; skips without a Vulkan device.
    std::optional<Renderer> makeRenderer(int framesInFlight) {
        RendererDesc base;
        base.validation = true;
        // Frames in flight, acquire/present semaphores and the blit are checked for hazards.
        base.synchronizationValidation = true;
        base.framesInFlight = framesInFlight;
        base.log = [this](LogLevel level, std::string_view message) {
            if (level >= LogLevel::Warning) {
                std::lock_guard lock(m_logMutex);
                m_messages.emplace_back(message);
            }
        };
        auto desc = glfw::forPresentation(base);
        EXPECT_TRUE(desc) << (desc ? "" : desc.error().describe());
        if (!desc) return std::nullopt;
        auto r = Renderer::create(*desc);
        if (!r && r.error().code == ErrorCode::NoDevice) {
            m_skipReason = "no Vulkan device: " + r.error().describe();
            return std::nullopt;
        }
        EXPECT_TRUE(r) << (r ? "" : r.error().describe());
        if (!r) return std::nullopt;
        if (!r->device().validationEnabled)
            std::cerr << "note: VK_LAYER_KHRONOS_validation is not installed; validation not checked\n";
        return std::move(*r);
    }

    // A window titled so that xWindow() finds it.
    static Result<glfw::Window> openWindow(Renderer& renderer, int width, int height,
                                           bool overlay = false,
                                           PresentMode mode = PresentMode::Fifo) {
        glfw::WindowDesc wd;
        wd.width = width;
        wd.height = height;
        wd.title = "lantern window test";
        wd.overlay = overlay;
        wd.presentMode = mode;
        return glfw::Window::create(renderer, wd);
    }

    // The X id of the test's window (found by its title, as xdotool finds windows).
    unsigned long xWindow() const {
        const auto id = m_server->waitForWindow("lantern window test", 10s);
        EXPECT_TRUE(id);
        return id ? std::stoul(*id) : 0;
    }

    std::string messages() {
        std::lock_guard lock(m_logMutex);
        std::string all;
        for (const auto& m : m_messages) all += m + "\n";
        return all;
    }

    static std::shared_ptr<const Scene> spheres() {
        auto s = builtinScene("spheres");
        EXPECT_TRUE(s);
        return std::make_shared<const Scene>(std::move(*s));
    }

    // Renders until a frame is presented (Recreated first is allowed), at most `tries` times.
    static Result<WindowFrame> present(glfw::Window& w, const PreparedScene& scene,
                                       RenderOptions options, const FrameRequest& request = {},
                                       const OverlayRecorder& overlay = {}, int tries = 4) {
        for (int i = 0;; ++i) {
            w.pollEvents(0.0);
            auto f = w.target().render(scene, options, 0.0, request, overlay);
            if (!f || f->status == FrameStatus::Presented || i + 1 == tries) return f;
        }
    }

    // The X server's copy of the window, once it equals `expected` within 1 (the blit's and
    // the reference's sRGB rounding), or the last one read when that never happens.
    std::optional<XImageRgb> grabWhenShown(const Image& expected, int& difference) {
        const unsigned long window = xWindow();
        std::optional<XImageRgb> shot;
        for (int i = 0; i < 50; ++i) {
            shot = m_server->grab(window);
            if (shot && shot->width == expected.width && shot->height == expected.height) {
                difference = maxDifference(*shot, expected, 0, 0, expected.width, expected.height);
                if (difference <= 1) return shot;
            }
            std::this_thread::sleep_for(40ms);
        }
        return shot;
    }

    std::filesystem::path m_dir;
    std::unique_ptr<XServer> m_server;
    std::string m_skipReason;
    std::mutex m_logMutex;
    std::vector<std::string> m_messages;
};

struct ModeRow {
    PresentMode mode;
    int framesInFlight;
    const char* why;
};

TEST_F(WindowTargetTest, EveryPresentModeShowsTheHeadlessPicture) {
    const ModeRow rows[] = {
        {PresentMode::Fifo, 2, "the default: vsync, double-buffered frames in flight"},
        {PresentMode::Fifo, 1, "one frame in flight: the CPU waits for each frame"},
        {PresentMode::Mailbox, 3, "mailbox with three frames in flight"},
        {PresentMode::Immediate, 2, "no vsync"},
    };
    for (const ModeRow& row : rows) {
        SCOPED_TRACE(std::string(toString(row.mode)) + ", " + std::to_string(row.framesInFlight) +
                     " in flight: " + row.why);
        auto renderer = makeRenderer(row.framesInFlight);
        if (!m_skipReason.empty()) GTEST_SKIP() << m_skipReason;
        ASSERT_TRUE(renderer);
        auto window = openWindow(*renderer, 96, 64, false, row.mode);
        ASSERT_TRUE(window) << window.error().describe();
        EXPECT_EQ(window->target().framesInFlight(), std::uint32_t(row.framesInFlight));
        EXPECT_GE(window->target().imageCount(), std::uint32_t(row.framesInFlight));
        auto prepared = renderer->prepare(spheres());
        ASSERT_TRUE(prepared);
        RenderOptions options;
        options.background = {0.05f, 0.1f, 0.2f, 1.0f};
        for (int i = 0; i < 6; ++i) {  // more frames than slots and images: every one reused
            auto f = present(*window, *prepared, options);
            ASSERT_TRUE(f) << f.error().describe();
            ASSERT_EQ(f->status, FrameStatus::Presented);
        }
        FrameRequest capture;
        capture.capture = true;
        auto f = present(*window, *prepared, options, capture);
        ASSERT_TRUE(f) << f.error().describe();
        ASSERT_EQ(f->status, FrameStatus::Presented);
        ASSERT_TRUE(f->capture);
        EXPECT_EQ(f->stats.nonFinite, 0u);
        RenderOptions headless = options;
        headless.width = window->target().width();
        headless.height = window->target().height();
        auto expected = renderer->render(*prepared, headless, 0.0);
        ASSERT_TRUE(expected);
        ASSERT_EQ(f->capture->width, 96);
        ASSERT_EQ(f->capture->height, 64);
        // The same engine, options and size: the very same floats.
        EXPECT_EQ(maxAbsDifference(*f->capture, *expected), 0.0f)
            << saveComparison(*f->capture, *expected, "window-capture");
        int difference = 255;
        auto shown = grabWhenShown(*f->capture, difference);
        ASSERT_TRUE(shown);
        EXPECT_LE(difference, 1) << "the X server does not show the captured picture";
        std::size_t lit = 0;  // pixels that are not the background: the spheres are in view
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 96; ++x) lit += std::abs(f->capture->pixel(x, y)[2] - 0.2f) > 0.01f;
        EXPECT_GT(lit, std::size_t(96 * 64 / 4));
        ASSERT_TRUE(window->target().waitIdle());
        EXPECT_EQ(renderer->validationMessageCount(), 0u) << messages();
    }
}

TEST_F(WindowTargetTest, MinimisedResizedAndOutOfDateAreStatuses) {
    auto renderer = makeRenderer(2);
    if (!m_skipReason.empty()) GTEST_SKIP() << m_skipReason;
    ASSERT_TRUE(renderer);
    auto window = openWindow(*renderer, 80, 60);
    ASSERT_TRUE(window) << window.error().describe();
    auto prepared = renderer->prepare(spheres());
    ASSERT_TRUE(prepared);
    WindowTarget& target = window->target();
    const RenderOptions options;
    auto f = present(*window, *prepared, options);
    ASSERT_TRUE(f);
    ASSERT_EQ(f->status, FrameStatus::Presented);

    // Minimised: a 0 x 0 framebuffer renders nothing and says so.
    target.resize(0, 0);
    f = target.render(*prepared, options, 0.0);
    ASSERT_TRUE(f) << f.error().describe();
    EXPECT_EQ(f->status, FrameStatus::Minimised);
    // Restored: the swapchain is rebuilt first (Recreated), then frames present again.
    target.resize(80, 60);
    f = target.render(*prepared, options, 0.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->status, FrameStatus::Recreated);
    f = target.render(*prepared, options, 0.0);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->status, FrameStatus::Presented);

    // The window grows behind the target's back: the driver reports the swapchain out of date
    // or suboptimal, and the target rebuilds it for the surface's new size by itself.
    glfwSetWindowSize(window->handle(), 120, 90);
    bool recreated = false;
    for (int i = 0; i < 20 && target.width() != 120; ++i) {
        std::this_thread::sleep_for(20ms);
        f = target.render(*prepared, options, 0.0);
        ASSERT_TRUE(f) << f.error().describe();
        recreated |= f->status == FrameStatus::Recreated;
    }
    EXPECT_TRUE(recreated);
    EXPECT_EQ(target.width(), 120);
    EXPECT_EQ(target.height(), 90);
    FrameRequest capture;
    capture.capture = true;
    f = present(*window, *prepared, options, capture);
    ASSERT_TRUE(f);
    ASSERT_EQ(f->status, FrameStatus::Presented);
    ASSERT_TRUE(f->capture);
    EXPECT_EQ(f->capture->width, 120);
    EXPECT_EQ(f->capture->height, 90);
    ASSERT_TRUE(target.waitIdle());
    EXPECT_EQ(renderer->validationMessageCount(), 0u) << messages();
}

TEST_F(WindowTargetTest, OverlayIsDrawnOverThePictureButNotCaptured) {
    auto renderer = makeRenderer(2);
    if (!m_skipReason.empty()) GTEST_SKIP() << m_skipReason;
    ASSERT_TRUE(renderer);
    auto window = openWindow(*renderer, 64, 48, true);
    ASSERT_TRUE(window) << window.error().describe();
    const OverlayContext& oc = window->target().overlayContext();
    ASSERT_NE(oc.renderPass, VK_NULL_HANDLE);
    ASSERT_NE(oc.descriptorPool, VK_NULL_HANDLE);
    EXPECT_GE(oc.imageCount, 2u);
    auto prepared = renderer->prepare(spheres());
    ASSERT_TRUE(prepared);
    // The overlay clears the top-left 16 x 16 pixels to pure red.
    const OverlayRecorder overlay = [](VkCommandBuffer cmd) {
        VkClearAttachment clear{VK_IMAGE_ASPECT_COLOR_BIT, 0, {}};
        clear.clearValue.color = {{1.0f, 0.0f, 0.0f, 1.0f}};
        VkClearRect rect{{{0, 0}, {16, 16}}, 0, 1};
        vkCmdClearAttachments(cmd, 1, &clear, 1, &rect);
    };
    FrameRequest capture;
    capture.capture = true;
    auto f = present(*window, *prepared, RenderOptions{}, capture, overlay);
    ASSERT_TRUE(f) << f.error().describe();
    ASSERT_EQ(f->status, FrameStatus::Presented);
    ASSERT_TRUE(f->capture);
    const unsigned long xwindow = xWindow();
    std::optional<XImageRgb> shot;
    for (int i = 0; i < 50; ++i) {
        shot = m_server->grab(xwindow);
        if (shot && maxDifference(*shot, *f->capture, 16, 16, 64, 48) <= 1) break;
        std::this_thread::sleep_for(40ms);
    }
    ASSERT_TRUE(shot);
    EXPECT_LE(maxDifference(*shot, *f->capture, 16, 16, 64, 48), 1) << "outside the overlay";
    const std::uint8_t* corner = &shot->rgb[(5 * std::size_t(shot->width) + 5) * 3];
    EXPECT_EQ(int(corner[0]), 255);
    EXPECT_EQ(int(corner[1]), 0);
    EXPECT_EQ(int(corner[2]), 0);
    EXPECT_LT(f->capture->pixel(5, 5)[0], 0.5f) << "the capture holds Lantern's picture only";
    ASSERT_TRUE(window->target().waitIdle());
    EXPECT_EQ(renderer->validationMessageCount(), 0u) << messages();
}

TEST_F(WindowTargetTest, RendererWithoutPresentationIsRefused) {
    auto r = Renderer::create(RendererDesc{});
    if (!r && r.error().code == ErrorCode::NoDevice) GTEST_SKIP() << "no Vulkan device";
    ASSERT_TRUE(r);
    WindowTargetDesc desc;
    desc.surface = reinterpret_cast<VkSurfaceKHR>(std::uintptr_t(1));  // refused before use
    auto target = WindowTarget::create(*r, desc);
    ASSERT_FALSE(target);
    EXPECT_EQ(target.error().code, ErrorCode::Usage);
}

} // namespace
} // namespace lantern::test
