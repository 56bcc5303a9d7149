// lantern::WindowTarget: window frames. The scene renders into the frame slot's float image
// (render/Engine), which is blitted into the acquired swapchain image; the host's overlay is
// recorded in a render pass on that image; then it is presented.
#include <lantern/Window.h>

#include "gpu/Swapchain.h"
#include "render/RendererImpl.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace lantern {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::vector<VkPresentModeKHR> modePreference(PresentMode m) {
    switch (m) {
    case PresentMode::Immediate:
        return {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_FIFO_KHR};
    case PresentMode::Mailbox: return {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_FIFO_KHR};
    case PresentMode::Fifo: break;
    }
    return {VK_PRESENT_MODE_FIFO_KHR};
}

Result<gpu::UniqueSemaphore> makeSemaphore(gpu::Context& ctx, const std::string& name) {
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateSemaphore(ctx.device(), &sci, nullptr, &s));
    ctx.setName(VK_OBJECT_TYPE_SEMAPHORE, s, name);
    return gpu::UniqueSemaphore(ctx.device(), s);
}

} // namespace

const char* toString(PresentMode mode) noexcept {
    switch (mode) {
    case PresentMode::Fifo: return "fifo";
    case PresentMode::Mailbox: return "mailbox";
    case PresentMode::Immediate: return "immediate";
    }
    return "?";
}

std::optional<PresentMode> parsePresentMode(std::string_view text) noexcept {
    if (text == "fifo") return PresentMode::Fifo;
    if (text == "mailbox") return PresentMode::Mailbox;
    if (text == "immediate") return PresentMode::Immediate;
    return std::nullopt;
}

struct WindowTarget::Impl {
    Renderer::Impl* renderer = nullptr;
    std::shared_ptr<gpu::Context> ctx;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    bool ownsSurface = false;
    std::optional<gpu::Swapchain> swapchain;
    int wantWidth = 0, wantHeight = 0;
    bool stale = true;  ///< rebuild the swapchain before the next frame
    std::vector<gpu::UniqueSemaphore> acquired;  ///< per frame slot
    std::vector<gpu::UniqueSemaphore> rendered;  ///< per swapchain image (kept across rebuilds)
    gpu::UniqueRenderPass overlayPass;
    std::vector<gpu::UniqueFramebuffer> framebuffers;
    gpu::UniqueDescriptorPool overlayPool;
    OverlayContext overlay;
    double slotGpuMs = -1.0;   ///< GPU time of the frame waited for by waitForFrameSlot()
    double slotWaitMs = 0.0;   ///< and how long that took

    render::Engine& engine() { return *renderer->engine; }

    ~Impl() {
        if (!ctx) return;
        (void)drain();
        {
            std::lock_guard lock(ctx->queueMutex());
            vkQueueWaitIdle(ctx->queue());
        }
        framebuffers.clear();
        swapchain.reset();
        if (ownsSurface && surface)
            vkDestroySurfaceKHR(ctx->instance(), surface, nullptr);
    }

    // Waits for every frame slot still in flight (their fences), releasing their scenes.
    Result<void> drain() {
        render::Engine& e = engine();
        for (std::uint32_t i = 0; i < e.slotCount(); ++i)
            if (e.busy(i)) {
                auto r = e.collect(i, RenderOptions{});
                if (!r) return std::move(r).error();
            }
        return {};
    }

    Result<void> makeOverlayObjects() {
        const VkDevice dev = ctx->device();
        VkAttachmentDescription color{};
        color.format = swapchain->format();
        color.samples = VK_SAMPLE_COUNT_1_BIT;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // Lantern's picture, blitted just before
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
        VkSubpassDescription sub{};
        sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &ref;
        VkSubpassDependency deps[2]{};
        deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
        deps[0].dstSubpass = 0;
        deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        deps[1].srcSubpass = 0;
        deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
        deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        deps[1].dstStageMask = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
        deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        deps[1].dstAccessMask = 0;
        VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
        rpci.attachmentCount = 1;
        rpci.pAttachments = &color;
        rpci.subpassCount = 1;
        rpci.pSubpasses = &sub;
        rpci.dependencyCount = 2;
        rpci.pDependencies = deps;
        VkRenderPass rp = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateRenderPass(dev, &rpci, nullptr, &rp));
        overlayPass = gpu::UniqueRenderPass(dev, rp);
        ctx->setName(VK_OBJECT_TYPE_RENDER_PASS, rp, "window overlay pass");

        VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 64};
        VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        dpci.maxSets = 64;
        dpci.poolSizeCount = 1;
        dpci.pPoolSizes = &size;
        VkDescriptorPool pool = VK_NULL_HANDLE;
        LANTERN_VK_TRY(vkCreateDescriptorPool(dev, &dpci, nullptr, &pool));
        overlayPool = gpu::UniqueDescriptorPool(dev, pool);

        overlay.instance = ctx->instance();
        overlay.physicalDevice = ctx->physicalDevice();
        overlay.device = dev;
        overlay.queueFamily = ctx->queueFamily();
        overlay.queue = ctx->queue();
        overlay.pipelineCache = ctx->pipelineCache();
        overlay.descriptorPool = pool;
        overlay.renderPass = rp;
        overlay.imageCount = std::max<std::uint32_t>(2, engine().slotCount());
        return {};
    }

    // Rebuilds the swapchain for the wanted size once nothing uses the current one. The
    // presentation engine's use of the old images is not fenced (without
    // VK_EXT_swapchain_maintenance1), so the queue is drained too; resizes are rare.
    Result<void> rebuild() {
        LANTERN_TRY(drain());
        {
            std::lock_guard lock(ctx->queueMutex());
            LANTERN_VK_TRY(vkQueueWaitIdle(ctx->queue()));
        }
        framebuffers.clear();
        auto built = swapchain->rebuild(std::uint32_t(std::max(wantWidth, 0)),
                                        std::uint32_t(std::max(wantHeight, 0)));
        if (!built) return std::move(built).error();
        stale = !*built;  // a 0 x 0 surface: try again at the next frame
        if (!*built) return {};
        // Render-finished semaphores per image: existing ones are kept (a pending present may
        // still wait on one), more are made when the new swapchain has more images.
        while (rendered.size() < swapchain->imageCount()) {
            auto s = makeSemaphore(*ctx, "rendered " + std::to_string(rendered.size()));
            if (!s) return std::move(s).error();
            rendered.push_back(std::move(*s));
        }
        if (overlayPass) {
            const VkExtent2D e = swapchain->extent();
            for (std::uint32_t i = 0; i < swapchain->imageCount(); ++i) {
                VkImageView view = swapchain->view(i);
                VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
                fci.renderPass = overlayPass.get();
                fci.attachmentCount = 1;
                fci.pAttachments = &view;
                fci.width = e.width;
                fci.height = e.height;
                fci.layers = 1;
                VkFramebuffer fb = VK_NULL_HANDLE;
                LANTERN_VK_TRY(vkCreateFramebuffer(ctx->device(), &fci, nullptr, &fb));
                framebuffers.emplace_back(ctx->device(), fb);
            }
        }
        return {};
    }

    // After the scene: the picture into the swapchain image, then the overlay pass.
    void recordPresentation(VkCommandBuffer cmd, VkImage color, std::uint32_t w, std::uint32_t h,
                            std::uint32_t index, const OverlayRecorder& recorder) {
        const VkImage target = swapchain->image(index);
        // Waits on the acquire semaphore, whose wait is at the transfer stage.
        gpu::imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                          VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[1] = {int(w), int(h), 1};
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.dstOffsets[1] = {int(w), int(h), 1};
        vkCmdBlitImage(cmd, color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
        if (!overlayPass) {
            gpu::imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT,
                              VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                              VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_NONE, 0);
            return;
        }
        gpu::imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
        VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        rbi.renderPass = overlayPass.get();
        rbi.framebuffer = framebuffers[index].get();
        rbi.renderArea = {{0, 0}, {w, h}};
        vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
        if (recorder) recorder(cmd);
        vkCmdEndRenderPass(cmd);
    }
};

