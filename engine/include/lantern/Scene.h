// Scene: Lantern's scene model, plain value data in double precision (transforms, colours)
// and float (vertex data, which is object-local). A glTF file loads into it; a host can build
// one in code. Nothing here knows about glTF or Vulkan.
//
// Spaces and units: right-handed, +Y up, a camera looks down its local -Z. Lengths are in the
// file's units (glTF: metres). Angles are radians unless a name ends in Deg. Colours are linear
// RGB(A). Scene section numbers refer to ../shared/spec/scene-format.md.
#pragma once

#include <lantern/Camera.h>
#include <lantern/Export.h>
#include <lantern/Result.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

// --- Lighting model (spec section 1 and LANTERN_lighting) ---------------------------------

/// Where the lighting equation is evaluated (spec section 1).
enum class ShadingMode {
    Flat,     ///< once per triangle, at its centroid, with the face normal
    Gouraud,  ///< per vertex with the vertex normal; colours interpolated
    Phong,    ///< per fragment with the interpolated, renormalised normal
};
/// The specular term: Blinn's halfway vector (GL's) or Phong's reflection vector.
enum class SpecularModel { Blinn, Phong };

LANTERN_API const char* toString(ShadingMode mode) noexcept;     ///< "flat", "gouraud", "phong"
LANTERN_API const char* toString(SpecularModel model) noexcept;  ///< "blinn", "phong"
LANTERN_API std::optional<ShadingMode> parseShadingMode(std::string_view text) noexcept;
LANTERN_API std::optional<SpecularModel> parseSpecularModel(std::string_view text) noexcept;

/// LANTERN_lighting: scene-wide lighting-model switches (GL's glLightModel).
struct LightingModel {
    glm::dvec3 globalAmbient{0.2, 0.2, 0.2};  ///< GL_LIGHT_MODEL_AMBIENT, linear RGB
    bool localViewer = false;  ///< true: v points to the eye; false: v = (0,0,1) (GL's default)
    /// Back faces lit with the negated normal and the back material (GL_LIGHT_MODEL_TWO_SIDE),
    /// for every draw when stated; absent: glTF's rule, two-sided for double-sided materials.
    std::optional<bool> twoSided;
    ShadingMode shading = ShadingMode::Phong;
    SpecularModel specular = SpecularModel::Blinn;
};

// --- Materials (spec section 2) ---------------------------------------------------------------

/// One side of a Phong material (GL's glMaterial). Defaults are OpenGL's.
struct MaterialSide {
    glm::dvec3 ambient{0.2, 0.2, 0.2};
    glm::dvec4 diffuse{0.8, 0.8, 0.8, 1.0};  ///< alpha is the material's opacity
    glm::dvec3 specular{0.0, 0.0, 0.0};
    glm::dvec3 emission{0.0, 0.0, 0.0};
    double shininess = 0.0;  ///< any finite value >= 0 (not limited to GL's 128)
};

enum class AlphaMode { Opaque, Mask, Blend };

/// A texture a material reads besides its base colour, with its KHR_texture_transform. It
/// reads the primitive's texture coordinates (Primitive::texcoords), or its second set
/// (Primitive::texcoords1) when `secondSet`.
struct TextureMap {
    int texture = -1;             ///< Scene::textures index; -1: none
    glm::dmat3 uvTransform{1.0};  ///< as Material::baseColorUvTransform
    bool secondSet = false;       ///< reads Primitive::texcoords1 (a bake's TEXCOORD_1)
};

/// The glTF metallic-roughness factors a material's classic colours were mapped from (see
/// docs/scene-format-support.md, Materials), kept so that a metallic-roughness texture can be
/// mapped per texel.
struct PbrFactors {
    glm::dvec4 baseColor{1.0};
    double metallic = 1.0;
    double roughness = 1.0;
    /// The F0 of the dielectric share (0.04; KHR_materials_ior and _specular change it; the
    /// per-texel mapping takes the mean of a coloured one).
    double dielectricF0 = 0.04;
};

