// Device.h: the GPU as the rest of the engine sees it, with no Vulkan type in sight: a device
// (Lantern's own or the host's), scenes uploaded to it, and a ring of frame slots that records
// a DrawList, submits it and reads the picture back. Frame k+1 can be recorded and rendering
// while frame k is read back (the headless double buffer): submit() returns the slot, and
// collect() every submitted slot in order. Everything Vulkan lives behind this, in gpu/.
#pragma once

#include "gpu/DrawList.h"

#include <lantern/Image.h>
#include <lantern/Log.h>
#include <lantern/RenderTypes.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lantern {
struct ExternalDevice;
}

namespace lantern::gpu {

class Context;
class FrameRing;
class SceneBuffers;

struct DeviceDesc {
    std::string deviceName;  ///< an index or a name substring; empty: LANTERN_DEVICE, else the best
    bool validation = false;
    bool synchronizationValidation = false;
    std::vector<std::string> instanceExtensions;  ///< e.g. the surface extensions of a window
    bool presentation = false;                    ///< enable VK_KHR_swapchain on the device
    std::uint32_t framesInFlight = 2;
    bool pipelineCacheOnDisk = true;  ///< RendererDesc's: keep compiled pipelines between runs
    std::string pipelineCacheFolder;  ///< empty: the environment's (gpu/PipelineCache.h)
    LogSink log;
};

/// What the device offers that options depend on.
struct DeviceLimits {
    std::uint32_t maxImageDimension = 0;  ///< pixels per side
    std::uint32_t sampleCounts = 1;       ///< bit mask of supported counts (float colour + depth)
    bool primitiveId = false;             ///< gl_PrimitiveID in fragments: the AOV ids need it
    bool wireframe = false;               ///< fillModeNonSolid
    std::uint64_t deviceMemory = 0;       ///< bytes of the largest device-local heap
};

/// The colour plane of a frame collected in place (collect(..., inPlace)): where the host reads
/// it, the mapped render target or staging buffer, rows `rowPitch` bytes apart. It stays there
/// until the ring submits its next frame or is destroyed, when `*live` turns false.
struct HostView {
    const char* data = nullptr;
    std::size_t rowPitch = 0;
    std::shared_ptr<const std::atomic<bool>> live;
};

/// A frame read back from its slot.
struct FrameReadback {
    lantern::Image image;           ///< empty when the frame was submitted without readback
                                    ///< (or collected in place: its size only, see `view`)
    HostView view;                  ///< the colour where it lies, when collected in place
    double gpuMs = -1.0;            ///< render-pass time from GPU timestamps (-1: unavailable)
    std::uint64_t nonFinite = 0;    ///< NaN/Inf values found (and zeroed) at readback
    int nonFiniteX = -1, nonFiniteY = -1;  ///< the first colour pixel that held one (-1: none)
    /// The host read the whole colour plane for NaN/Inf. False when the stages that made the
    /// frame's colours vouched for it (shaders/include/guard.glsl): nothing tripped the guard.
    bool hostChecked = true;
    std::size_t draws = 0;
    /// Flat triangles given to the per-triangle lighting pass (gpu/FlatLight.h); those it
    /// finds outside the view or back-facing are skipped, the others lit once.
    std::uint64_t flatTriangles = 0;
    /// The clustered draws' triangles and those the culling pass kept (gpu/Clusters.h).
    std::uint64_t clusterTriangles = 0, clusterTrianglesDrawn = 0;
    /// When the frame asked for them (TargetDesc::ids, the probe): per pixel (draw index + 1,
    /// primitive id); 0: no draw.
    std::vector<std::uint32_t> ids;
    /// Exact transparency (gpu/Transparency.h): the blended fragments the frame stored, the
    /// lists' capacity (more fragments than that: the frame lost some and is rendered again
    /// with room for them) and the pixels with more than LANTERN_OIT_MAX_LAYERS.
    std::uint64_t listFragments = 0, listCapacity = 0, listTruncatedPixels = 0;
    bool listsGrow = false;  ///< the lists overflowed and the next frame's hold more
};

class Device {
public:
    /// Creates Lantern's own instance and device. NoDevice when none can render.
    static Result<std::shared_ptr<Device>> create(const DeviceDesc& desc);
    /// A device on the host's instance, device and queue (never destroyed by Lantern).
    static Result<std::shared_ptr<Device>> adopt(const ExternalDevice& external,
                                                 const DeviceDesc& desc);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    const DeviceInfo& info() const;
    const DeviceLimits& limits() const;
    bool presentation() const;
    std::uint64_t validationMessageCount() const;
    /// Bytes of device memory Lantern's buffers and images hold now.
    std::uint64_t deviceBytes() const;
    void log(LogLevel level, const std::string& message) const;

    /// Uploads `scene` (which must have passed Scene::validate()).
    Result<std::shared_ptr<SceneBuffers>> upload(std::shared_ptr<const Scene> scene);
    /// The scene an upload holds.
    static const Scene& sceneOf(const SceneBuffers& buffers);
    /// Writes again the positions and normals of one primitive of an upload of this device
    /// after the host edited them in its Scene (SceneBuffers::updateVertices); Usage for an
    /// upload of another device.
    Result<void> updateVertices(SceneBuffers& buffers, std::uint32_t mesh, std::uint32_t prim);

    /// Refuses, before anything is allocated, a target or overlay this device cannot make:
    /// InvalidInput, Unsupported or OutOfMemory naming the option.
    Result<void> checkTarget(const TargetDesc& target, const Overlays& overlays) const;

    /// Records and submits `list` into the next slot (which must have been collected).
    Result<std::uint32_t> submit(const DrawList& list, const std::shared_ptr<SceneBuffers>& scene);
    /// Waits for the frame in `slot` and reads it back, into `storage`'s vectors when given (their
    /// memory is reused: a host rendering many frames of one size allocates nothing). With
    /// `inPlace` the colour is not copied: FrameReadback::view says where it lies (checked for
    /// NaN and Inf there, not scrubbed), valid until the next submit; AOV planes are not read.
    Result<FrameReadback> collect(std::uint32_t slot, lantern::Image storage = {},
                                  bool inPlace = false);
    /// Collects every slot still in flight (their pictures are dropped).
    Result<void> drain();
    bool busy(std::uint32_t slot) const;
    std::uint32_t nextSlot() const;
    std::uint32_t slotCount() const;
    std::size_t pipelineCount() const;  ///< pipeline variants created so far

    /// For gpu/ itself (the window presenter): the Vulkan objects behind the device.
    Context& context();
    FrameRing& ring();

private:
    struct Impl;
    static Result<std::shared_ptr<Device>> assemble(std::shared_ptr<Context> ctx,
                                                    const DeviceDesc& desc);
    explicit Device(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

/// The Vulkan devices of this machine, on an instance of its own (lantern::listDevices).
Result<DeviceList> listDevices(const std::string& deviceName);
/// The Vulkan loader's version ("1.3.239"), or empty (lantern::vulkanLoaderVersion).
std::string vulkanLoaderVersion();

} // namespace lantern::gpu
