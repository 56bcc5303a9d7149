// Renderer: turns a Scene at an instant into an Image, headless, on any Vulkan device
// (lavapipe included). The only public entry to the GPU; no Vulkan type appears here.
#pragma once

#include <lantern/Camera.h>
#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Log.h>
#include <lantern/Options.h>
#include <lantern/Probe.h>
#include <lantern/RenderTypes.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>
#include <lantern/Sequence.h>

#include <glm/vec4.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lantern {

namespace gpu {
class SceneBuffers;
}
class WindowTarget;
struct ExternalDevice;  // lantern/ExternalDevice.h (includes vulkan.h)

/// A scene uploaded to a renderer's device: geometry and textures stay on the device for as
/// many frames as the host renders. Holds a reference to the (immutable) Scene and keeps the
/// device alive; cheap to copy (shared).
class LANTERN_API PreparedScene {
public:
    PreparedScene() = default;
    const Scene& scene() const;
    explicit operator bool() const { return m_gpu != nullptr; }

private:
    friend class Renderer;
    friend class WindowTarget;
    std::shared_ptr<gpu::SceneBuffers> m_gpu;
};

/// Lists the Vulkan devices (on an instance of its own, created and destroyed here) in the
/// loader's order (the index RendererDesc::deviceName and LANTERN_DEVICE may give) with what
/// each lacks and the one Renderer::create(desc with this deviceName) would choose (LANTERN_DEVICE
/// applies when `deviceName` is empty). NoDevice, naming the driver manifests the loader could
/// read and how to install lavapipe, when no Vulkan driver can be loaded; an empty list is not
/// an error (DeviceList::choice then says the same).
LANTERN_API Result<DeviceList> listDevices(const std::string& deviceName = {});

/// The Vulkan loader's version ("1.3.239"), or an empty string when no loader can be queried.
LANTERN_API std::string vulkanLoaderVersion();

/// Where a CameraSpec puts the camera for a view (what a render would use), double precision.
struct CameraPlacement {
    glm::dmat4 viewFromWorld{1.0};
    Projection projection;
    std::string description;  ///< e.g. "camera 0 \"main\"", "automatic framing"
};

/// Resolves `spec` for a view of aspect `aspect` (width / height) of `scene` (which must have
/// passed Scene::validate()) at `timeSeconds`: a host that lets the user move the camera starts
/// from here. InvalidInput when the spec names a camera that does not exist or is not placed.
LANTERN_API Result<CameraPlacement> resolveCameraPlacement(const Scene& scene,
                                                           const CameraSpec& spec, double aspect,
                                                           int root = -1, double timeSeconds = 0.0);

/// The features `scene` needs under `options` at `timeSeconds` and the pipeline variants a
/// renderer would choose for them, computed on the CPU without any device (what `lantern info`
/// and Renderer::explain print). InvalidInput when the scene or the options are refused.
LANTERN_API Result<FeatureReport> explainScene(const Scene& scene, const RenderOptions& options,
                                               double timeSeconds = 0.0);

/// The colour of a frame where the renderer left it (Renderer::renderView): the pixels are read
/// in the device's own memory, mapped for the host, with no copy. On a device whose memory is
/// the host's (lavapipe, integrated GPUs) that is the render target itself; elsewhere the
/// buffer the frame was copied into. Same layout and values as Image::rgba (top row first,
/// linear RGBA floats, premultiplied, checked finite), but rows are rowPitch() bytes apart.
///
/// A view is valid until its renderer submits another frame (render, renderView, a sequence,
/// a probe or a window frame) or is destroyed; after that valid() is false and row() returns
/// null. Copy what must outlive it (toImage()).
class LANTERN_API FrameView {
public:
    FrameView() = default;
    int width() const { return m_header.width; }
    int height() const { return m_header.height; }
    /// Bytes from one row to the next (at least 16 * width()).
    std::size_t rowPitch() const { return m_rowPitch; }
    /// False once the renderer has submitted another frame or is gone (or for an empty view).
    bool valid() const { return m_live && m_live->load(std::memory_order_acquire); }
    /// Row y (0: top): width() RGBA pixels, 4 floats each; null when !valid() or y is outside.
    const float* row(int y) const;
    /// Pixel (x, y): 4 floats; null when !valid() or outside the picture.
    const float* pixel(int x, int y) const;
    /// A copy as an Image: the same pixels, metadata and camera render() would have returned
    /// (no AOV planes); an empty Image when !valid().
    Image toImage() const;

private:
    friend class Renderer;
    Image m_header;  ///< width, height, metadata and camera; no pixels
    const char* m_data = nullptr;
    std::size_t m_rowPitch = 0;
    std::shared_ptr<const std::atomic<bool>> m_live;
};