struct Material {
    std::string name;
    MaterialSide front;
    std::optional<MaterialSide> back;  ///< without it both sides use `front`
    bool unlit = false;  ///< KHR_materials_unlit: colour = front.diffuse (x COLOR_0 x texture)
    AlphaMode alphaMode = AlphaMode::Opaque;
    double alphaCutoff = 0.5;  ///< for AlphaMode::Mask
    bool doubleSided = false;  ///< false: back faces are culled (glTF)
    int baseColorTexture = -1; ///< index into Scene::textures; multiplies the diffuse colour
    /// KHR_texture_transform of the base-colour texture: the texture is read at
    /// (M (u, v, 1)).xy, M = translation(offset) * rotation * scale (identity without it).
    glm::dmat3 baseColorUvTransform{1.0};
    /// True when the ambient colour is the diffuse colour by definition (the PBR fallback maps
    /// ambient = diffuse): then the base-colour texture and COLOR_0 scale the ambient too.
    bool ambientFollowsDiffuse = false;
    /// glTF's other textures (phong shading; docs/gl-differences.md says what gouraud and flat
    /// do). Metallic-roughness (B metallic, G roughness) scales `pbr`'s factors per texel and
    /// needs `pbr`; the normal map (tangent space, +Y up) is scaled in X and Y by normalScale;
    /// occlusion (R) scales the ambient term by 1 + occlusionStrength (R - 1); the emissive map
    /// (sRGB) multiplies the emission.
    std::optional<PbrFactors> pbr;
    TextureMap metallicRoughnessMap;
    TextureMap normalMap;
    double normalScale = 1.0;
    TextureMap occlusionMap;
    double occlusionStrength = 1.0;  ///< [0, 1]
    TextureMap emissiveMap;

    const MaterialSide& side(bool backFace) const { return backFace && back ? *back : front; }
};

// --- Lights (spec section 3) ----------------------------------------------------------------

enum class LightType { Directional, Point, Spot };

/// How a light's strength falls off with distance and across a spot cone.
enum class LightFalloff {
    Gl,    ///< LANTERN_lights_phong / glLight: 1/(kc + kl d + kq d^2), GL spot cutoff + exponent
    Gltf,  ///< KHR_lights_punctual alone: 1/max(d^2, 1e-4) times the range window, smooth cone
};

/// A light. Its position and direction come from its node: it sits at the node's origin and
/// shines down the node's local -Z (for spots and directional lights).
struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::dvec3 ambient{0.0, 0.0, 0.0};
    glm::dvec3 diffuse{1.0, 1.0, 1.0};
    glm::dvec3 specular{1.0, 1.0, 1.0};
    LightFalloff falloff = LightFalloff::Gl;
    // Gl falloff
    glm::dvec3 attenuation{1.0, 0.0, 0.0};  ///< kc, kl, kq: >= 0, not all zero
    double spotExponent = 0.0;              ///< >= 0
    double spotCutoffDeg = 180.0;           ///< [0, 90], or exactly 180 (no cone)
    // Gltf falloff
    double range = kInfinity;        ///< > 0; +inf: unlimited
    double innerConeAngle = 0.0;     ///< radians, [0, outer)
    double outerConeAngle = 0.7853981633974483;  ///< radians, (inner, pi/2]
    /// The light casts shadows (LANTERN_lights_shadow; RenderOptions::shadows.all makes every
    /// light cast them).
    bool castShadows = false;
};

// --- Meshes ---------------------------------------------------------------------------------

/// A morph target: displacements added to the base mesh, weighted (glTF `targets`).
struct MorphTarget {
    std::vector<glm::vec3> positions;  ///< empty, or one displacement per vertex
    std::vector<glm::vec3> normals;    ///< empty, or one displacement per vertex
};

/// What a primitive's vertex sequence draws (OpenGL's GL_TRIANGLES, GL_LINES, GL_POINTS).
/// Loaders convert strips, fans and loops to these lists.
enum class Topology : std::uint8_t { Triangles, Lines, Points };

