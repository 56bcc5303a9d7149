// Options.h: everything that shapes a render besides the scene and the time: image size,
// shading overrides, cameras and views, multisampling, depth mode, AOVs, background, overlays.
// Plain values, checked by the renderer (Renderer::render refuses bad ones with InvalidInput).
#pragma once

#include <lantern/Camera.h>
#include <lantern/CameraConventions.h>
#include <lantern/Export.h>
#include <lantern/Image.h>
#include <lantern/Scene.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <optional>
#include <string_view>
#include <vector>

namespace lantern {

/// Where automatic framing puts the camera, as the views modelling programs name them. The
/// default is a three-quarter view from the front right, above (Blender's and F3D's habit):
/// 45 degrees round from the front (+Z, glTF's front) towards +X, 30 degrees up, so a scene that
/// lies in any axis plane is seen at 30 degrees or more, never edge-on.
enum class ViewDirection {
    ThreeQuarter,  ///< from front right, above (the default)
    Front,         ///< from +Z, looking down -Z
    Back,          ///< from -Z
    Left,          ///< from -X
    Right,         ///< from +X
    Top,           ///< from +Y, looking down (+X to the right, -Z up on screen)
    Bottom,        ///< from -Y
    Iso,           ///< from (+1, +1, +1): the isometric corner
};
inline constexpr ViewDirection kViewDirections[] = {
    ViewDirection::ThreeQuarter, ViewDirection::Front, ViewDirection::Back,   ViewDirection::Left,
    ViewDirection::Right,        ViewDirection::Top,   ViewDirection::Bottom, ViewDirection::Iso};
/// "three-quarter", "front", "back", "left", "right", "top", "bottom", "iso".
LANTERN_API const char* toString(ViewDirection view) noexcept;
LANTERN_API std::optional<ViewDirection> parseViewDirection(std::string_view text) noexcept;
/// The unit direction the camera looks along (world space, towards the scene) for `view`.
LANTERN_API glm::dvec3 framingDirection(ViewDirection view) noexcept;

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
    /// Replaces the view with this rigid viewFromWorld, exactly (not with lookAt): see
    /// viewFromPose() for OpenCV's world_to_camera and glTF's camera_to_world.
    std::optional<glm::dmat4> viewFromWorld;
    /// Replaces the projection with OpenCV intrinsics (lantern/CameraConventions.h); the view
    /// must then be exactly intrinsics.width x intrinsics.height pixels. An automatic near
    /// plane is fitted to the scene's bounds (docs/cameras.md).
    std::optional<Intrinsics> intrinsics;

    /// The direction automatic framing looks along (world space, towards the scene; need not
    /// be unit length): the three-quarter view by default (framingDirection(ViewDirection)).
    /// The framing fits the bounding sphere, near and far planes around it.
    glm::dvec3 framingDirection{-0.6123724356957945, -0.5, -0.6123724356957945};
    bool framingOrthographic = false;  ///< frame with an orthographic projection

    /// Automatic framing from a named view, whatever cameras the scene has.
    static CameraSpec framed(ViewDirection view, bool orthographic = false) noexcept {
        CameraSpec s;
        s.source = Source::Framing;
        s.framingDirection = lantern::framingDirection(view);
        s.framingOrthographic = orthographic;
        return s;
    }
    /// A computer-vision camera: intrinsics and a pose in OpenCV's or glTF's axes.
    static CameraSpec fromPose(const Intrinsics& intrinsics, const glm::dmat4& pose,
                               PoseConvention convention = PoseConvention::OpenCV) {
        CameraSpec s;
        s.source = Source::GlDefault;  // every part is replaced
        s.viewFromWorld = viewFromPose(pose, convention);
        s.intrinsics = intrinsics;
        return s;
    }
};

/// A pixel rectangle in GL's convention (origin at the bottom-left of the image, as
/// glViewport) drawn with its own camera.
struct View {
    int x = 0, y = 0, width = 0, height = 0;
    CameraSpec camera;
};

/// How a shadow map is filtered: the device's 2 x 2 comparison (Hardware), percentage closer
/// filtering over kernel x kernel comparisons a texel apart (Pcf), or percentage closer soft
/// shadows (Pcss): a blocker search finds how far the caster is from the receiver, and the
/// kernel x kernel comparisons spread over the penumbra a light of ShadowOptions::lightRadius
/// (sunRadius for directional lights) casts there.
enum class ShadowFilter { Hardware, Pcf, Pcss };

/// Shadow maps (docs/shadows.md): a light casts shadows when the scene says so
/// (LANTERN_lights_shadow, Light::castShadows) or when `all` is set; a frame without such a
/// light renders as it did without shadows, with the same pipeline variants. Under GL
/// compatibility only `all` casts them (GL has no shadows).
/// The most cascades a directional light's shadow may have (ShadowOptions::cascades).
inline constexpr int kMaxShadowCascades = 8;