/// The headless renderer. Move-only; one per thread (see docs/library.md for thread rules).
class LANTERN_API Renderer {
public:
    /// Creates the Vulkan instance and device. Fails with NoDevice when no device exists (the
    /// message names the driver manifests the loader read and how to install lavapipe), or
    /// when none matches RendererDesc::deviceName or LANTERN_DEVICE (the message lists the
    /// devices found with their indices).
    static Result<Renderer> create(const RendererDesc& desc = {});

    /// Creates a renderer on the host's own Vulkan instance, device and queue (include
    /// lantern/ExternalDevice.h, which lists what the device must have enabled). Lantern never
    /// destroys them. Fails with Unsupported naming a missing feature or extension, or with
    /// Usage for null or mismatched handles. RendererDesc's deviceName, validation and
    /// instanceExtensions do not apply (the host chose them).
    static Result<Renderer> create(const ExternalDevice& device, const RendererDesc& desc = {});

    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    ~Renderer();

    /// Validates `scene` and uploads it. While prepared, the Scene's geometry must not change
    /// (but see updateVertices): meshes (their primitives' vertex data and material indices)
    /// and textures; nor may
    /// materials, lights, cameras or nodes be removed (they are referred to by index).
    /// Everything else is read afresh for every frame, when render() (or a WindowTarget frame)
    /// is called, so a host may edit it between such calls, on the thread that renders:
    /// material and light values, node transforms, cameras, animations (added, removed or
    /// edited) and the roots' lighting models. Edited values must stay within the ranges
    /// Scene::validate() accepts (they are not checked again); frames already submitted keep
    /// the values they were built with.
    Result<PreparedScene> prepare(std::shared_ptr<const Scene> scene);

    /// Uploads again the positions and normals of primitive `primitive` of mesh `mesh` after
    /// the host changed them in place in the prepared Scene (it keeps a non-const pointer to
    /// the Scene it prepared), the count unchanged. Only that primitive's ranges are written
    /// (with its skinning inputs and flat-shading streams); the renderer, its device and the
    /// rest of the upload stay. Waits for frames in flight first; call it on the thread that
    /// renders. InvalidInput naming the primitive when its vertex count changed or a value is
    /// not finite; Usage for a primitive that does not exist or a scene of another renderer.
    Result<void> updateVertices(const PreparedScene& scene, int mesh, int primitive);

    /// Renders a prepared scene at `timeSeconds` and reads the picture back. Options are
    /// checked first (InvalidInput on bad values; OutOfMemory for images too large, refused
    /// before anything is allocated).
    Result<Image> render(const PreparedScene& scene, const RenderOptions& options,
                         double timeSeconds);

    /// The same, into `into`, whose memory is reused (its previous pixels are replaced): a
    /// host that renders frame after frame of one size allocates nothing. It matters for
    /// pictures the C library maps afresh for every allocation (glibc: above 32 MiB, a float
    /// picture larger than 1920x1080), whose pages the kernel must fault in and zero each
    /// frame. On failure `into` is left empty.
    Result<void> render(const PreparedScene& scene, const RenderOptions& options,
                        double timeSeconds, Image& into);