/// A list of triangles, lines or points. Attributes are per vertex and object-local. Loaders
/// convert strips, fans and loops to lists, and fill in missing normals of triangles
/// (angle-weighted vertex normals).
struct Primitive {
    Topology topology = Topology::Triangles;
    std::vector<glm::vec3> positions;
    /// Same count as positions (may contain zero vectors). Lines and points may have none:
    /// they are then drawn unlit (base colour times vertex colour), as glTF recommends.
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> colors;     ///< empty, or COLOR_0 per vertex (linear RGBA)
    /// Empty, or texture coordinates per vertex: the set the base colour and most maps read
    /// (glTF: the material's set, TEXCOORD_0 in most files).
    std::vector<glm::vec2> texcoords;
    /// Empty, or the second set, which the maps with TextureMap::secondSet read (glTF: the
    /// other TEXCOORD_n the material's maps name, such as a baked occlusion's TEXCOORD_1).
    std::vector<glm::vec2> texcoords1;
    /// Empty, or a tangent per vertex (glTF TANGENT: xyz along +u, w = +-1 the sign of the
    /// bitangent cross(normal, tangent) w). The normal map's frame in phong; without it (and for
    /// skinned or morphed primitives) the frame comes from screen-space derivatives.
    std::vector<glm::vec4> tangents;
    /// Skinning (JOINTS_0/1, WEIGHTS_0/1): up to 8 influences per vertex, indices into the
    /// joints of the skin of the node that draws the mesh. Empty, or one per vertex; set 1
    /// only with set 0. Weights are used as given (a vertex whose weights are all 0 is not
    /// moved by the skin).
    std::vector<glm::uvec4> joints0, joints1;
    std::vector<glm::vec4> weights0, weights1;
    /// Morph targets; every primitive of a mesh has the same number (glTF).
    std::vector<MorphTarget> targets;
    /// The list of triangles (3 per element), lines (2) or points (1); empty: the vertices
    /// taken in order.
    std::vector<std::uint32_t> indices;
    int material = -1;  ///< index into Scene::materials; -1: the default material
    /// KHR_materials_variants: the material this primitive takes in each variant that lists it
    /// (variant index into Scene::variants, material), and the material it has in none of them
    /// (the file's own). selectMaterialVariant() sets `material` from these.
    struct VariantMaterial {
        int variant = -1;
        int material = -1;
    };
    std::vector<VariantMaterial> variantMaterials;
    int materialWithoutVariant = -1;

    /// Vertices per element: 3, 2 or 1.
    std::size_t verticesPerElement() const {
        return topology == Topology::Triangles ? 3 : topology == Topology::Lines ? 2 : 1;
    }
    /// Triangles, lines or points drawn.
    std::size_t elementCount() const {
        return (indices.empty() ? positions.size() : indices.size()) / verticesPerElement();
    }
    /// Triangles drawn (0 for lines and points).
    std::size_t triangleCount() const {
        return topology == Topology::Triangles ? elementCount() : 0;
    }
    /// Drawn unlit: lines or points without normals.
    bool unlitForWantOfNormals() const {
        return topology != Topology::Triangles && normals.empty();
    }
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    std::vector<double> weights;  ///< default morph-target weights (empty: all 0)

    /// Morph targets per primitive (every primitive of a mesh has the same number).
    std::size_t morphTargetCount() const { return primitives.empty() ? 0 : primitives[0].targets.size(); }
};

/// A skin (glTF `skins`): the joints that deform the vertices of the meshes drawn with it.
/// The vertex of a skinned primitive lands at sum_i w_i * worldFromNode[joints[j_i]] *
/// inverseBind[j_i] * p: in world space, so the transform of the node that draws the mesh is
/// not applied (glTF: it only places the skeleton through the joints).
struct Skin {
    std::string name;
    std::vector<int> joints;              ///< node indices
    std::vector<glm::dmat4> inverseBind;  ///< one per joint (identity when the file has none)
    int skeleton = -1;                    ///< the skeleton's root node (a hint only), or -1
};

