// Window frames on the Vulkan side: swapchain (re)building, the overlay render pass, acquire,
// submission through the frame ring with the window's semaphores, the blit into the swapchain
// image, and presentation.
#include "gpu/Presenter.h"

#include "gpu/FrameRing.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace lantern::gpu {
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

Result<UniqueSemaphore> makeSemaphore(Context& ctx, const std::string& name) {
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateSemaphore(ctx.device(), &sci, nullptr, &s));
    ctx.setName(VK_OBJECT_TYPE_SEMAPHORE, s, name);
    return UniqueSemaphore(ctx.device(), s);
}

} // namespace

VkInstance Presenter::instance(Device& device) { return device.context().instance(); }

Result<std::unique_ptr<Presenter>> Presenter::create(Device& device, const WindowTargetDesc& desc) {
    Context& ctx = device.context();
    if (!desc.surface) return makeError(ErrorCode::Usage, "WindowTargetDesc::surface is null");
    if (!device.presentation()) {
        if (desc.ownsSurface) vkDestroySurfaceKHR(ctx.instance(), desc.surface, nullptr);
        return makeError(ErrorCode::Usage,
                         "the renderer was not created for presentation (RendererDesc::presentation)");
    }
    // From here on the presenter owns an owned surface: a failure below destroys it with it.
    std::unique_ptr<Presenter> p(new Presenter(device));
    p->m_surface = desc.surface;
    p->m_ownsSurface = desc.ownsSurface;
    p->m_wantWidth = desc.width;
    p->m_wantHeight = desc.height;
    auto swapchain = Swapchain::create(ctx, desc.surface, modePreference(desc.presentMode),
                                       device.slotCount());
    if (!swapchain) return std::move(swapchain).error();
    p->m_swapchain.emplace(std::move(*swapchain));
    for (std::uint32_t i = 0; i < device.slotCount(); ++i) {
        auto s = makeSemaphore(ctx, "acquired " + std::to_string(i));
        if (!s) return std::move(s).error();
        p->m_acquired.push_back(std::move(*s));
    }
    if (desc.overlay) LANTERN_TRY(p->makeOverlayObjects());
    if (desc.width > 0 && desc.height > 0) LANTERN_TRY(p->rebuild());
    return p;
}

Presenter::~Presenter() {
    Context& ctx = m_device.context();
    (void)drain();
    {
        std::lock_guard lock(ctx.queueMutex());
        vkQueueWaitIdle(ctx.queue());
    }
    m_framebuffers.clear();
    m_swapchain.reset();
    if (m_ownsSurface && m_surface) vkDestroySurfaceKHR(ctx.instance(), m_surface, nullptr);
}

// Waits for every frame slot still in flight (their fences), releasing their scenes.
Result<void> Presenter::drain() { return m_device.drain(); }

void Presenter::resize(int width, int height) {
    if (width == m_wantWidth && height == m_wantHeight) return;
    m_wantWidth = width;
    m_wantHeight = height;
    m_stale = true;
}

Result<std::optional<FrameStatus>> Presenter::prepare() {
    if (m_wantWidth <= 0 || m_wantHeight <= 0) return std::optional(FrameStatus::Minimised);
    if (m_stale || !m_swapchain->valid()) {
        LANTERN_TRY(rebuild());
        return std::optional(m_swapchain->valid() ? FrameStatus::Recreated : FrameStatus::Minimised);
    }
    return std::optional<FrameStatus>();
}

Result<void> Presenter::makeOverlayObjects() {
    Context& ctx = m_device.context();
    const VkDevice dev = ctx.device();
    VkAttachmentDescription color{};
    color.format = m_swapchain->format();
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
    m_overlayPass = UniqueRenderPass(dev, rp);
    ctx.setName(VK_OBJECT_TYPE_RENDER_PASS, rp, "window overlay pass");

    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 64};
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dpci.maxSets = 64;
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    LANTERN_VK_TRY(vkCreateDescriptorPool(dev, &dpci, nullptr, &pool));
    m_overlayPool = UniqueDescriptorPool(dev, pool);

    m_overlay.instance = ctx.instance();
    m_overlay.physicalDevice = ctx.physicalDevice();
    m_overlay.device = dev;
    m_overlay.queueFamily = ctx.queueFamily();
    m_overlay.queue = ctx.queue();
    m_overlay.pipelineCache = ctx.pipelineCache();
    m_overlay.descriptorPool = pool;
    m_overlay.renderPass = rp;
    m_overlay.imageCount = std::max<std::uint32_t>(2, m_device.slotCount());
    return {};
}