WindowTarget::WindowTarget(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
WindowTarget::WindowTarget(WindowTarget&&) noexcept = default;
WindowTarget& WindowTarget::operator=(WindowTarget&&) noexcept = default;
WindowTarget::~WindowTarget() = default;

VkInstance WindowTarget::windowInstance(const Renderer& renderer) {
    return renderer.m_impl->ctx->instance();
}

Result<WindowTarget> WindowTarget::create(Renderer& renderer, const WindowTargetDesc& desc) {
    Renderer::Impl& r = *renderer.m_impl;
    if (!desc.surface) return makeError(ErrorCode::Usage, "WindowTargetDesc::surface is null");
    if (!r.presentation) {
        if (desc.ownsSurface) vkDestroySurfaceKHR(r.ctx->instance(), desc.surface, nullptr);
        return makeError(ErrorCode::Usage,
                         "the renderer was not created for presentation (RendererDesc::presentation)");
    }
    // From here on the Impl owns an owned surface: a failure below destroys it with the Impl.
    auto impl = std::make_unique<Impl>();
    impl->renderer = &r;
    impl->ctx = r.ctx;
    impl->surface = desc.surface;
    impl->ownsSurface = desc.ownsSurface;
    impl->wantWidth = desc.width;
    impl->wantHeight = desc.height;
    auto swapchain = gpu::Swapchain::create(*r.ctx, desc.surface, modePreference(desc.presentMode),
                                            r.engine->slotCount());
    if (!swapchain) return std::move(swapchain).error();
    impl->swapchain.emplace(std::move(*swapchain));
    for (std::uint32_t i = 0; i < r.engine->slotCount(); ++i) {
        auto s = makeSemaphore(*r.ctx, "acquired " + std::to_string(i));
        if (!s) return std::move(s).error();
        impl->acquired.push_back(std::move(*s));
    }
    if (desc.overlay) LANTERN_TRY(impl->makeOverlayObjects());
    if (desc.width > 0 && desc.height > 0) LANTERN_TRY(impl->rebuild());
    return WindowTarget(std::move(impl));
}

void WindowTarget::resize(int width, int height) {
    if (width == m_impl->wantWidth && height == m_impl->wantHeight) return;
    m_impl->wantWidth = width;
    m_impl->wantHeight = height;
    m_impl->stale = true;
}

Result<WindowFrame> WindowTarget::render(const PreparedScene& prepared, const RenderOptions& options,
                                         double time, const FrameRequest& request,
                                         const OverlayRecorder& overlay) {
    Impl& m = *m_impl;
    if (!prepared) return makeError(ErrorCode::Usage, "render() needs a prepared scene");
    WindowFrame out;
    if (m.wantWidth <= 0 || m.wantHeight <= 0) {
        out.status = FrameStatus::Minimised;
        return out;
    }
    if (m.stale || !m.swapchain->valid()) {
        LANTERN_TRY(m.rebuild());
        out.status = m.swapchain->valid() ? FrameStatus::Recreated : FrameStatus::Minimised;
        return out;
    }
    render::Engine& engine = m.engine();
    RenderOptions o = options;
    o.width = int(m.swapchain->extent().width);
    o.height = int(m.swapchain->extent().height);
    LANTERN_TRY(engine.checkOptions(o));
    const auto t0 = Clock::now();
    auto plan = render::buildFramePlan(prepared.scene(), o, time);
    if (!plan) return std::move(plan).error();
    const std::size_t pipelinesBefore = engine.pipelineCount();
    double planMs = msSince(t0);

    // The slot's previous frame must be finished before its images, arena and acquire
    // semaphore are reused: this wait is what bounds the frames in flight.
    const auto t1 = Clock::now();
    const std::uint32_t slot = engine.nextSlot();
    out.stats.gpuMs = std::exchange(m.slotGpuMs, -1.0);
    const double waitedBefore = std::exchange(m.slotWaitMs, 0.0);
    if (engine.busy(slot)) {
        auto done = engine.collect(slot, o);
        if (!done) return std::move(done).error();
        out.stats.gpuMs = done->gpuMs;
    }
    std::uint32_t index = 0;
    auto acquired = m.swapchain->acquire(m.acquired[slot].get(), index);
    if (!acquired) return std::move(acquired).error();
    if (*acquired == gpu::SwapchainState::OutOfDate) {
        m.stale = true;
        LANTERN_TRY(m.rebuild());
        out.status = m.swapchain->valid() ? FrameStatus::Recreated : FrameStatus::Minimised;
        return out;
    }
    if (*acquired == gpu::SwapchainState::Suboptimal) m.stale = true;
    out.stats.waitMs = waitedBefore + msSince(t1);

    const auto t2 = Clock::now();
    render::SubmitHooks hooks;
    hooks.readback = request.capture;
    hooks.wait = m.acquired[slot].get();
    hooks.signal = m.rendered[index].get();
    hooks.afterRender = [&](VkCommandBuffer cmd, VkImage color, std::uint32_t w, std::uint32_t h) {
        m.recordPresentation(cmd, color, w, h, index, overlay);
    };
    auto submitted = engine.submit(prepared.m_gpu, *plan, o, hooks);
    if (!submitted) {
        // The acquire semaphore is signalled and will never be waited on: replace it.
        if (auto fresh = makeSemaphore(*m.ctx, "acquired " + std::to_string(slot)))
            m.acquired[slot] = std::move(*fresh);
        m.stale = true;
        return std::move(submitted).error();
    }
    out.stats.cpuMs = planMs + msSince(t2);
    const auto t3 = Clock::now();
    auto presented = m.swapchain->present(m.rendered[index].get(), index);
    if (!presented) return std::move(presented).error();
    if (*presented != gpu::SwapchainState::Ready) m.stale = true;
    out.presentMs = msSince(t3);
    out.stats.draws = 0;
    for (const render::ViewPlan& v : plan->views) out.stats.draws += v.draws.size();
    out.stats.pipelinesCreated = engine.pipelineCount() - pipelinesBefore;
    out.status = FrameStatus::Presented;

    if (request.capture) {
        auto frame = engine.collect(*submitted, o);
        if (!frame) return std::move(frame).error();
        out.stats.gpuMs = frame->gpuMs;
        out.stats.nonFinite = frame->nonFinite;
        Image image = std::move(frame->image);
        attachMetadata(image, *plan, m.renderer->info, time);
        out.capture = std::move(image);
    }
    m.renderer->stats = out.stats;
    return out;
}

Result<double> WindowTarget::waitForFrameSlot() {
    render::Engine& engine = m_impl->engine();
    const std::uint32_t slot = engine.nextSlot();
    if (!engine.busy(slot)) return 0.0;
    const auto t0 = Clock::now();
    auto done = engine.collect(slot, RenderOptions{});
    if (!done) return std::move(done).error();
    m_impl->slotGpuMs = done->gpuMs;
    m_impl->slotWaitMs += msSince(t0);
    return m_impl->slotWaitMs;
}

int WindowTarget::width() const {
    return m_impl->swapchain->valid() ? int(m_impl->swapchain->extent().width) : 0;
}
int WindowTarget::height() const {
    return m_impl->swapchain->valid() ? int(m_impl->swapchain->extent().height) : 0;
}

PresentMode WindowTarget::presentMode() const {
    switch (m_impl->swapchain->presentMode()) {
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return PresentMode::Immediate;
    case VK_PRESENT_MODE_MAILBOX_KHR: return PresentMode::Mailbox;
    default: return PresentMode::Fifo;
    }
}

std::uint32_t WindowTarget::imageCount() const { return m_impl->swapchain->imageCount(); }
std::uint32_t WindowTarget::framesInFlight() const { return m_impl->engine().slotCount(); }
VkFormat WindowTarget::format() const { return m_impl->swapchain->format(); }
const OverlayContext& WindowTarget::overlayContext() const { return m_impl->overlay; }

Result<void> WindowTarget::submitOnce(const std::function<void(VkCommandBuffer)>& record) {
    return m_impl->ctx->submitAndWait(record);
}

Result<void> WindowTarget::waitIdle() {
    LANTERN_TRY(m_impl->drain());
    std::lock_guard lock(m_impl->ctx->queueMutex());
    LANTERN_VK_TRY(vkQueueWaitIdle(m_impl->ctx->queue()));
    return {};
}

} // namespace lantern