/// How texture coordinates outside [0, 1] are read (glTF samplers' wrapS/wrapT).
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

/// An RGBA8 texture, top row first: colour in sRGB encoding (base colour, emissive: glTF's
/// convention) or linear data (metallic-roughness, normal and occlusion maps).
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba8;
    bool srgb = true;      ///< false: the bytes are linear (data, not colour)
    bool nearest = false;  ///< nearest filtering instead of linear
    TextureWrap wrapS = TextureWrap::Repeat;  ///< along u
    TextureWrap wrapT = TextureWrap::Repeat;  ///< along v
};

// --- Nodes and animation --------------------------------------------------------------------

struct LANTERN_API Node {
    std::string name;
    glm::dvec3 translation{0.0, 0.0, 0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  ///< unit quaternion (w, x, y, z)
    glm::dvec3 scale{1.0, 1.0, 1.0};
    std::optional<glm::dmat4> matrix;  ///< when set, replaces TRS (and cannot be animated)
    std::vector<int> children;
    int mesh = -1;
    int camera = -1;
    int light = -1;
    int skin = -1;                ///< index into Scene::skins; -1: none
    std::vector<double> weights;  ///< morph weights overriding the mesh's (empty: the mesh's)
    /// The semantic id of the node and the nodes below it that set none (glTF node extras
    /// "semantic_id", 0 .. 2^32 - 2; docs/aovs.md): the id.semantic AOV. Unset: the parent's,
    /// 0 at a root.
    std::optional<std::uint32_t> semantic;

    /// parentFromNode: `matrix`, or T * R * S.
    glm::dmat4 localTransform() const;
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimationPath { Translation, Rotation, Scale, Weights };

/// Keyframes. `values` holds one entry per key (xyz, or a quaternion as x,y,z,w), or for
/// CubicSpline three per key: in-tangent, value, out-tangent. A Weights sampler keeps its
/// keys in `weights` instead: `weightCount` numbers per key (three such groups per key for
/// CubicSpline: in-tangents, values, out-tangents).
struct AnimationSampler {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;  ///< seconds, strictly increasing, >= 0
    std::vector<glm::dvec4> values;
    std::vector<double> weights;   ///< AnimationPath::Weights only
    std::size_t weightCount = 0;   ///< morph targets per key (Weights only)
};

struct AnimationChannel {
    int node = -1;
    AnimationPath path = AnimationPath::Translation;
    int sampler = -1;
};

struct LANTERN_API Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;

    double startTime() const;  ///< the earliest key time (0 if none)
    double endTime() const;    ///< the latest key time (0 if none)
};

/// Samples one sampler at `time` (seconds): times before the first key and after the last
/// clamp; rotations use shortest-arc slerp (Linear) and are normalised (CubicSpline).
LANTERN_API glm::dvec4 sampleAnimation(const AnimationSampler& sampler, AnimationPath path,
                                       double time);
/// Samples a Weights sampler at `time`: weightCount numbers, interpolated component-wise
/// (Step, Linear or Hermite), clamped outside the key range.
LANTERN_API std::vector<double> sampleWeights(const AnimationSampler& sampler, double time);

/// A glTF scene: the root nodes to draw and the scene's lighting model (LANTERN_lighting).
struct SceneRoot {
    std::string name;
    std::vector<int> nodes;
    std::optional<LightingModel> lighting;  ///< absent: GL's defaults
};

// --- Fidelity: how the features a file uses are drawn ------------------------------------------

/// How Lantern draws a feature of a file (docs/scene-format-support.md, "At a glance").
enum class Fidelity {
    Supported,     ///< as the format says
    Approximated,  ///< drawn, by a documented rule (`rule` names it)
    Skipped,       ///< left out, with a warning (`rule` says why)
};
LANTERN_API const char* toString(Fidelity fidelity) noexcept;  ///< "supported", ...

/// One feature a file uses, where, and how it is drawn (`lantern info --json`, `render --report`).
struct FeatureUse {
    std::string key;  ///< the row's key in docs/scene-format-support.md ("skins", "KHR_materials_ior")
    Fidelity fidelity = Fidelity::Supported;
    std::string rule;  ///< Approximated: the rule's name; Skipped: why
    std::vector<std::string> objects;  ///< the file's objects that use it (at most 64 listed)
    std::size_t count = 0;             ///< how many objects use it (may exceed objects.size())
};

/// Every key a fidelity report may hold, with the status and rule it is reported with when no
/// render option changes it (the rows of docs/scene-format-support.md's table).
LANTERN_API const std::vector<FeatureUse>& fidelityKeys();

// --- The scene ------------------------------------------------------------------------------

/// Everything a file (or a host) describes. Indices refer into the vectors of the same Scene.
struct LANTERN_API Scene {
    std::string sourcePath;  ///< the file it came from ("builtin:NAME" for built-in scenes)
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    std::vector<Node> nodes;
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    std::vector<SceneRoot> roots;  ///< glTF scenes; may be empty (nothing is drawn)
    /// KHR_materials_variants: the variants' names, and the one the primitives' materials are
    /// set for (-1: none, the file's own materials).
    std::vector<std::string> variants;
    int activeVariant = -1;
    /// The features the file uses and how they are drawn, in fidelityKeys() order (loaders fill
    /// it; a scene built in code has none).
    std::vector<FeatureUse> features;
    int defaultRoot = 0;           ///< the root drawn unless another is chosen (0 when none)

