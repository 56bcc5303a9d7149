// gpu::Device: the context, the pipeline variants and the frame ring behind one Vulkan-free
// interface, and the description of the device (DeviceInfo) the public API reports.
#include "gpu/Device.h"

#include "gpu/Context.h"
#include "gpu/FrameRing.h"
#include "gpu/Overlays.h"
#include "gpu/Pipelines.h"
#include "gpu/SceneBuffers.h"
#include "gpu/Targets.h"

#include <algorithm>
#include <optional>

namespace lantern::gpu {

// Members are destroyed in reverse order: the ring (which waits for the GPU) first, the
// context (the device itself) last.
struct Device::Impl {
    std::shared_ptr<Context> ctx;
    std::optional<Pipelines> pipelines;
    std::unique_ptr<FrameRing> ring;
    DeviceInfo info;
    DeviceLimits limits;
    bool presentation = false;
};

namespace {

const char* deviceType(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

void describe(const Context& ctx, DeviceInfo& info, DeviceLimits& limits) {
    const auto& p = ctx.properties();
    info.name = p.deviceName;
    info.driver = ctx.driverInfo();
    info.type = deviceType(p.deviceType);
    info.apiVersion = p.apiVersion;
    info.validationEnabled = ctx.validationEnabled();
    const Capabilities& caps = ctx.capabilities();
    for (int s : {1, 2, 4, 8})
        if (caps.colorDepthSampleCounts & std::uint32_t(s)) info.msaaSampleCounts.push_back(s);
    info.pipelineCacheFile = ctx.diskCache().file().string();
    info.pipelineCacheLoadedBytes = ctx.diskCache().loadedBytes();
    limits.maxImageDimension = p.limits.maxImageDimension2D;
    limits.sampleCounts = caps.colorDepthSampleCounts;
    limits.primitiveId = caps.primitiveIdInFragment;
    limits.wireframe = caps.fillModeNonSolid;
    limits.deviceMemory = ctx.largestDeviceLocalHeap();
}

PipelineCacheSettings pipelineCacheSettings(const DeviceDesc& desc) {
    return {desc.pipelineCacheOnDisk, desc.pipelineCacheFolder};
}

} // namespace

Device::Device(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Device::~Device() = default;

Result<std::shared_ptr<Device>> Device::assemble(std::shared_ptr<Context> ctx,
                                                const DeviceDesc& desc) {
    auto impl = std::make_unique<Impl>();
    impl->ctx = std::move(ctx);
    impl->presentation = desc.presentation;
    auto pipelines = Pipelines::create(*impl->ctx);
    if (!pipelines) return std::move(pipelines).error();
    impl->pipelines.emplace(std::move(*pipelines));
    auto ring = FrameRing::create(*impl->ctx, *impl->pipelines, desc.framesInFlight);
    if (!ring) return std::move(ring).error();
    impl->ring = std::move(*ring);
    describe(*impl->ctx, impl->info, impl->limits);
    return std::shared_ptr<Device>(new Device(std::move(impl)));
}

Result<std::shared_ptr<Device>> Device::create(const DeviceDesc& desc) {
    ContextDesc cd;
    cd.deviceName = desc.deviceName;
    cd.validation = desc.validation;
    cd.synchronizationValidation = desc.synchronizationValidation;
    cd.log = desc.log;
    cd.instanceExtensions = desc.instanceExtensions;
    cd.swapchain = desc.presentation;
    cd.pipelineCache = pipelineCacheSettings(desc);
    auto ctx = Context::create(cd);
    if (!ctx) return std::move(ctx).error();
    return assemble(std::move(*ctx), desc);
}

Result<std::shared_ptr<Device>> Device::adopt(const ExternalDevice& external,
                                              const DeviceDesc& desc) {
    auto ctx =
        Context::adopt(external, desc.presentation, pipelineCacheSettings(desc), desc.log);
    if (!ctx) return std::move(ctx).error();
    return assemble(std::move(*ctx), desc);
}

const DeviceInfo& Device::info() const { return m_impl->info; }
const DeviceLimits& Device::limits() const { return m_impl->limits; }
bool Device::presentation() const { return m_impl->presentation; }
std::uint64_t Device::deviceBytes() const { return m_impl->ctx->deviceBytes(); }

std::uint64_t Device::validationMessageCount() const {
    return m_impl->ctx->validationMessageCount();
}
void Device::log(LogLevel level, const std::string& message) const {
    m_impl->ctx->log(level, message);
}

Result<std::shared_ptr<SceneBuffers>> Device::upload(std::shared_ptr<const Scene> scene) {
    return SceneBuffers::create(m_impl->ctx, std::move(scene),
                                m_impl->pipelines->textureSetLayout());
}

const Scene& Device::sceneOf(const SceneBuffers& buffers) { return buffers.scene(); }

Result<void> Device::updateVertices(SceneBuffers& buffers, std::uint32_t mesh,
                                    std::uint32_t prim) {
    if (buffers.context() != m_impl->ctx.get())
        return makeError(ErrorCode::Usage, "the scene was prepared by another renderer",
                         "updateVertices");
    return buffers.updateVertices(mesh, prim);
}

Result<void> Device::checkTarget(const TargetDesc& target, const Overlays& overlays) const {
    LANTERN_TRY(gpu::checkTarget(*m_impl->ctx, target, m_impl->ring->slotCount()));
    return OverlayPipelines::check(*m_impl->ctx, overlays, target.aovs);
}

Result<std::uint32_t> Device::submit(const DrawList& list,
                                     const std::shared_ptr<SceneBuffers>& scene) {
    return m_impl->ring->submit(list, scene);
}

Result<FrameReadback> Device::collect(std::uint32_t slot, lantern::Image storage, bool inPlace) {
    return m_impl->ring->collect(slot, std::move(storage), inPlace);
}

Result<void> Device::drain() {
    FrameRing& ring = *m_impl->ring;
    for (std::uint32_t i = 0; i < ring.slotCount(); ++i)
        if (ring.busy(i)) {
            auto r = ring.collect(i);
            if (!r) return std::move(r).error();
        }
    return {};
}

bool Device::busy(std::uint32_t slot) const { return m_impl->ring->busy(slot); }
std::uint32_t Device::nextSlot() const { return m_impl->ring->nextSlot(); }
std::uint32_t Device::slotCount() const { return m_impl->ring->slotCount(); }
std::size_t Device::pipelineCount() const { return m_impl->pipelines->count(); }
Context& Device::context() { return *m_impl->ctx; }
FrameRing& Device::ring() { return *m_impl->ring; }

} // namespace lantern::gpu
