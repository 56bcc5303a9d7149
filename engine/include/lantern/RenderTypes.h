// RenderTypes.h: the plain types the renderer's entry points (lantern/Renderer.h) and the
// engine's rooms share: how a renderer is created, what a device is, what a frame measured,
// what a render needs. Types only: nothing here is implemented anywhere.
#pragma once

#include <lantern/Log.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lantern {

/// How the renderer is created.
struct RendererDesc {
    /// The device to render on: a whole number is its index in listDevices() (the loader's
    /// order), other text picks the best usable device whose name contains it
    /// (case-insensitive). Empty: the environment variable LANTERN_DEVICE (same forms) when it
    /// is set, else the best usable device (discrete GPUs first, then integrated, virtual,
    /// CPU). A request that matches no usable device is NoDevice, listing the devices found.
    std::string deviceName;
    /// Enable the Khronos validation layer when it is installed; its messages go to `log` at
    /// Warning or Error level and are counted (validationMessageCount()).
    bool validation = false;
    /// Also enable synchronisation validation (implies `validation`).
    bool synchronizationValidation = false;
    /// Frames that may be in flight at once (each with its own images, command buffer, fence
    /// and readback buffer): 2 is the classic double buffer.
    int framesInFlight = 2;
    /// For presenting in a window (lantern/Window.h): the instance extensions the host's
    /// surface needs (GLFW: glfwGetRequiredInstanceExtensions; lantern/glfw/GlfwWindow.h fills
    /// them in), and VK_KHR_swapchain on the device (devices without it are passed over).
    std::vector<std::string> instanceExtensions;
    bool presentation = false;
    /// Keep compiled pipelines on disk so that the next process does not compile them again
    /// (docs/performance.md, "Pipeline cache"): one file per device, driver and Lantern
    /// version in `pipelineCacheFolder`, or when that is empty in $LANTERN_CACHE_DIR,
    /// $XDG_CACHE_HOME/lantern or ~/.cache/lantern. A damaged file or a folder that cannot be
    /// written is a warning, never a failure. The environment variable LANTERN_PIPELINE_CACHE=0
    /// turns it off whatever this says.
    bool pipelineCacheOnDisk = true;
    std::string pipelineCacheFolder;
    LogSink log;
};

/// Measurements of the last frame rendered.
struct FrameStats {
    double gpuMs = -1.0;    ///< render-pass time from GPU timestamps (-1: not available)
    double cpuMs = 0.0;     ///< planning, recording and submission on the CPU
    double waitMs = 0.0;    ///< waiting for the GPU and reading the image back
    std::size_t draws = 0;  ///< draw calls (an instanced draw counts once)
    std::size_t pipelinesCreated = 0;  ///< variants compiled for this frame (first use)
    /// NaN/Inf values found at readback (always 0 unless a bug). render() and renderSequence()
    /// refuse such a frame (ErrorCode::Internal, naming the first pixel's object); the
    /// viewer shows it with the values replaced by 0.
    std::uint64_t nonFinite = 0;
    /// The triangles of the frame's clustered draws (every view, every instance, at full
    /// detail) and those the culling pass kept for the rasteriser (after the view, back-face
    /// and level-of-detail tests). Both 0 when no draw was clustered (culling off, or no mesh
    /// large enough).
    std::uint64_t clusterTriangles = 0, clusterTrianglesDrawn = 0;
};

/// What the device is.
struct DeviceInfo {
    std::string name;         ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string driver;       ///< e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
    std::string type;         ///< "cpu", "discrete-gpu", "integrated-gpu", "virtual-gpu", "other"
    std::uint32_t apiVersion = 0;
    bool validationEnabled = false;
    std::vector<int> msaaSampleCounts;  ///< supported for float colour + depth
    /// The file compiled pipelines are kept in between runs (empty: kept in memory only).
    std::string pipelineCacheFile;
    /// Bytes of the driver's pipeline data loaded from that file when the device was created
    /// (0: a first run, the cache off, or a file refused with a warning).
    std::uint64_t pipelineCacheLoadedBytes = 0;
};

/// One Vulkan device of this machine, as listDevices() sees it.
struct DeviceListing {
    std::string name;    ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string type;    ///< "cpu", "discrete-gpu", "integrated-gpu", "virtual-gpu", "other"
    std::string driver;  ///< e.g. "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"; empty before Vulkan 1.2
    std::string apiVersion;  ///< the Vulkan version the device supports, e.g. "1.3.230"
    bool usable = false;     ///< has what Lantern needs to render headless
    std::string whyNot;      ///< when not usable: what it lacks ("supports Vulkan 1.2, ...")
    bool presentation = false;  ///< has VK_KHR_swapchain (a window, `lantern view`, can use it)
    std::vector<int> msaaSampleCounts;  ///< supported for float colour + depth
    bool chosen = false;  ///< the device Renderer::create would take with the same deviceName
    /// Where Renderer::create (with the default RendererDesc) keeps this device's compiled
    /// pipelines between runs, empty when that is off (then pipelineCacheOff says why), and
    /// the file's size now (-1: not written yet).
    std::string pipelineCacheFile;
    std::int64_t pipelineCacheBytes = -1;
    std::string pipelineCacheOff;
};

/// The devices of this machine and the one Lantern would choose.
struct DeviceList {
    std::vector<DeviceListing> devices;
    /// Why the chosen device (or why none): the ranking applied, e.g. "the best usable device
    /// (discrete GPUs first, then integrated, virtual, CPU)".
    std::string choice;
};

/// What a render needs (the features the scene uses) and the pipelines chosen for it.
struct FeatureReport {
    std::vector<std::string> features;  ///< e.g. "light:directional", "specular:blinn"
    std::vector<std::string> variants;  ///< one line per pipeline variant
};

} // namespace lantern