struct ShadowOptions {
    bool all = false;           ///< every light casts shadows (--shadows)
    int resolution = 2048;      ///< texels per side of each map (a cube face for point lights)
    ShadowFilter filter = ShadowFilter::Pcf;
    int kernel = 3;             ///< Pcf: comparisons per side, odd, 1 to 9
    double slopeBias = 2.0;     ///< depth bias, in units of the depth's slope (texels)
    double normalOffset = 1.5;  ///< the lookup point moves this many texels along the normal
    /// Directional lights: maps fitted to consecutive depth ranges of the first view (cascaded
    /// shadow maps), 1 to kMaxShadowCascades; 1: one map around everything drawn (also when
    /// several views share the maps).
    int cascades = 2;
    /// Pcss: the radius of point and spot lights, in world units (the exact reference then
    /// treats them as discs of that radius facing the point), and the angular radius of
    /// directional lights, in degrees (the sun's is 0.27). The hard filters and the
    /// reference under them treat every light as a point.
    double lightRadius = 0.05;
    double sunRadius = 0.5;
};

/// How blended surfaces (glTF alphaMode BLEND) are composited (docs/transparency.md).
enum class TransparencyMethod {
    /// Each draw blended over what is behind it, far to near by the eye depth of its bounds'
    /// centre (what GL programs do): wrong where surfaces cross or a mesh overlaps itself.
    Sorted,
    /// Every blended fragment stored in a per-pixel list, then sorted by depth and composited
    /// per pixel: exact where surfaces cross (up to LANTERN_OIT_MAX_LAYERS layers a pixel).
    Exact,
    /// Weighted blended order-independent transparency (McGuire and Bavoil 2013): one pass,
    /// no sorting, no per-pixel memory; an approximation whose error depends on the depths.
    Weighted,
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
    /// Pixels across a point (glTF POINTS, GL_POINTS) and a line (LINES, LINE_STRIP,
    /// LINE_LOOP; GL_LINES), each in [1, 255]: 1 is GL's default. Above 1 the device needs
    /// the largePoints / wideLines feature and its range (lavapipe has both).
    double pointSize = 1.0;
    double lineWidth = 1.0;
    DepthMode depth = DepthMode::ReversedZ;
    CameraSpec camera;       ///< the camera when `views` is empty
    std::vector<View> views; ///< several views in one image; empty: one full-image view
    AovSet aovs;
    /// Exact colours for label images (docs/aovs.md): every material unlit, its colour the
    /// base colour as the scene wrote it (no lighting, texture, map, blending or clamp),
    /// shaded per fragment. Needs msaa 1 (no anti-aliasing); the colour written is the float
    /// nearest the scene's number, bit for bit.
    bool unlitExact = false;
    FeatureMode features = FeatureMode::Specialised;
    /// Nodes that place one primitive with the same material and winding (glTF nodes that
    /// share a mesh, EXT_mesh_gpu_instancing's instances) are drawn by one instanced draw;
    /// false: one draw per node. The picture is the same either way (docs/performance.md,
    /// "Instanced draws"); the switch is there to measure what instancing buys.
    bool instancing = true;
    /// What cannot cover a pixel of a pass is not drawn: each shadow map's pass skips the
    /// casters outside its map, and the clusters of large meshes (runs of their triangles, in
    /// the file's order) outside a view, or facing away where the draw culls back faces, are
    /// dropped by a compute pass before the draws (docs/performance.md, "Clusters"). The
    /// picture is the same either way; false draws everything, to measure what culling buys
    /// and check that it changes no pixel.
    bool culling = true;
    /// Level of detail: each clustered mesh is drawn, per instance and per view, at the
    /// coarsest of its simplified levels whose error (object-space distance, projected at the
    /// mesh's nearest point) stays under this many pixels. 0 (the default): the full mesh,
    /// exact. The levels are built on the first frame that asks for them (needs culling on).
    double lodError = 0.0;
    ShadowOptions shadows;
    /// How blended surfaces are composited; default: Exact (Sorted under glCompat, as GL
    /// programs draw), docs/transparency.md has the measurements behind it. A frame without
    /// blended draws pays nothing for either.
    std::optional<TransparencyMethod> transparency;
    /// Linear, premultiplied. Opaque black by default, as `lantern render` and `lantern view`
    /// (one rule, docs/cli.md); {0, 0, 0, 0} for a transparent background, whose alpha is then
    /// each pixel's coverage (for compositing).
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
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

/// The AOV names of `lantern render --aov` and Python's aov= (docs/aovs.md), comma-separated.
LANTERN_API const char* aovNames() noexcept;
/// Switches on the AOV called `name` (one of aovNames()); false for an unknown name.
LANTERN_API bool enableAov(AovSet& aovs, std::string_view name) noexcept;

} // namespace lantern