// Rebuilds the swapchain for the wanted size once nothing uses the current one. The
// presentation engine's use of the old images is not fenced (without
// VK_EXT_swapchain_maintenance1), so the queue is drained too; resizes are rare.
Result<void> Presenter::rebuild() {
    Context& ctx = m_device.context();
    LANTERN_TRY(drain());
    {
        std::lock_guard lock(ctx.queueMutex());
        LANTERN_VK_TRY(vkQueueWaitIdle(ctx.queue()));
    }
    m_framebuffers.clear();
    auto built = m_swapchain->rebuild(std::uint32_t(std::max(m_wantWidth, 0)),
                                    std::uint32_t(std::max(m_wantHeight, 0)));
    if (!built) return std::move(built).error();
    m_stale = !*built;  // a 0 x 0 surface: try again at the next frame
    if (!*built) return {};
    // Render-finished semaphores per image: existing ones are kept (a pending present may
    // still wait on one), more are made when the new swapchain has more images.
    while (m_rendered.size() < m_swapchain->imageCount()) {
        auto s = makeSemaphore(ctx, "rendered " + std::to_string(m_rendered.size()));
        if (!s) return std::move(s).error();
        m_rendered.push_back(std::move(*s));
    }
    if (m_overlayPass) {
        const VkExtent2D e = m_swapchain->extent();
        for (std::uint32_t i = 0; i < m_swapchain->imageCount(); ++i) {
            VkImageView view = m_swapchain->view(i);
            VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
            fci.renderPass = m_overlayPass.get();
            fci.attachmentCount = 1;
            fci.pAttachments = &view;
            fci.width = e.width;
            fci.height = e.height;
            fci.layers = 1;
            VkFramebuffer fb = VK_NULL_HANDLE;
            LANTERN_VK_TRY(vkCreateFramebuffer(ctx.device(), &fci, nullptr, &fb));
            m_framebuffers.emplace_back(ctx.device(), fb);
        }
    }
    return {};
}

