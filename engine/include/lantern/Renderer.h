// Renderer: turns a Scene at an instant into an Image, headless, on any Vulkan device
// (lavapipe included). The only public entry to the GPU; no Vulkan type appears here.
#pragma once

#include <lantern/Camera.h>
#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Log.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>
#include <lantern/Sequence.h>

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lantern {

namespace render {
class GpuScene;
struct RendererAccess;
}
class WindowTarget;
struct ExternalDevice;  // lantern/ExternalDevice.h (includes vulkan.h)

/// Which camera a view uses, and optional overrides of its parts.
struct CameraSpec {
    enum class Source {
        Automatic,    ///< the scene's first camera, else automatic framing of the bounds
        SceneCamera,  ///< Scene::cameras[sceneCamera] on the first node that carries it
        Framing,      ///< automatic framing of the scene's bounds
        GlDefault,    ///< GL's default: origin, looking down -Z, the 2x2x2 orthographic cube
    };
    Source source = Source::Automatic;
    int sceneCamera = -1;
    std::optional<LookAt> lookAt;          ///< replaces the view (gluLookAt), world space
    std::optional<Projection> projection;  ///< replaces the projection

    /// Which fixed direction automatic framing looks from (world space, towards the scene):
    /// the default is the GL camera's -Z. The quad layout uses -Y (top) and -X (side) too.
    glm::dvec3 framingDirection{0.0, 0.0, -1.0};
    bool framingOrthographic = false;  ///< frame with an orthographic projection
};

/// A pixel rectangle in GL's convention (origin at the bottom-left of the image, as
/// glViewport) drawn with its own camera.
struct View {
    int x = 0, y = 0, width = 0, height = 0;
    CameraSpec camera;
};

/// Which pipeline features are compiled in: only those the scene needs (the default), or all
/// of them (for measuring what specialisation saves). Floor draws the same geometry with a
/// trivial shader (constant white, no lighting): the cost of rasterising alone, the floor that
/// `lantern bench speed` divides frame times by.
enum class FeatureMode { Specialised, AllFeatures, Floor };

/// Everything that affects a render besides the scene and the time.
struct RenderOptions {
    int width = 1280;
    int height = 720;
    int root = -1;  ///< glTF scene index; -1: the scene's default
    std::optional<ShadingMode> shading;     ///< default: the scene's, else Phong
    std::optional<SpecularModel> specular;  ///< default: the scene's, else Blinn
    std::optional<bool> localViewer;        ///< default: the scene's
    std::optional<bool> twoSided;           ///< default: the scene's
    bool clamp = false;     ///< clamp lit colours to [0,1] (GL's behaviour)
    bool glCompat = false;  ///< reproduce GL fixed function: provoking-vertex flat, per-vertex
                            ///< clamp, shininess and spot exponent limited to [0,128]
    int msaa = 1;           ///< samples per pixel: 1, 2, 4 or 8 (as the device supports)
    DepthMode depth = DepthMode::ReversedZ;
    CameraSpec camera;       ///< the camera when `views` is empty
    std::vector<View> views; ///< several views in one image; empty: one full-image view
    AovSet aovs;
    FeatureMode features = FeatureMode::Specialised;
    glm::vec4 background{0.0f, 0.0f, 0.0f, 0.0f};  ///< linear, premultiplied
    /// Lights that follow the camera (a headlight rig): when set, every scene light is placed
    /// in eye space through this viewFromWorld instead of each view's own, so the lights keep
    /// their place relative to the camera however it moves. The viewer sets it to the camera
    /// of the moment the mode is switched on. GL's default light 0 is always eye-space.
    std::optional<glm::dmat4> lightsViewFromWorld;
    /// Display overlays (for viewers; not combinable with AOVs): every drawn triangle's edges,
    /// and each vertex normal as a line from its vertex.
    bool wireframe = false;
    bool normals = false;
    /// Length of the normal lines in world units; 0: 3% of the radius of the drawn bounds.
    double normalLength = 0.0;
};

/// How the renderer is created.
struct RendererDesc {
    /// Use the first device whose name contains this text (case-insensitive); empty: the
    /// first device that can render (discrete GPUs first, then integrated, virtual, CPU).
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
    LogSink log;
};

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
    friend struct render::RendererAccess;
    std::shared_ptr<render::GpuScene> m_gpu;
};

/// Measurements of the last frame rendered.
struct FrameStats {
    double gpuMs = -1.0;    ///< render-pass time from GPU timestamps (-1: not available)
    double cpuMs = 0.0;     ///< planning, recording and submission on the CPU
    double waitMs = 0.0;    ///< waiting for the GPU and reading the image back
    std::size_t draws = 0;
    std::size_t pipelinesCreated = 0;  ///< variants compiled for this frame (first use)
    std::uint64_t nonFinite = 0;       ///< NaN/Inf values replaced by 0 (always 0 unless a bug)
};

/// What the device is.
struct DeviceInfo {
    std::string name;         ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string driver;       ///< e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
    std::string type;         ///< "cpu", "discrete-gpu", "integrated-gpu", "virtual-gpu", "other"
    std::uint32_t apiVersion = 0;
    bool validationEnabled = false;
    std::vector<int> msaaSampleCounts;  ///< supported for float colour + depth
};

/// What a render needs (the features the scene uses) and the pipelines chosen for it.
struct FeatureReport {
    std::vector<std::string> features;  ///< e.g. "light:directional", "specular:blinn"
    std::vector<std::string> variants;  ///< one line per pipeline variant
};

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