    /// Renders and leaves the picture where the device put it: a FrameView of the colour in the
    /// device's host-mapped memory, with no copy into an Image (docs/library.md, "Reading a
    /// frame in place"). It is the fastest way to get float pixels to the host; the view is
    /// valid until the next frame this renderer submits. Colour only: Usage when options ask
    /// for AOVs (render() returns those). Other failures as render().
    Result<FrameView> renderView(const PreparedScene& scene, const RenderOptions& options,
                                 double timeSeconds);

    /// One band of a picture from renderBands: a view of its rows, and the picture row (0: the
    /// top) where the band starts.
    using BandSink = std::function<Result<void>(const FrameView& band, int top)>;

    /// Renders the picture in horizontal bands of `rows` rows (the last may be shorter; 0: a
    /// height chosen for the scene, see docs/library.md, "Rendering in bands"), top first, and
    /// hands each band to `sink` while the next one renders. The device then holds two bands'
    /// attachments instead of the whole picture's: `lantern render` writes PNGs this way
    /// (PngStream). A band's view is valid during its call only and carries no metadata or
    /// camera. It covers the pixels renderView covers; values may differ from renderView's in
    /// their last bits (the rasteriser rounds a band's window coordinates on their own: on
    /// lavapipe by at most 3.1e-6, tests/gpu/BandsTest.cpp). Colour only: Usage
    /// when options ask for AOVs. A sink's error stops the render and is returned; other
    /// failures as render().
    Result<void> renderBands(const PreparedScene& scene, const RenderOptions& options,
                             double timeSeconds, int rows, const BandSink& sink);

    /// Convenience: validates, uploads and renders `scene` in one call (the upload is not
    /// kept; prepare() once to render many frames).
    Result<Image> render(const Scene& scene, const RenderOptions& options, double timeSeconds);

    /// Renders the frames of `sequence` (frame k at time k / fps, only the shard's frames) and
    /// writes each to the output patterns. Frames are double buffered (frame k+1 renders while
    /// frame k is read back) and encoded on worker threads through a bounded queue, so memory
    /// stays flat. Output is deterministic: the same scene, frame and options give the same
    /// bytes whatever the shard layout. Stops early when shouldStop() says so (report.stopped)
    /// or at the first error (IoError when a file cannot be written); frames already written
    /// stay, and no file is left half-written.
    Result<SequenceReport> renderSequence(const PreparedScene& scene, const RenderOptions& options,
                                          const SequenceOptions& sequence);

    /// The features the scene needs under these options and the pipeline variants chosen.
    Result<FeatureReport> explain(const Scene& scene, const RenderOptions& options,
                                  double timeSeconds = 0.0);

    /// Renders `scene` once (one sample per pixel, AOVs on) and explains pixel (x, y): which
    /// surface the renderer drew there and each term of the lighting equation at it, computed
    /// by the double-precision CPU reference under the same shading rule (for an opaque
    /// surface without texture, `colour` equals `pixel` to float precision). InvalidInput for
    /// a pixel outside the image; a pixel with no surface gives hit = false.
    Result<ProbeReport> probe(const Scene& scene, const RenderOptions& options, double timeSeconds,
                              int x, int y);

    /// Measurements of the last frame (render or sequence).
    const FrameStats& lastFrameStats() const;

    const DeviceInfo& device() const;

    /// Bytes of device memory this renderer's buffers and images hold now: every prepared
    /// scene's geometry, textures, clusters and levels of detail, and the frames' targets and
    /// staging buffers (the driver's own memory, pipelines included, is not counted). On
    /// lavapipe device memory is host memory.
    std::uint64_t deviceMemoryBytes() const;

    /// Validation-layer messages of Warning or Error severity seen so far.
    std::uint64_t validationMessageCount() const;

private:
    friend class WindowTarget;
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    /// The Cryptomatte layers options.aovs asks for, into `into` (a second, supersampled render).
    Result<void> addCryptomatte(const PreparedScene& scene, const RenderOptions& options,
                                double timeSeconds, Image& into);
    std::unique_ptr<Impl> m_impl;
};

} // namespace lantern