    /// Checks every index, count and number (spec section 6); the error names the object.
    Result<void> validate() const;
};

/// Axis-aligned bounds in world space.
struct LANTERN_API Bounds {
    glm::dvec3 min{kInfinity};
    glm::dvec3 max{-kInfinity};
    bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
    glm::dvec3 center() const { return (min + max) * 0.5; }
    double radius() const;  ///< half the diagonal (0 when empty)
    void extend(const glm::dvec3& p);
};

/// The state of a scene at one instant: world transforms of the root's nodes in double
/// precision, with animations applied. A pure function of (scene, root, time).
struct Pose {
    int root = 0;
    double time = 0.0;
    std::vector<glm::dmat4> worldFromNode;  ///< one per Scene::nodes entry
    std::vector<bool> visible;              ///< true for nodes reachable from the root
    /// Per node: the morph weights its mesh is drawn with (animated, else the node's, else the
    /// mesh's, else zeros); empty for a node whose mesh has no morph targets.
    std::vector<std::vector<double>> morphWeights;
    /// Per skin: worldFromNode[joint] * inverseBind, one per joint (world from bind space).
    std::vector<std::vector<glm::dmat4>> jointMatrices;
};

/// Evaluates every animation of the scene at `time` (seconds) and composes node transforms.
/// `root` -1 means scene.defaultRoot. Assumes scene.validate() succeeded.
LANTERN_API Pose evaluatePose(const Scene& scene, int root, double time);

/// Gives every primitive the material variant `name` maps it to (KHR_materials_variants), or
/// its own where the variant does not list it; an empty name restores the file's materials.
/// InvalidInput, listing the variants, when the scene has no variant of that name.
LANTERN_API Result<void> selectMaterialVariant(Scene& scene, std::string_view name);

/// A span of animation time, in seconds.
struct TimeRange {
    double start = 0.0;
    double end = 0.0;
    double duration() const { return end - start; }
};

/// The key times that animation `animation` of `scene` spans, or with -1 all its animations
/// together ({0, 0} when there are none): the range a host plays. Stepping an animation is
/// choosing the time passed to Renderer::render() (or evaluatePose()); nothing in Lantern
/// keeps a clock. An index out of range gives {0, 0}.
LANTERN_API TimeRange animationRange(const Scene& scene, int animation = -1);

/// `time` wrapped into `range` for looping playback: range.start + (time - range.start) modulo
/// the duration, in [start, end); range.start for an empty range or a non-finite time.
LANTERN_API double loopTime(double time, const TimeRange& range);

/// True when node `node` draws `prim` skinned: the node has a skin and the primitive has
/// joints. Its deformed vertices are then in world space (see Skin).
LANTERN_API bool isSkinned(const Scene& scene, int node, const Primitive& prim);
/// True when node `node` draws `prim` deformed: skinned, or with morph targets.
LANTERN_API bool isDeformed(const Scene& scene, int node, const Primitive& prim);

/// A primitive's vertices as a pose deforms them, in double precision.
struct DeformedPrimitive {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  ///< unit length, or zero where the normal vanishes
};

/// The vertices node `node` draws `prim` with in `pose`: the morph targets blended with the
/// node's weights (p + sum w_t dp_t, n + sum w_t dn_t), then, when skinned, each vertex
/// transformed by the weighted sum S of its joints' matrices (normals by S's cofactor
/// matrix, sign-corrected for mirroring), normals normalised. Skinned results are in world
/// space, others in the node's space (worldFromDrawn() says which). The one CPU
/// implementation: bounds, framing and the reference use it; shaders/deform.comp is its twin.
LANTERN_API DeformedPrimitive deformPrimitive(const Scene& scene, const Pose& pose, int node,
                                              const Primitive& prim);
/// worldFromModel for node `node` drawing `prim`: identity when skinned (the vertices are
/// already in world space), else pose.worldFromNode[node].
LANTERN_API glm::dmat4 worldFromDrawn(const Scene& scene, const Pose& pose, int node,
                                      const Primitive& prim);

/// World-space bounds of everything drawn in a pose.
LANTERN_API Bounds computeBounds(const Scene& scene, const Pose& pose);

/// What a scene contains, for `lantern info` and --explain.
struct SceneSummary {
    std::size_t nodes = 0, meshes = 0, primitives = 0, triangles = 0, vertices = 0;
    std::size_t lines = 0, points = 0;  ///< line and point elements (glTF's other modes)
    std::size_t materials = 0, textures = 0, lights = 0, cameras = 0, animations = 0;
    std::size_t roots = 0;
    /// Bytes the scene's vertex attributes, indices, morph targets, texture pixels and
    /// animation keys hold in host memory (the arrays' capacities).
    std::size_t hostBytes = 0;
    Bounds bounds;  ///< at time 0, default root
};
LANTERN_API SceneSummary summarize(const Scene& scene);

/// Why scene root `root` (-1: the default) draws nothing, e.g. "the file defines no scene and
/// no node" or "scene 0 \"Empty\" has no nodes"; nothing when it draws something. A valid
/// scene that draws nothing renders the background: hosts show this reason as a warning.
LANTERN_API std::optional<std::string> nothingToDraw(const Scene& scene, int root = -1);

// --- Building blocks ------------------------------------------------------------------------

/// Angle-weighted vertex normals (each face contributes its unit normal times the angle it
/// makes at the vertex): the classic smooth "mesh shading" normals. Degenerate faces add
/// nothing; a vertex with no usable face gets the zero vector.
LANTERN_API std::vector<glm::vec3> computeSmoothNormals(const std::vector<glm::vec3>& positions,
                                                        const std::vector<std::uint32_t>& indices);

/// A UV sphere of radius r centred at the origin with analytic normals: `segments` around
/// (>= 3) and `rings` from pole to pole (>= 2).
LANTERN_API Primitive makeSphere(double radius, int segments, int rings);
/// A square in the XY plane, side `size`, normal +Z, split into n x n quads.
LANTERN_API Primitive makePlane(double size, int subdivisions = 1);
/// An axis-aligned cube of side `size` with flat faces (24 vertices).
LANTERN_API Primitive makeCube(double size);

} // namespace lantern