/// One light's share of a probed colour (see ProbeReport). Linear RGB.
struct ProbeLight {
    std::string name;  ///< the light's name, or "light N" (N: its index in Scene::lights)
    LightType type = LightType::Directional;  ///< as drawn: a GL spot with cutoff 180 is Point
    double attenuation = 1.0;  ///< att_i
    double spot = 1.0;         ///< spot_i
    double nDotL = 0.0;        ///< n.l_i (the highlight needs it > 0)
    double specularTerm = 0.0; ///< spec_i: the Blinn or Phong lobe (0 on the dark side)
    glm::dvec3 ambient{0.0};   ///< att spot a_m a_i
    glm::dvec3 diffuse{0.0};   ///< att spot max(n.l, 0) d_m d_i
    glm::dvec3 specular{0.0};  ///< att spot f_i spec_i s_m s_i
};

/// One evaluation of the lighting equation that a probed pixel's colour is made of: at the
/// surface point (phong shading), at the triangle's centroid with its face normal (flat), at
/// a vertex (gouraud: three, weighted by the pixel's perspective-correct barycentrics; GL
/// flat: the provoking vertex).
struct ProbeEvaluation {
    std::string where;      ///< "surface point", "triangle centroid", "vertex 17", ...
    double weight = 1.0;    ///< its share of the pixel's colour
    glm::dvec3 position{0.0};  ///< eye space, where the equation was evaluated
    glm::dvec3 normal{0.0};    ///< eye space, unit (zero: no direction) as lit (back side negated)
    glm::dvec3 ambientM{0.0}, diffuseM{0.0};  ///< a_m and d_m after COLOR_0
    glm::dvec3 emission{0.0};       ///< e_m
    glm::dvec3 globalAmbient{0.0};  ///< a_m * A_global
    std::vector<ProbeLight> lights;  ///< in the renderer's order
    glm::dvec3 colour{0.0};  ///< the equation's result here (per-vertex clamp with --gl-compat)
    double alpha = 1.0;
};

/// What Renderer::probe() reports for one pixel: the lighting equation made visible,
/// evaluated in double precision by the CPU reference at the surface point the renderer drew
/// at that pixel's centre, under the same shading rule as the render.
struct ProbeReport {
    int x = 0, y = 0;  ///< the pixel: x from the left, y from the top row (as image viewers)
    bool hit = false;  ///< false: no surface covers the pixel (everything below is empty)
    int view = 0;      ///< RenderOptions::views index (0 without views)
    int node = -1, mesh = -1, primitive = -1;
    std::uint32_t triangle = 0;      ///< index of the triangle in the primitive
    std::uint32_t vertices[3] = {};  ///< its vertex indices
    glm::dvec3 barycentric{0.0};     ///< perspective-correct weights of the vertices at the centre
    std::string nodeName;
    glm::dvec3 position{0.0};  ///< eye space: the pixel centre's ray meets the triangle here
    glm::dvec3 normal{0.0};    ///< eye space, unit: the shading normal there (interpolated and
                               ///< renormalised; the face normal with flat shading), front side
    bool backFacing = false;   ///< the renderer saw the back of the triangle
    bool backMaterial = false; ///< two-sided lighting: the back material and -normal were used
    int material = -1;         ///< Scene::materials index; -1: the default material
    std::string materialName;
    MaterialSide materialSide; ///< the side used, after GL-compat limits
    bool unlit = false;
    bool textured = false;  ///< a base-colour texture modulates the pixel; the probe does not
                            ///< sample it (colour assumes a white texel)
    ShadingMode shading = ShadingMode::Phong;
    SpecularModel specular = SpecularModel::Blinn;
    bool specularPresent = false;  ///< the pipeline variant has a specular term
    bool localViewer = false, twoSided = false, glCompat = false;
    bool clamped = false;          ///< --clamp or --gl-compat clamp to [0, 1]
    std::vector<ProbeEvaluation> evaluations;  ///< their weighted sum is `colour`
    double materialAlpha = 1.0;  ///< the material's alpha there (what alpha-mask compares)
    glm::dvec4 colour{0.0};  ///< the reference's linear RGB and alpha for the surface
    glm::dvec4 pixel{0.0};   ///< what the renderer wrote at the pixel (after blending)
};

/// The headless renderer. Move-only; one per thread (see docs/library.md for thread rules).
class LANTERN_API Renderer {
public:
    /// Creates the Vulkan instance and device. Fails with NoDevice when no device exists (or
    /// none matches RendererDesc::deviceName; the message lists the devices present).
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

    /// Validates `scene` and uploads it. While prepared, the Scene's geometry must not change:
    /// meshes (their primitives' vertex data and material indices) and textures; nor may
    /// materials, lights, cameras or nodes be removed (they are referred to by index).
    /// Everything else is read afresh for every frame, when render() (or a WindowTarget frame)
    /// is called, so a host may edit it between such calls, on the thread that renders:
    /// material and light values, node transforms, cameras, animations (added, removed or
    /// edited) and the roots' lighting models. Edited values must stay within the ranges
    /// Scene::validate() accepts (they are not checked again); frames already submitted keep
    /// the values they were built with.
    Result<PreparedScene> prepare(std::shared_ptr<const Scene> scene);

    /// Renders a prepared scene at `timeSeconds` and reads the picture back. Options are
    /// checked first (InvalidInput on bad values; OutOfMemory for images too large, refused
    /// before anything is allocated).
    Result<Image> render(const PreparedScene& scene, const RenderOptions& options,
                         double timeSeconds);

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

    /// Validation-layer messages of Warning or Error severity seen so far.
    std::uint64_t validationMessageCount() const;

private:
    friend class WindowTarget;
    friend struct render::RendererAccess;  ///< the engine's own tests and --probe
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

} // namespace lantern