// After the scene: the picture into the swapchain image, then the overlay pass.
void Presenter::recordPresentation(VkCommandBuffer cmd, VkImage color, VkImageLayout layout,
                                   std::uint32_t w, std::uint32_t h,
                        std::uint32_t index, const OverlayRecorder& recorder) {
    const VkImage target = m_swapchain->image(index);
    // Waits on the acquire semaphore, whose wait is at the transfer stage.
    imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                      VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int(w), int(h), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int(w), int(h), 1};
    vkCmdBlitImage(cmd, color, layout, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    if (!m_overlayPass) {
        imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT,
                          VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                          VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_NONE, 0);
        return;
    }
    imageBarrier(cmd, target, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rbi.renderPass = m_overlayPass.get();
    rbi.framebuffer = m_framebuffers[index].get();
    rbi.renderArea = {{0, 0}, {w, h}};
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    if (recorder) recorder(cmd);
    vkCmdEndRenderPass(cmd);
}
Result<PresentedFrame> Presenter::present(const DrawList& list,
                                          const std::shared_ptr<SceneBuffers>& scene,
                                          bool capture, const OverlayRecorder& overlay) {
    Context& ctx = m_device.context();
    FrameRing& ring = m_device.ring();
    PresentedFrame out;
    const std::size_t pipelinesBefore = m_device.pipelineCount();
    // The slot's previous frame must be finished before its images, arena and acquire
    // semaphore are reused: this wait is what bounds the frames in flight.
    const auto t1 = Clock::now();
    const std::uint32_t slot = ring.nextSlot();
    out.gpuMs = std::exchange(m_slotGpuMs, -1.0);
    const double waitedBefore = std::exchange(m_slotWaitMs, 0.0);
    if (ring.busy(slot)) {
        auto done = ring.collect(slot);
        if (!done) return std::move(done).error();
        out.gpuMs = done->gpuMs;
    }
    std::uint32_t index = 0;
    auto acquired = m_swapchain->acquire(m_acquired[slot].get(), index);
    if (!acquired) return std::move(acquired).error();
    if (*acquired == SwapchainState::OutOfDate) {
        m_stale = true;
        LANTERN_TRY(rebuild());
        out.status = m_swapchain->valid() ? FrameStatus::Recreated : FrameStatus::Minimised;
        return out;
    }
    if (*acquired == SwapchainState::Suboptimal) m_stale = true;
    out.waitMs = waitedBefore + msSince(t1);

    const auto t2 = Clock::now();
    SubmitHooks hooks;
    hooks.readback = capture;
    hooks.wait = m_acquired[slot].get();
    hooks.signal = m_rendered[index].get();
    hooks.afterRender = [&](VkCommandBuffer cmd, VkImage color, VkImageLayout layout,
                            std::uint32_t w, std::uint32_t h) {
        recordPresentation(cmd, color, layout, w, h, index, overlay);
    };
    auto submitted = ring.submit(list, scene, hooks);
    if (!submitted) {
        // The acquire semaphore is signalled and will never be waited on: replace it.
        if (auto fresh = makeSemaphore(ctx, "acquired " + std::to_string(slot)))
            m_acquired[slot] = std::move(*fresh);
        m_stale = true;
        return std::move(submitted).error();
    }
    out.submitMs = msSince(t2);
    const auto t3 = Clock::now();
    auto presented = m_swapchain->present(m_rendered[index].get(), index);
    if (!presented) return std::move(presented).error();
    if (*presented != SwapchainState::Ready) m_stale = true;
    out.presentMs = msSince(t3);
    out.pipelinesCreated = m_device.pipelineCount() - pipelinesBefore;
    out.status = FrameStatus::Presented;
    if (capture) {
        auto frame = ring.collect(*submitted);
        if (!frame) return std::move(frame).error();
        out.gpuMs = frame->gpuMs;
        out.capture = std::move(*frame);
    }
    return out;
}

Result<double> Presenter::waitForFrameSlot() {
    FrameRing& ring = m_device.ring();
    const std::uint32_t slot = ring.nextSlot();
    if (!ring.busy(slot)) return 0.0;
    const auto t0 = Clock::now();
    auto done = ring.collect(slot);
    if (!done) return std::move(done).error();
    m_slotGpuMs = done->gpuMs;
    m_slotWaitMs += msSince(t0);
    return m_slotWaitMs;
}

Result<void> Presenter::waitIdle() {
    LANTERN_TRY(drain());
    Context& ctx = m_device.context();
    std::lock_guard lock(ctx.queueMutex());
    LANTERN_VK_TRY(vkQueueWaitIdle(ctx.queue()));
    return {};
}

Result<void> Presenter::submitOnce(const std::function<void(VkCommandBuffer)>& record) {
    return m_device.context().submitAndWait(record);
}

int Presenter::width() const { return m_swapchain->valid() ? int(m_swapchain->extent().width) : 0; }
int Presenter::height() const {
    return m_swapchain->valid() ? int(m_swapchain->extent().height) : 0;
}

PresentMode Presenter::presentMode() const {
    switch (m_swapchain->presentMode()) {
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return PresentMode::Immediate;
    case VK_PRESENT_MODE_MAILBOX_KHR: return PresentMode::Mailbox;
    default: return PresentMode::Fifo;
    }
}

std::uint32_t Presenter::imageCount() const { return m_swapchain->imageCount(); }
std::uint32_t Presenter::framesInFlight() const { return m_device.slotCount(); }
VkFormat Presenter::format() const { return m_swapchain->format(); }

} // namespace lantern::gpu

namespace lantern {

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

} // namespace lantern
