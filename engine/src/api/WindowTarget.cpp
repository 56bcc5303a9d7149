// lantern::WindowTarget: window frames. The frame is built and packed as for a headless render
// (render/), then gpu/Presenter renders it into the frame slot's float image, blits it into the
// acquired swapchain image, runs the host's overlay and presents. This file passes the host's
// Vulkan handles through; it calls no Vulkan function itself.
#include <lantern/Window.h>

#include "api/RendererImpl.h"
#include "gpu/Presenter.h"
#include "render/FrameRender.h"

#include <chrono>

namespace lantern {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

} // namespace

struct WindowTarget::Impl {
    Renderer::Impl* renderer = nullptr;
    std::unique_ptr<gpu::Presenter> presenter;
};

WindowTarget::WindowTarget(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
WindowTarget::WindowTarget(WindowTarget&&) noexcept = default;
WindowTarget& WindowTarget::operator=(WindowTarget&&) noexcept = default;
WindowTarget::~WindowTarget() = default;

VkInstance WindowTarget::windowInstance(const Renderer& renderer) {
    return gpu::Presenter::instance(*renderer.m_impl->device);
}

Result<WindowTarget> WindowTarget::create(Renderer& renderer, const WindowTargetDesc& desc) {
    auto presenter = gpu::Presenter::create(*renderer.m_impl->device, desc);
    if (!presenter) return std::move(presenter).error();
    auto impl = std::make_unique<Impl>();
    impl->renderer = renderer.m_impl.get();
    impl->presenter = std::move(*presenter);
    return WindowTarget(std::move(impl));
}

void WindowTarget::resize(int width, int height) { m_impl->presenter->resize(width, height); }

Result<WindowFrame> WindowTarget::render(const PreparedScene& prepared, const RenderOptions& options,
                                         double time, const FrameRequest& request,
                                         const OverlayRecorder& overlay) {
    if (!prepared) return makeError(ErrorCode::Usage, "render() needs a prepared scene");
    gpu::Presenter& presenter = *m_impl->presenter;
    gpu::Device& device = *m_impl->renderer->device;
    WindowFrame out;
    auto status = presenter.prepare();
    if (!status) return std::move(status).error();
    if (*status) {
        out.status = **status;
        return out;
    }
    RenderOptions o = options;
    o.width = presenter.width();
    o.height = presenter.height();
    LANTERN_TRY(render::checkOptions(device, o));
    const auto t0 = Clock::now();
    auto planned = render::planFrame(prepared.scene(), o, time);
    if (!planned) return std::move(planned).error();
    const double planMs = msSince(t0);
    auto presented = presenter.present(planned->list, prepared.m_gpu, request.capture, overlay);
    if (!presented) return std::move(presented).error();
    out.status = presented->status;
    out.stats.gpuMs = presented->gpuMs;
    out.stats.waitMs = presented->waitMs;
    if (out.status != FrameStatus::Presented) return out;
    out.stats.cpuMs = planMs + presented->submitMs;
    out.presentMs = presented->presentMs;
    out.stats.draws = planned->list.drawCount();
    out.stats.pipelinesCreated = presented->pipelinesCreated;
    if (presented->capture) {
        out.stats.nonFinite = presented->capture->nonFinite;
        Image image = std::move(presented->capture->image);
        attachMetadata(image, planned->frame, device.info(), time);
        out.capture = std::move(image);
    }
    m_impl->renderer->stats = out.stats;
    return out;
}

Result<double> WindowTarget::waitForFrameSlot() { return m_impl->presenter->waitForFrameSlot(); }
int WindowTarget::width() const { return m_impl->presenter->width(); }
int WindowTarget::height() const { return m_impl->presenter->height(); }
PresentMode WindowTarget::presentMode() const { return m_impl->presenter->presentMode(); }
std::uint32_t WindowTarget::imageCount() const { return m_impl->presenter->imageCount(); }
std::uint32_t WindowTarget::framesInFlight() const { return m_impl->presenter->framesInFlight(); }
VkFormat WindowTarget::format() const { return m_impl->presenter->format(); }
const OverlayContext& WindowTarget::overlayContext() const {
    return m_impl->presenter->overlayContext();
}

Result<void> WindowTarget::submitOnce(const std::function<void(VkCommandBuffer)>& record) {
    return m_impl->presenter->submitOnce(record);
}

Result<void> WindowTarget::waitIdle() { return m_impl->presenter->waitIdle(); }

} // namespace lantern
